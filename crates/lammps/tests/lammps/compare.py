#!/usr/bin/env python3
"""Compare thermo series: LAMMPS log(s) against the reference driver (creep-lammps-ref run).

    compare.py TOL REF LOG [LOG ...]     each LOG's `step c_ppair c_kin` against REF's
                                         `step pressure ke contacts`, relative difference <= TOL
    compare.py --step0 TOL REF LOG       only step 0's pressure
    compare.py --ke TOL REF LOG [LOG ...] only the kinetic energy (REF from `creep-lammps-ref dem`,
                                         creep-dem reports no pair virial)
REF may also be a LAMMPS log (e.g. the 1-rank run, against the 2- and 4-rank runs).

Relative difference of a quantity: |a - b| / max(|b|, 1e-12 max_run |b|) (the floor keeps a
pressure passing through zero from dividing by ~0). Exit status 1 if any comparison fails.
"""
import sys


def lammps_thermo(path):
    rows, on = {}, False
    for line in open(path):
        w = line.split()
        if w[:3] == ["Step", "c_ppair", "c_kin"]:
            on = True
            continue
        if on:
            if not w or w[0] == "Loop":
                on = False
                continue
            try:
                rows[int(w[0])] = (float(w[1]), float(w[2]))
            except ValueError:
                on = False
    return rows


def ref_thermo(path):
    """The reference driver's output, or another LAMMPS log (rank-count comparisons)."""
    if any(l.split()[:3] == ["Step", "c_ppair", "c_kin"] for l in open(path)):
        return lammps_thermo(path)
    rows = {}
    for line in open(path):
        w = line.split()
        if w and w[0].isdigit():
            rows[int(w[0])] = (float(w[1]), float(w[2]))
    return rows


def rel(a, b, floor):
    return abs(a - b) / max(abs(b), floor)


def main(argv):
    step0 = argv[1] == "--step0"
    ke_only = argv[1] == "--ke"
    if step0 or ke_only:
        argv = argv[1:]
    tol, ref = float(argv[1]), ref_thermo(argv[2])
    passed = failed = 0
    for log in argv[3:]:
        got = lammps_thermo(log)
        steps = [0] if step0 else sorted(got)
        if not steps or any(s not in ref for s in steps) or (step0 and 0 not in got):
            print(f"FAIL {log}: steps {steps[:3]}... missing in the reference or the log")
            failed += 1
            continue
        worst = [0.0, 0.0]
        for k in (0, 1):
            if (step0 and k == 1) or (ke_only and k == 0):
                continue
            floor = 1e-12 * max(abs(ref[s][k]) for s in steps)
            worst[k] = max(rel(got[s][k], ref[s][k], floor) for s in steps)
        ok = max(worst) <= tol
        print(f"{'ok  ' if ok else 'FAIL'} {log}: {len(steps)} steps (last {steps[-1]}), "
              f"max relative difference: pressure {'-' if ke_only else f'{worst[0]:.3e}'}, kinetic energy {worst[1]:.3e} (tol {tol:g})")
        passed += ok
        failed += not ok
    print(f"compare: {passed} ok, {failed} not ok")
    return 0 if failed == 0 else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
