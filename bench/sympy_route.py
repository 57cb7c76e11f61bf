#!/usr/bin/python3
"""Baseline for the benchmark table: the same job as `kinema eval`, done the way a
student would with SymPy + NumPy.

For each of three mechanisms (four-bar, offset slider-crank, Problem 4.4 six-bar)
the script

1. derives, with SymPy, the loop equations Phi(q, theta) = 0 (real and imaginary
   parts of the complex vector loops), the Jacobian Phi_q, Phi_theta, the
   acceleration right-hand side gamma (chain rule in time) and the points'
   position/velocity/acceleration, then lambdifies all of them (timed: best of a
   few runs, SymPy's cache cleared before each run);
2. sweeps the input over a full revolution: Newton-Raphson warm-started from the
   previous angle to |Phi| < 1e-12, then qd = solve(Phi_q, -Phi_theta*thetad) and
   qdd = solve(Phi_q, gamma), plus the points (timed: mean time per angle);
3. checks the results: every angle assembled, Phi_q well conditioned, the branch
   kept around the revolution, the rates against finite differences of the
   position solution, and Problem 4.4's printed seed numbers at phi = 30 deg.

The mechanisms are read from the repository's samples/*.toml with tomllib, so the
numbers are those of the files. Only the subset of kinema's file format that these
samples use is understood (crank inputs, complex-form or x/y loops, the units below).

Run:  /usr/bin/python3 bench/sympy_route.py [--json] [--angles N] [--no-points]
                                           [--modules numpy|math]
Needs Debian's python3-sympy and python3-numpy (a pyenv `python3` may lack them).
"""

import argparse
import json
import math
import re
import sys
import time
import tomllib
from pathlib import Path

import numpy as np
import sympy as sp
from sympy.core.cache import clear_cache

REPO = Path(__file__).resolve().parent.parent
SAMPLES = REPO / "samples"

MECHANISMS = {  # JSON key -> sample file
    "four_bar": "four_bar.toml",
    "slider_crank": "slider_crank.toml",
    "problem_4_4": "problem_4_4_six_bar.toml",
}

NEWTON_TOL = 1e-12       # max |Phi| in metres at an accepted position
NEWTON_MAX_IT = 50
DERIVATION_RUNS = 3      # best of; each run starts from a cleared SymPy cache
SWEEP_RUNS = 3           # best of; every run redoes the identical sweep

# Problem 4.4 seed numbers at phi = 30 deg (samples/problem_4_4_six_bar.toml header).
P44_EXPECTED = {"omega2": -1.1307, "omega3": -2.82169, "omega4": 0.58475, "alpha2": -22.33}
P44_REL_TOL = 1e-4

# ---------------------------------------------------------------------------
# Reading the sample files (units -> SI, as kinema does internally)
# ---------------------------------------------------------------------------

LENGTH_UNITS = {"m": 1.0, "mm": 1e-3, "cm": 1e-2, "in": 0.0254, "ft": 0.3048}
ANGLE_UNITS = {"rad": 1.0, "deg": math.pi / 180.0}
_QUANTITY = re.compile(r"^\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*([A-Za-z/^0-9]*)\s*$")


def quantity(text):
    """'40 mm' -> (0.04, 'length'); '3000 rpm' -> (314.159..., 'angle'); None if not a
    number with a known unit (then it is a formula of earlier parameters)."""
    m = _QUANTITY.match(str(text))
    if not m:
        return None
    value, unit = float(m.group(1)), m.group(2)
    if unit == "":
        return value, "number"
    if unit == "rpm":                       # a rate already: revolutions per minute
        return value * 2.0 * math.pi / 60.0, "angle"
    base = re.sub(r"/s(\^2)?$", "", unit)   # rates share the factor of their base unit
    if base in LENGTH_UNITS:
        return value * LENGTH_UNITS[base], "length"
    if base in ANGLE_UNITS:
        return value * ANGLE_UNITS[base], "angle"
    raise ValueError(f"unit not understood: {text!r}")


def rate_names(name, kind):
    """kinema's naming: theta3/phi3 -> omega3, alpha3; r1 -> r1_dot, r1_ddot."""
    m = re.match(r"^(theta|phi)(.*)$", name)
    if kind == "angle" and m:
        return "omega" + m.group(2), "alpha" + m.group(2)
    return name + "_dot", name + "_ddot"


def load_mechanism(path):
    """Numbers and formula strings from a sample file, everything in SI."""
    doc = tomllib.loads(Path(path).read_text())

    params = {}
    for name, text in doc["parameters"].items():
        q = quantity(text)
        if q is None:   # e.g. EF = "CE": a formula of earlier parameters
            expr = sp.sympify(str(text), locals={k: sp.Float(v) for k, v in params.items()})
            params[name] = float(expr)
        else:
            params[name] = q[0]

    inp = doc["input"]
    value, kind = quantity(inp["value"])
    if kind != "angle":
        raise ValueError(f"{path}: only crank (angle) inputs are swept over a revolution")
    default_rate, default_second = rate_names(inp["name"], kind)
    input_ = {
        "name": inp["name"],
        "value": value,
        "rate": quantity(inp["rate"])[0],
        "second_rate": quantity(inp.get("second_rate", "0 rad/s^2"))[0],
        "rate_name": inp.get("rate_name", default_rate),
        "second_rate_name": inp.get("second_rate_name", default_second),
    }

    unknowns = []
    for name, spec in doc["unknowns"].items():
        spec = spec if isinstance(spec, dict) else {"guess": spec}
        guess, kind = quantity(spec["guess"])
        r1, r2 = rate_names(name, kind)
        unknowns.append({"name": name, "guess": guess, "kind": kind,
                         "rate_name": spec.get("rate_name", r1),
                         "second_rate_name": spec.get("second_rate_name", r2)})

    return {
        "title": doc.get("title", path.name),
        "params": params,
        "input": input_,
        "unknowns": unknowns,
        "loops": doc["loops"],
        "points": doc.get("points", {}),
        "length_unit": doc.get("output", {}).get("length", "m"),
    }


# ---------------------------------------------------------------------------
# 1. Derivation with SymPy (this whole function is what is timed)
# ---------------------------------------------------------------------------

def derive(mech, with_points=True, modules="numpy"):
    """Symbols -> loop equations -> Phi_q, Phi_theta, gamma -> lambdified functions.

    No simplify(): it is what makes the student route slow in practice, but kinema's
    evaluator does not simplify either (only its printed derivation does), so leaving
    it out keeps the comparison about the same job."""
    names = [u["name"] for u in mech["unknowns"]]
    q = sp.Matrix([sp.Symbol(n, real=True) for n in names])
    qd = sp.Matrix([sp.Symbol(n + "_d", real=True) for n in names])
    qdd = sp.Matrix([sp.Symbol(n + "_dd", real=True) for n in names])
    th = sp.Symbol(mech["input"]["name"], real=True)
    thd, thdd = sp.symbols("thetad thetadd", real=True)
    par = {n: sp.Symbol(n, real=True) for n in mech["params"]}

    # Every name in the strings is a real symbol; the locals also shadow SymPy's own
    # one-letter names (E, S, N, ...) that a parameter might be called.
    ns = dict(par)
    ns.update({n: s for n, s in zip(names, q)})
    ns[th.name] = th
    ns.update({"I": sp.I, "Pi": sp.pi})

    def real_imag(text):
        z = sp.sympify(text, locals=ns)
        # exp(I*x) -> cos x + I sin x; with real symbols the split is exact.
        return sp.expand_complex(z).as_real_imag()

    rows = []
    for loop in mech["loops"].values():
        if isinstance(loop, dict):          # loop given by components
            rows += [sp.sympify(loop["x"], locals=ns), sp.sympify(loop["y"], locals=ns)]
        else:
            rows += list(real_imag(loop))
    phi = sp.Matrix(rows)
    if phi.shape[0] != len(q):
        raise ValueError("two equations per loop must match the number of unknowns")

    phi_q = phi.jacobian(q)
    phi_th = phi.diff(th)

    # Velocity constraint v = Phi_q qd + Phi_theta thetad = 0; differentiating it in
    # time (q and theta move, qd and thetad are the chain-rule factors) gives
    # Phi_q qdd = gamma.
    v = phi_q * qd + phi_th * thd
    gamma = -(v.jacobian(q) * qd + v.diff(th) * thd + phi_th * thdd)

    exprs = {"phi": phi, "phi_q": phi_q, "phi_th": phi_th, "gamma": gamma}
    if with_points and mech["points"]:
        pos = sp.Matrix([c for text in mech["points"].values() for c in real_imag(text)])
        pos_q, pos_th = pos.jacobian(q), pos.diff(th)
        vel = pos_q * qd + pos_th * thd
        acc = vel.jacobian(q) * qd + vel.diff(th) * thd + pos_q * qdd + pos_th * thdd
        exprs.update(pos=pos, vel=vel, acc=acc)

    # Numbers in last, as a student substituting the data into the derived formulas.
    values = {par[n]: v for n, v in mech["params"].items()}
    args = list(q) + [th] + list(qd) + [thd, thdd] + list(qdd)
    funcs = {}
    for key, m in exprs.items():
        m = m.subs(values)
        if modules == "numpy":
            # Flat scalar arguments; lambdify's default NumPy printer (what a tutorial
            # uses): a Matrix comes back as a 2-D array.
            funcs[key] = sp.lambdify(args, m, modules="numpy")
        else:
            # The 'math' printer cannot return a Matrix, so return nested lists and
            # make the array here; math.cos on floats is cheaper than numpy.cos.
            g = sp.lambdify(args, m.tolist(), modules="math")
            funcs[key] = lambda *a, g=g: np.array(g(*a))
    return funcs


def time_derivation(mech, with_points, modules):
    best, funcs = math.inf, None
    for _ in range(DERIVATION_RUNS):
        clear_cache()   # otherwise runs 2..n reuse run 1's cached results
        t0 = time.perf_counter()
        funcs = derive(mech, with_points, modules)
        best = min(best, time.perf_counter() - t0)
    return best, funcs


# ---------------------------------------------------------------------------
# 2. Per angle: Newton, velocity, acceleration, points
# ---------------------------------------------------------------------------

class Evaluator:
    """Calls the lambdified functions with the flat argument list they were made with;
    arguments that an expression does not use are passed as zeros."""

    def __init__(self, funcs, n):
        self.f, self.n = funcs, n
        self.zeros = [0.0] * n

    def position(self, q, th):
        """Newton-Raphson from q to max |Phi| < NEWTON_TOL; returns (q, iterations)."""
        z, f_phi, f_jac = self.zeros, self.f["phi"], self.f["phi_q"]
        for it in range(NEWTON_MAX_IT):
            r = f_phi(*q, th, *z, 0.0, 0.0, *z).ravel()
            if np.max(np.abs(r)) < NEWTON_TOL:
                return q, it
            q = q + np.linalg.solve(f_jac(*q, th, *z, 0.0, 0.0, *z), -r)
        raise RuntimeError(f"Newton did not converge at input {th} rad")

    def rates(self, q, th, thd, thdd):
        z = self.zeros
        jac = self.f["phi_q"](*q, th, *z, 0.0, 0.0, *z)
        qd = np.linalg.solve(jac, -self.f["phi_th"](*q, th, *z, 0.0, 0.0, *z).ravel() * thd)
        qdd = np.linalg.solve(jac, self.f["gamma"](*q, th, *qd, thd, thdd, *z).ravel())
        return qd, qdd

    def points(self, q, qd, qdd, th, thd, thdd):
        if "pos" not in self.f:
            return None
        a = (*q, th, *qd, thd, thdd, *qdd)
        return self.f["pos"](*a), self.f["vel"](*a), self.f["acc"](*a)


def sweep(ev, q0, th0, thd, thdd, n_angles, with_points):
    """One full revolution from th0 in n_angles equal steps, each warm-started from the
    previous solution. Returns (seconds, qs, qds, qdds, Newton iterations)."""
    step = 2.0 * math.pi / n_angles
    qs = np.empty((n_angles, len(q0)))
    qds, qdds = np.empty_like(qs), np.empty_like(qs)
    iters = 0
    q = q0
    t0 = time.perf_counter()
    for i in range(n_angles):
        th = th0 + i * step
        q, it = ev.position(q, th)
        qd, qdd = ev.rates(q, th, thd, thdd)
        if with_points:
            ev.points(q, qd, qdd, th, thd, thdd)
        qs[i], qds[i], qdds[i] = q, qd, qdd
        iters += it
    return time.perf_counter() - t0, qs, qds, qdds, iters


# ---------------------------------------------------------------------------
# 3. Checks (untimed)
# ---------------------------------------------------------------------------

def check_sweep(mech, ev, q_start, qs, qds, qdds, th0, thd, thdd):
    """Raise if the revolution is not feasible on one branch or the rates are wrong.
    Returns the largest condition number of Phi_q met on the sweep."""
    n_angles, n = qs.shape
    step = 2.0 * math.pi / n_angles
    z = ev.zeros
    conds = [np.linalg.cond(ev.f["phi_q"](*q, th0 + i * step, *z, 0.0, 0.0, *z))
             for i, q in enumerate(qs)]
    if max(conds) > 1e5:
        raise RuntimeError(f"{mech['title']}: Phi_q nearly singular on the sweep "
                           f"(cond {max(conds):.3g}): not a full-turn mechanism here")

    # Branch kept: one more step closes the revolution back onto the start, with the
    # angles advanced by whole turns only.
    q_end, _ = ev.position(qs[-1], th0 + 2.0 * math.pi)
    for u, a, b in zip(mech["unknowns"], q_start, q_end):
        d = b - a
        if u["kind"] == "angle":
            d = d - 2.0 * math.pi * round(d / (2.0 * math.pi))
        if abs(d) > 1e-9:
            raise RuntimeError(f"{mech['title']}: {u['name']} does not return to its start "
                               f"after a revolution (branch changed?)")

    # Rates against central differences of the positions along the sweep (periodic,
    # so wrap around). With thetadd = 0: qd = q' thetad, qdd = q'' thetad^2.
    if thdd == 0.0:
        turns = np.array([2 * math.pi if u["kind"] == "angle" else 0.0 for u in mech["unknowns"]])
        nxt = np.roll(qs, -1, axis=0)
        prv = np.roll(qs, 1, axis=0)
        # the rolled-around rows are one revolution apart: undo the turns the angles made
        nxt[-1] += np.round((qs[-1] - nxt[-1]) / np.where(turns > 0, turns, 1)) * turns
        prv[0] += np.round((qs[0] - prv[0]) / np.where(turns > 0, turns, 1)) * turns
        fd_qd = (nxt - prv) / (2 * step) * thd
        fd_qdd = (nxt - 2 * qs + prv) / step**2 * thd**2
        for label, exact, fd in (("velocity", qds, fd_qd), ("acceleration", qdds, fd_qdd)):
            err = np.max(np.abs(exact - fd), axis=0) / np.maximum(np.max(np.abs(exact), axis=0), 1e-300)
            if np.max(err) > 1e-3:
                raise RuntimeError(f"{mech['title']}: {label} disagrees with finite "
                                   f"differences (relative {np.max(err):.3g})")
    return max(conds)


def at_sample_value(mech, ev):
    """Solve at the file's own input value from the file's guesses (this picks the
    branch the sweep then follows)."""
    inp = mech["input"]
    q, _ = ev.position(np.array([u["guess"] for u in mech["unknowns"]]), inp["value"])
    qd, qdd = ev.rates(q, inp["value"], inp["rate"], inp["second_rate"])
    return q, qd, qdd


def report_lines(mech, q, qd, qdd):
    inp = mech["input"]
    unit = mech["length_unit"]
    scale = 1.0 / LENGTH_UNITS[unit]
    lines = [f"  {inp['name']} = {math.degrees(inp['value']):g} deg   "
             f"{inp['rate_name']} = {inp['rate']:g} rad/s   "
             f"{inp['second_rate_name']} = {inp['second_rate']:g} rad/s^2"]
    for u, x, xd, xdd in zip(mech["unknowns"], q, qd, qdd):
        if u["kind"] == "angle":
            deg = (math.degrees(x) + 180.0) % 360.0 - 180.0
            lines.append(f"    {u['name']:<7} {deg:>11.6g} deg  {u['rate_name']} = {xd:.6g} rad/s"
                         f"  {u['second_rate_name']} = {xdd:.6g} rad/s^2")
        else:
            lines.append(f"    {u['name']:<7} {x * scale:>11.6g} {unit:<3}  {u['rate_name']} = "
                         f"{xd * scale:.6g} {unit}/s  {u['second_rate_name']} = {xdd * scale:.6g} {unit}/s^2")
    return lines


def check_problem_4_4(mech, qd, qdd):
    got = {}
    for u, xd, xdd in zip(mech["unknowns"], qd, qdd):
        got[u["rate_name"]], got[u["second_rate_name"]] = xd, xdd
    bad = [f"{k} = {got[k]:.6g}, expected {v}" for k, v in P44_EXPECTED.items()
           if abs(got[k] - v) > P44_REL_TOL * abs(v)]
    return bad


# ---------------------------------------------------------------------------

def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--json", action="store_true", help="print one JSON object on stdout")
    ap.add_argument("--angles", type=int, default=3600,
                    help="angles per revolution in the timed sweep (default 3600)")
    ap.add_argument("--no-points", action="store_true",
                    help="leave the points' motion out of derivation and sweep")
    ap.add_argument("--modules", choices=("numpy", "math"), default="numpy",
                    help="lambdify printer: numpy (lambdify's default when NumPy is "
                         "installed) or math (scalar math.*, nested lists)")
    args = ap.parse_args()
    with_points = not args.no_points
    # In JSON mode stdout carries only the JSON; the readable notes go to stderr.
    out = sys.stderr if args.json else sys.stdout

    results, failed = {}, False
    print(f"SymPy {sp.__version__}, NumPy {np.__version__}, Python {sys.version.split()[0]}; "
          f"derivation best of {DERIVATION_RUNS} (cache cleared), sweep of {args.angles} angles "
          f"per revolution, best of {SWEEP_RUNS}; lambdify modules='{args.modules}'; "
          f"points {'included' if with_points else 'left out'}",
          file=out)
    for key, fname in MECHANISMS.items():
        mech = load_mechanism(SAMPLES / fname)
        inp = mech["input"]
        deriv_s, funcs = time_derivation(mech, with_points, args.modules)
        ev = Evaluator(funcs, len(mech["unknowns"]))

        q0, qd0, qdd0 = at_sample_value(mech, ev)
        print(f"\n{mech['title']}  ({fname})", file=out)
        for line in report_lines(mech, q0, qd0, qdd0):
            print(line, file=out)
        if key == "problem_4_4":
            bad = check_problem_4_4(mech, qd0, qdd0)
            print("  seed numbers: " + ("MISMATCH: " + "; ".join(bad) if bad else
                  "omega2, omega3, omega4, alpha2 match to 1e-4 relative"), file=out)
            failed |= bool(bad)

        best, per_run = math.inf, None
        for _ in range(SWEEP_RUNS):
            secs, qs, qds, qdds, iters = sweep(ev, q0, inp["value"], inp["rate"],
                                               inp["second_rate"], args.angles, with_points)
            if secs < best:
                best, per_run = secs, (qs, qds, qdds, iters)
        qs, qds, qdds, iters = per_run
        try:
            cond = check_sweep(mech, ev, q0, qs, qds, qdds, inp["value"], inp["rate"],
                               inp["second_rate"])
            print(f"  full revolution: all {args.angles} angles assembled, branch kept, "
                  f"max cond(Phi_q) = {cond:.3g}, rates agree with finite differences; "
                  f"{iters / args.angles:.2f} Newton steps per angle", file=out)
        except RuntimeError as e:
            print(f"  FAILED: {e}", file=out)
            failed = True

        results[key] = {"derivation_ms": round(deriv_s * 1e3, 3),
                        "per_angle_ns": round(best / args.angles * 1e9)}

    if args.json:
        print(json.dumps(results))
    else:
        print(f"\n{'mechanism':<14} {'derivation [ms]':>16} {'per angle [ns]':>15}")
        for key, r in results.items():
            print(f"{key:<14} {r['derivation_ms']:>16.1f} {r['per_angle_ns']:>15,d}")
        print("derivation: symbols to lambdified residual, Phi_q, Phi_theta, gamma"
              + (", points" if with_points else "") + "; per angle: Newton (tol 1e-12) + "
              "velocity + acceleration" + (" + points" if with_points else ""))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
