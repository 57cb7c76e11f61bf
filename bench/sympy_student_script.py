#!/usr/bin/python3
"""The four-bar of samples/four_bar.toml over 0:360:0.01 deg (36,001 values) to CSV,
written the way a student would with SymPy + NumPy: derive the loop equations and
their time derivatives symbolically, lambdify, Newton-Raphson per angle (warm start
from the previous one), solve for the rates and second rates, print a row per angle
with the columns of `kinema eval --format csv` at 12 significant digits.

The benchmark (bench/kinema_bench.cpp) runs it as a whole process against
`kinema eval samples/four_bar.toml --sweep 0:360:0.01 --format csv`, in the same run.

usage: /usr/bin/python3 bench/sympy_student_script.py OUT.csv
"""
import sys

import numpy as np
import sympy as sp

# The sample's data (mm, deg, rad/s).
a, b, c, d, p, delta = 40.0, 120.0, 80.0, 100.0, 60.0, np.radians(30.0)
omega2, alpha2 = 10.0, 0.0

t = sp.symbols("t", real=True)
th2, th3, th4 = (sp.Function(n, real=True)(t) for n in ("theta2", "theta3", "theta4"))
q = sp.Matrix([th3, th4])
loop = a * sp.exp(sp.I * th2) + b * sp.exp(sp.I * th3) - c * sp.exp(sp.I * th4) - d
phi = sp.Matrix([sp.re(sp.expand_complex(loop)), sp.im(sp.expand_complex(loop))])
points = {
    "A": a * sp.exp(sp.I * th2),
    "B": d + c * sp.exp(sp.I * th4),
    "P": a * sp.exp(sp.I * th2) + p * sp.exp(sp.I * (th3 + delta)),
}

# Plain symbols for lambdify: angles, rates, second rates.
T2, T3, T4, W2, W3, W4, A2, A3, A4 = sp.symbols("T2 T3 T4 W2 W3 W4 A2 A3 A4")
def plain(expr):
    expr = expr.subs({sp.Derivative(th2, (t, 2)): A2, sp.Derivative(th3, (t, 2)): A3, sp.Derivative(th4, (t, 2)): A4})
    expr = expr.subs({sp.Derivative(th2, t): W2, sp.Derivative(th3, t): W3, sp.Derivative(th4, t): W4})
    return expr.subs({th2: T2, th3: T3, th4: T4})

jacobian = plain(phi.jacobian(q))
phi_t = plain(phi.diff(t))
velocity_rhs = -phi_t.subs({W3: 0, W4: 0})                       # Phi_q qd = -Phi_theta omega2
accel_rhs = -plain(phi.diff(t, 2)).subs({A3: 0, A4: 0})           # Phi_q qdd = gamma
args = (T2, T3, T4, W2, W3, W4, A2)
f_phi = sp.lambdify(args, plain(phi), "numpy")
f_jac = sp.lambdify(args, jacobian, "numpy")
f_vel = sp.lambdify(args, velocity_rhs, "numpy")
f_acc = sp.lambdify(args, accel_rhs, "numpy")
point_functions = []
for name, z in points.items():
    x, y = sp.re(sp.expand_complex(z)), sp.im(sp.expand_complex(z))
    exprs = [x, y, x.diff(t), y.diff(t), x.diff(t, 2), y.diff(t, 2)]
    point_functions.append(sp.lambdify(args + (A3, A4), [plain(e) for e in exprs], "numpy"))

def fmt(v):
    return "%.12g" % v

header = ["theta2 [deg]", "omega2 [rad/s]", "alpha2 [rad/s^2]", "status"]
for n, w, al in (("theta3", "omega3", "alpha3"), ("theta4", "omega4", "alpha4")):
    header += [n + " [deg]", w + " [rad/s]", al + " [rad/s^2]"]
for name in points:
    header += [f"{name}_{c} [mm]" for c in ("x", "y")] + [f"{name}_{c} [mm/s]" for c in ("vx", "vy", "speed")]
    header += [f"{name}_{c} [mm/s^2]" for c in ("ax", "ay", "acceleration")]
out = open(sys.argv[1], "w")
out.write(",".join(header) + ",note\n")

x = np.radians([20.0, 80.0])
for k in range(36001):
    deg = 0.01 * k
    t2 = np.radians(deg)
    for _ in range(50):  # Newton-Raphson
        r = np.array(f_phi(t2, x[0], x[1], omega2, 0, 0, alpha2), dtype=float).ravel()
        if np.max(np.abs(r)) < 1e-9:
            break
        x = x - np.linalg.solve(np.array(f_jac(t2, x[0], x[1], omega2, 0, 0, alpha2), dtype=float), r)
    J = np.array(f_jac(t2, x[0], x[1], omega2, 0, 0, alpha2), dtype=float)
    qd = np.linalg.solve(J, np.array(f_vel(t2, x[0], x[1], omega2, 0, 0, alpha2), dtype=float).ravel())
    qdd = np.linalg.solve(J, np.array(f_acc(t2, x[0], x[1], omega2, qd[0], qd[1], alpha2), dtype=float).ravel())
    wrap = lambda angle: (np.degrees(angle) + 180.0) % 360.0 - 180.0
    row = [fmt(deg), fmt(omega2), fmt(alpha2), "ok"]
    for i in range(2):
        row += [fmt(wrap(x[i])), fmt(qd[i]), fmt(qdd[i])]
    for f in point_functions:
        px, py, vx, vy, ax, ay = (float(v) for v in f(t2, x[0], x[1], omega2, qd[0], qd[1], alpha2, qdd[0], qdd[1]))
        row += [fmt(px), fmt(py), fmt(vx), fmt(vy), fmt(np.hypot(vx, vy)), fmt(ax), fmt(ay), fmt(np.hypot(ax, ay))]
    out.write(",".join(row) + ",\n")
out.close()
