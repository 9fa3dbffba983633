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
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from curve_difference import differences, load_curve  # noqa: E402


def main():
    if len(sys.argv) not in (3, 4):
        sys.exit(__doc__)
    column = sys.argv[3] if len(sys.argv) == 4 else "axial_stress_platens_Pa"
    ref, run = load_curve(sys.argv[1], column), load_curve(sys.argv[2], column)
    d = differences(ref, run, scales_over_shared_rows=True)
    peak, run_peak = d["peak"], d["run_peak"]
    print(f"rows compared: {d['rows']} (to {100 * ref[d['rows'] - 1][0]:.2f} % axial strain)")
    print(f"peak: reference {peak[1] / 1e3:.2f} kPa at {100 * peak[0]:.2f} %, "
          f"run {run_peak[1] / 1e3:.2f} kPa at {100 * run_peak[0]:.2f} % "
          f"({100 * (run_peak[1] / peak[1] - 1):+.2f} %)")
    print(f"to the reference's peak: largest Δσ_a / peak {100 * d['to_peak_stress']:.2f} %, "
          f"Δε_v / max |ε_v| {100 * d['to_peak_volumetric']:.2f} %")
    print(f"all shared rows: largest Δσ_a / peak {100 * d['all_stress']:.2f} %, "
          f"Δε_v / max |ε_v| {100 * d['all_volumetric']:.2f} %")


main()
