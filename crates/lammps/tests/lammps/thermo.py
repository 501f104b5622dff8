#!/usr/bin/env python3
"""Checks a condition on a LAMMPS log's thermo rows.

    thermo.py LOG EXPR     EXPR: a Python expression over `rows` (a list of dicts, one per thermo
                           line of every run in LOG, keyed by the column names of its header,
                           e.g. rows[-1]["Atoms"], r["c_cp[2]"]) and `finite(x)`; exit status 0
                           if it is true, 1 if false or if there are no rows.
"""
import math
import sys


def thermo_rows(path):
    rows, names = [], None
    for line in open(path):
        w = line.split()
        if w and w[0] == "Step":
            names = w
            continue
        if names is None or (w and w[0] == "WARNING:"):
            continue
        if not w or w[0] == "Loop" or len(w) != len(names):
            names = None
            continue
        try:
            rows.append({k: float(v) for k, v in zip(names, w)})
        except ValueError:
            names = None
    return rows


def main(argv):
    rows = thermo_rows(argv[1])
    ok = bool(rows) and bool(eval(argv[2], {"rows": rows, "finite": math.isfinite}))
    last = rows[-1] if rows else {}
    print(f"{'ok  ' if ok else 'FAIL'} {argv[1]}: {len(rows)} thermo rows, last {last}: {argv[2]}")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
