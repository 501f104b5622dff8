#!/usr/bin/env python3
"""Compares `creep triaxial` runs with a reference run: peak friction
angle and dilatancy angle (within 0.5 deg), wall and contact stress (within 1 %), from the
runs' CSVs, computed as creep-scenes' ShearSummary computes them.

    compare.py REF_DIR RUN_DIR [RUN_DIR ...]
"""
import csv
import math
import sys


def rows(path):
    with open(path) as f:
        return [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]


def summary(rs):
    peak = max(rs, key=lambda r: r["q_over_p"])
    s1, s3 = peak["sigma_axial"], peak["sigma_lateral"]
    phi = math.degrees(math.asin((s1 - s3) / (s1 + s3)))
    d_max = -math.inf
    for i, a in enumerate(rs):
        b = next((b for b in rs[i:] if b["axial_strain"] >= a["axial_strain"] + 0.01), None)
        if b is not None:
            d = -(b["volumetric_strain"] - a["volumetric_strain"]) / (
                b["axial_strain"] - a["axial_strain"])
            d_max = max(d_max, d)
    psi = math.degrees(math.asin(d_max / (2 + d_max)))
    return dict(phi=phi, psi=psi, peak=peak, last=rs[-1])


def interp(rs, key, eps):
    for a, b in zip(rs, rs[1:]):
        if a["axial_strain"] <= eps <= b["axial_strain"]:
            t = (eps - a["axial_strain"]) / (b["axial_strain"] - a["axial_strain"])
            return a[key] + t * (b[key] - a[key])
    return None


def curve_gap(ref, run, key, lo=0.01):
    """Largest relative gap of `key` between the curves (interpolated at the run's strains)
    after `lo` axial strain."""
    gap = 0.0
    for r in run:
        if r["axial_strain"] < lo:
            continue
        v = interp(ref, key, r["axial_strain"])
        if v is not None:
            gap = max(gap, abs(r[key] / v - 1.0))
    return gap


def main():
    ref_dir, runs = sys.argv[1], sys.argv[2:]
    print("| run | law | peak angle [deg] (diff) | dilatancy angle [deg] (diff) | "
          "axial stress at peak | lateral stress at peak | contact p at peak | "
          "wall p at 20 % | largest gap of p / q along the curve (>1 %) |")
    print("|---|---|---|---|---|---|---|---|---|")
    for run in [ref_dir] + runs:
        for law in ["coulomb", "creep"]:
            ref = rows(f"{ref_dir}/triaxial_{law}.csv")
            rr = rows(f"{run}/triaxial_{law}.csv")
            a, b = summary(ref), summary(rr)
            rel = lambda k, which: b[which][k] / a[which][k] - 1.0
            print(f"| {run.rstrip('/').split('/')[-1]} | {law} "
                  f"| {b['phi']:.2f} ({b['phi'] - a['phi']:+.2f}) "
                  f"| {b['psi']:.2f} ({b['psi'] - a['psi']:+.2f}) "
                  f"| {100 * rel('sigma_axial', 'peak'):+.2f} % "
                  f"| {100 * rel('sigma_lateral', 'peak'):+.2f} % "
                  f"| {100 * rel('p_contacts', 'peak'):+.2f} % "
                  f"| {100 * rel('p', 'last'):+.2f} % "
                  f"| {100 * curve_gap(ref, rr, 'p'):.2f} % / {100 * curve_gap(ref, rr, 'q'):.2f} % |")


if __name__ == "__main__":
    main()
