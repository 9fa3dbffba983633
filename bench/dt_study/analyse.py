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
import csv
import json
import os
import sys


def load(d):
    s = json.load(open(os.path.join(d, "summary.json"))) if os.path.exists(os.path.join(d, "summary.json")) else None
    name = "curve.csv" if os.path.exists(os.path.join(d, "curve.csv")) else "curve.csv.partial"
    rows = list(csv.DictReader(open(os.path.join(d, name))))
    curve = [(float(r["axial_strain"]), float(r["axial_stress_walls_Pa"]), float(r["volumetric_strain"])) for r in rows]
    return s, curve


def peak(curve):
    return max(curve, key=lambda r: r[1])


def main():
    finest = sys.argv[1]
    s0, c0 = load(finest)
    p0 = peak(c0)
    ev_scale = max(abs(r[2]) for r in c0)
    # (no '|' inside a cell: it would split the Markdown table)
    print("| run | dt (s) | dt / t_c | largest I | steps | peak (kPa) | vs finest | strain at peak "
          "| to the peak: Δσ_a / peak | to the peak: Δε_v / max ε_v | whole curve: Δσ_a / peak "
          "| whole curve: Δε_v / max ε_v | rows |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for d in sys.argv[1:]:
        s, c = load(d)
        p = peak(c)
        n = min(len(c), len(c0))
        ds = max(abs(c[k][1] - c0[k][1]) for k in range(n)) / p0[1]
        dv = max(abs(c[k][2] - c0[k][2]) for k in range(n)) / ev_scale
        m = [k for k in range(n) if c0[k][0] <= p0[0]]
        ds_pre = max(abs(c[k][1] - c0[k][1]) for k in m) / p0[1]
        dv_pre = max(abs(c[k][2] - c0[k][2]) for k in m) / ev_scale
        dt = s["time_step_s"] if s else float("nan")
        tc = s["collision_duration_s"] if s else float("nan")
        print(f"| {os.path.basename(d.rstrip('/'))} | {dt:.3g} | {dt / tc:.3f} | {s['max_inertial_number']:.2g} | {s['steps'] if s else '?'} "
              f"| {p[1] / 1e3:.1f} | {100 * (p[1] / p0[1] - 1):+.2f} % | {100 * p[0]:.2f} % | {100 * ds_pre:.2f} % | {100 * dv_pre:.2f} % "
              f"| {100 * ds:.2f} % | {100 * dv:.2f} % | {n} |")


main()
