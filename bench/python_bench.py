"""The Python module's costs against the C++ library (issue 36's targets), written in
docs/benchmarks.md:

- one value through Model.at (a float in SI), against kinema_bench's facade_solve/ (the
  library's MechanismModel::solve) on the same samples: the module may add at most 2 us;
- Problem 4.4 over 10^6 values of a turn through Model.sweep into NumPy, against
  kinema_bench's kinema_sweep_1e6/ (the C++ sweep, results kept in memory).

    PYTHONPATH=build/python /usr/bin/python3 bench/python_bench.py samples
"""
import math
import pathlib
import sys
import time
import timeit

import kinema

samples = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else "samples")

for name in ("four_bar.toml", "slider_crank.toml", "problem_4_4_six_bar.toml"):
    model = kinema.load(str(samples / name))
    values = [0.5 + 1e-3 * k for k in range(5000)]  # a new value each time, near the last

    def run():
        for value in values:
            model.at(value)

    best = min(timeit.repeat(run, number=1, repeat=5))
    print(f"Model.at/{name}: {best / len(values) * 1e6:.2f} us a value")

model = kinema.load(str(samples / "problem_4_4_six_bar.toml"))
step = 2 * math.pi / 1_000_000
best = math.inf
for _ in range(3):
    started = time.perf_counter()
    table = model.sweep(0.0, 2 * math.pi - step / 2, step)
    best = min(best, time.perf_counter() - started)
print(f"Model.sweep/problem_4_4_six_bar.toml 10^6 values: {best * 1e3:.0f} ms ({len(table)} rows, {table.nbytes / 1e6:.0f} MB)")
