#!/usr/bin/python3
"""Time-step convergence table of a set of triaxial runs on one specimen.

usage: analyse.py FINEST_DIR RUN_DIR [RUN_DIR ...]
Each RUN_DIR holds a finished (or, for the last rows, partial) triaxial run: summary.json and
curve.csv (or curve.csv.partial). Against FINEST_DIR it reports, per run: the step (s and as a
fraction of t_c), the step count, the peak axial stress and its difference, the strain at the
peak, and the largest differences of the axial stress and of the volumetric strain over the
curve rows both runs have (Δσ_a relative to the finest run's peak, Δε_v to the finest run's
largest absolute ε_v), up to the finest run's peak and over the whole curve.
Prints a Markdown table."""
import json
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from curve_difference import differences, load_curve, peak_row  # noqa: E402


def load(d):
    summary_path = os.path.join(d, "summary.json")
    s = json.load(open(summary_path)) if os.path.exists(summary_path) else None
    name = "curve.csv" if os.path.exists(os.path.join(d, "curve.csv")) else "curve.csv.partial"
    return s, load_curve(os.path.join(d, name), "axial_stress_walls_Pa")


def main():
    finest = sys.argv[1]
    s0, c0 = load(finest)
    p0 = peak_row(c0)
    # (no '|' inside a cell: it would split the Markdown table)
    print("| run | dt (s) | dt / t_c | largest I | steps | peak (kPa) | vs finest | strain at peak "
          "| to the peak: Δσ_a / peak | to the peak: Δε_v / max ε_v | whole curve: Δσ_a / peak "
          "| whole curve: Δε_v / max ε_v | rows |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for d in sys.argv[1:]:
        s, c = load(d)
        p = peak_row(c)
        # (the finest run's peak and largest |ε_v| over its whole curve)
        diff = differences(c0, c, scales_over_shared_rows=False)
        dt = s["time_step_s"] if s else float("nan")
        tc = s["collision_duration_s"] if s else float("nan")
        print(f"| {os.path.basename(d.rstrip('/'))} | {dt:.3g} | {dt / tc:.3f} | {s['max_inertial_number']:.2g} | {s['steps'] if s else '?'} "
              f"| {p[1] / 1e3:.1f} | {100 * (p[1] / p0[1] - 1):+.2f} % | {100 * p[0]:.2f} % "
              f"| {100 * diff['to_peak_stress']:.2f} % | {100 * diff['to_peak_volumetric']:.2f} % "
              f"| {100 * diff['all_stress']:.2f} % | {100 * diff['all_volumetric']:.2f} % | {diff['rows']} |")


main()
