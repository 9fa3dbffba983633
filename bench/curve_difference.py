"""How far one element test's curve.csv lies from another's, row by row (shared by
bench/hold_study/compare.py and bench/dt_study/analyse.py).

A curve is a list of (axial_strain, axial_stress_Pa, volumetric_strain) rows, every
output_strain_interval. The differences are the largest |Δσ_a| relative to the reference's peak
axial stress and the largest |Δε_v| relative to the reference's largest |ε_v|, over the rows both
curves have: up to the reference's peak and over all of them."""
import csv
import sys


def load_curve(path, stress_column):
    """The rows of a curve.csv (or curve.csv.partial) as (ε_a, σ_a, ε_v); exits naming the file
    where it has no rows or no such column."""
    with open(path) as f:
        rows = list(csv.DictReader(f))
    if not rows or stress_column not in rows[0]:
        sys.exit(f"{path}: no rows, or no column {stress_column}")
    return [(float(r["axial_strain"]), float(r[stress_column]), float(r["volumetric_strain"]))
            for r in rows]


def peak_row(curve):
    """The row of the largest axial stress."""
    return max(curve, key=lambda r: r[1])


def differences(reference, run, scales_over_shared_rows):
    """The differences of `run` from `reference` over the rows both have. The reference's peak
    and largest |ε_v|, which scale them and divide the rows before the peak from the rest, are
    taken over the shared rows (scales_over_shared_rows) or over the reference's whole curve.
    Returns a dict: rows (shared), peak (the reference's row), run_peak (the run's row, over the
    shared rows), to_peak_stress, to_peak_volumetric, all_stress, all_volumetric (fractions)."""
    n = min(len(reference), len(run))
    for k in range(n):
        if abs(reference[k][0] - run[k][0]) > 1e-6:
            sys.exit(f"row {k + 2}: axial strains differ ({reference[k][0]} and {run[k][0]})")
    scale_rows = reference[:n] if scales_over_shared_rows else reference
    peak = peak_row(scale_rows)
    ev_scale = max(abs(r[2]) for r in scale_rows)
    shared = list(zip(reference[:n], run[:n]))
    to_peak = [(a, b) for a, b in shared if a[0] <= peak[0]]

    def largest(pairs, i, scale):
        return max(abs(a[i] - b[i]) for a, b in pairs) / scale

    return {
        "rows": n,
        "peak": peak,
        "run_peak": peak_row(run[:n]),
        "to_peak_stress": largest(to_peak, 1, peak[1]),
        "to_peak_volumetric": largest(to_peak, 2, ev_scale),
        "all_stress": largest(shared, 1, peak[1]),
        "all_volumetric": largest(shared, 2, ev_scale),
    }
