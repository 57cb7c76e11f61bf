"""Checks that kinema's .npy output holds what its CSV says (run by tests/cli).

usage: npy_matches_csv.py RESULTS.npy RESULTS.csv
Every CSV column "name [unit]" is the field "name": equal to the CSV's 12 significant
digits, NaN where the CSV cell is empty; status and note as codes. Exit 0 when all agree.
"""
import csv
import math
import sys

import numpy as np

STATUS = {"ok": 0, "singular": 1, "unassembled": 2}


def main(npy_path, csv_path):
    array = np.load(npy_path)
    with open(csv_path, newline="") as f:
        rows = list(csv.reader(f))
    header, rows = rows[0], rows[1:]
    if len(rows) != array.shape[0]:
        return f"{len(rows)} CSV rows, {array.shape[0]} records"
    for column, title in enumerate(header):
        name = title.split(" [")[0]
        for r, row in enumerate(rows):
            cell, value = row[column], array[r][name if name != "note" else "resumed_after_gap"]
            if name == "status":
                ok = STATUS[cell] == value
            elif name == "note":
                ok = (cell == "resumed_after_gap") == bool(value)
            elif cell == "":
                ok = math.isnan(value)
            else:
                ok = math.isclose(float(cell), value, rel_tol=2e-11, abs_tol=1e-9 * max(1.0, abs(float(cell))))
            if not ok:
                return f"row {r}, column {title}: CSV {cell!r}, npy {value!r}"
    print(f"{len(rows)} rows, {len(header)} columns agree")
    return None


if __name__ == "__main__":
    problem = main(sys.argv[1], sys.argv[2])
    if problem:
        print(problem, file=sys.stderr)
        sys.exit(1)
