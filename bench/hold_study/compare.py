#!/usr/bin/python3
"""How far a run on a specimen held to a looser equilibrium lies from the reference run.

usage: compare.py REFERENCE_CURVE RUN_CURVE [STRESS_COLUMN]
Both are curve.csv files of the same element test (the same config but the hold's criterion,
test.preparation_unbalanced_tolerance). Over the rows both files have (same axial strains, every
output_strain_interval) it prints the peak axial stress of each (over those rows) and its
difference, the strain at each peak, and the largest differences of the axial stress (relative to
the reference's peak) and of the volumetric strain (relative to the reference's largest |ε_v|),
up to the reference's peak and over all shared rows. STRESS_COLUMN defaults to the plane strain
test's axial_stress_platens_Pa (the triaxial's is axial_stress_walls_Pa)."""
import csv
import sys


def load(path, column):
    rows = list(csv.DictReader(open(path)))
    if not rows or column not in rows[0]:
        sys.exit(f"{path}: no rows, or no column {column}")
    return [(float(r["axial_strain"]), float(r[column]), float(r["volumetric_strain"])) for r in rows]


def main():
    if len(sys.argv) not in (3, 4):
        sys.exit(__doc__)
    column = sys.argv[3] if len(sys.argv) == 4 else "axial_stress_platens_Pa"
    ref, run = load(sys.argv[1], column), load(sys.argv[2], column)
    n = min(len(ref), len(run))
    for k in range(n):
        if abs(ref[k][0] - run[k][0]) > 1e-6:
            sys.exit(f"row {k + 2}: axial strains differ ({ref[k][0]} and {run[k][0]})")
    ref, run = ref[:n], run[:n]
    k_peak = max(range(n), key=lambda k: ref[k][1])
    run_peak = max(run, key=lambda r: r[1])
    peak, ev_scale = ref[k_peak][1], max(abs(r[2]) for r in ref)

    def largest(rows, i, scale):
        return max(abs(a[i] - b[i]) for a, b in rows) / scale

    pre = list(zip(ref[:k_peak + 1], run[:k_peak + 1]))
    both = list(zip(ref, run))
    print(f"rows compared: {n} (to {100 * ref[-1][0]:.2f} % axial strain)")
    print(f"peak: reference {peak / 1e3:.2f} kPa at {100 * ref[k_peak][0]:.2f} %, "
          f"run {run_peak[1] / 1e3:.2f} kPa at {100 * run_peak[0]:.2f} % "
          f"({100 * (run_peak[1] / peak - 1):+.2f} %)")
    print(f"to the reference's peak: largest Δσ_a / peak {100 * largest(pre, 1, peak):.2f} %, "
          f"Δε_v / max |ε_v| {100 * largest(pre, 2, ev_scale):.2f} %")
    print(f"all shared rows: largest Δσ_a / peak {100 * largest(both, 1, peak):.2f} %, "
          f"Δε_v / max |ε_v| {100 * largest(both, 2, ev_scale):.2f} %")


main()
