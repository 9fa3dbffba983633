#!/usr/bin/python3
"""Seed-study table of reference triaxial runs (bench/seed_study/run.sh).

usage: analyse.py RUN_DIR [RUN_DIR ...]
RUN_DIR names are eE_seedN (E: the compaction restitution, N: the seed); each holds a finished
run's summary.json and curve.csv. Prints, as Markdown, one row per run (wall times, the
specimen's solid fraction and coordination number, the peak axial stress and the strain at it,
their differences to the laboratory, the strains between which the axial stress stays within
1 % of the peak, the stress at 2 % axial strain, the volumetric strain at
the end) and per restitution the mean, the sample standard deviation and the range of each."""
import csv
import json
import os
import re
import statistics
import sys

COLUMNS = [  # (heading, key, format)
    ("preparation (s)", "prep_s", "{:.0f}"),
    ("shearing (s)", "shear_s", "{:.0f}"),
    ("solid fraction", "phi", "{:.4f}"),
    ("Z", "z", "{:.2f}"),
    ("peak (kPa)", "peak_kpa", "{:.1f}"),
    ("strain at peak (%)", "strain_at_peak", "{:.2f}"),
    ("peak vs lab (%)", "peak_vs_lab", "{:+.1f}"),
    ("strain at peak vs lab (%)", "strain_vs_lab", "{:+.1f}"),
    ("within 1 % of the peak: from (%)", "plateau_from", "{:.1f}"),
    ("to (%)", "plateau_to", "{:.1f}"),
    ("σ_a at 2 % (kPa)", "stress_2pc", "{:.1f}"),
    ("ε_v at 8 % (%)", "ev_end", "{:+.2f}"),
]


def load(d):
    s = json.load(open(os.path.join(d, "summary.json")))
    rows = list(csv.DictReader(open(os.path.join(d, "curve.csv"))))
    curve = [(float(r["axial_strain"]), float(r["axial_stress_walls_Pa"]),
              float(r["volumetric_strain"])) for r in rows]
    at_2pc = min(curve, key=lambda r: abs(r[0] - 0.02))
    # the strains over which the axial stress stays within 1 % of the peak: how flat the peak is
    top = max(r[1] for r in curve)
    near = [r[0] for r in curve if r[1] >= 0.99 * top]
    ref = s["reference"]
    return {
        "prep_s": s["preparation_wall_time_s"],
        "shear_s": s["shearing_wall_time_s"],
        "phi": s["specimen"]["solid_fraction"],
        "z": s["specimen"]["coordination_number"],
        "peak_kpa": s["peak_axial_stress_Pa"] / 1e3,
        "strain_at_peak": 100 * s["axial_strain_at_peak"],
        "peak_vs_lab": 100 * ref["difference_to_laboratory"],
        "strain_vs_lab": 100 * ref["strain_at_peak_difference_to_laboratory"],
        "plateau_from": 100 * min(near),
        "plateau_to": 100 * max(near),
        "stress_2pc": at_2pc[1] / 1e3,
        "ev_end": 100 * curve[-1][2],
    }


def main():
    runs = {}
    for d in sys.argv[1:]:
        name = os.path.basename(d.rstrip("/"))
        m = re.fullmatch(r"e([0-9.]+)_seed([0-9]+)", name)
        if not m or not os.path.exists(os.path.join(d, "summary.json")):
            continue
        runs.setdefault(m.group(1), []).append((int(m.group(2)), load(d)))
    print("| restitution | seed | " + " | ".join(c[0] for c in COLUMNS) + " |")
    print("|---|---|" + "---|" * len(COLUMNS))
    for e, rs in sorted(runs.items()):
        for seed, r in sorted(rs):
            print(f"| {e} | {seed} | " + " | ".join(f.format(r[k]) for _, k, f in COLUMNS) + " |")
    print()
    print("| restitution | runs | " + " | ".join(c[0] for c in COLUMNS) + " |")
    print("|---|---|" + "---|" * len(COLUMNS))
    for e, rs in sorted(runs.items()):
        cells = []
        for _, k, f in COLUMNS:
            v = [r[k] for _, r in rs]
            sd = statistics.stdev(v) if len(v) > 1 else float("nan")
            cells.append(f"{f.format(statistics.mean(v))} ± {f.format(sd).lstrip('+')} "
                         f"({f.format(min(v))} to {f.format(max(v))})")
        print(f"| {e} | {len(rs)} | " + " | ".join(cells) + " |")


main()
