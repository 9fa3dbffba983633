#!/usr/bin/env python3
"""The specimen-state sensitivity study of the reference triaxial test.

The reference triaxial config (examples/triaxial/reference.toml: 11,636 beads, 150 kPa, I <= 1e-3)
is run on specimens prepared to different states, everything else unchanged:

  * the bead-bead friction while compacting (`compaction_friction`) steers the density: below the
    glass's measured 0.16 the packing gets denser, above it looser; the measured friction is
    switched on once the packing has settled;
  * the walls' friction during the preparation on or off (`wall_friction_while_preparing`): on,
    shear is locked into the wall contacts and the test starts anisotropic.

usage: study.py GRAINLAB OUT_DIR [--max-axial-strain 0.12] [--only NAME,...] [--jobs 2]

Every state is an ordinary run in OUT_DIR/NAME: a finished one (summary.json) is kept, an
interrupted one (checkpoint.bin or preparation.bin) is resumed, so the study can be stopped and
started again. At the end: OUT_DIR/study.csv, OUT_DIR/study.md (the table) and OUT_DIR/study.png
(peak axial stress and strain at peak against the solid fraction, the laboratory point drawn).
"""
import argparse
import csv
import json
import math
import os
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
REFERENCE = os.path.join(HERE, "..", "..", "examples", "triaxial", "reference.toml")
LAB_PEAK_PA, LAB_STRAIN_AT_PEAK, LAB_SOLID_FRACTION = 342.4e3, 0.0511, 0.583
# The former reference state (measured friction, walls frictional while preparing), not run by
# this study: the recorded full run of docs/lab-tests.md ("The reference run", 15 % axial strain).
RECORDED_REFERENCE = {"bulk_solid_fraction": 0.5799, "peak_axial_stress_kPa": 345.7,
                      "axial_strain_at_peak_percent": 5.60}

# name, [test] keys added to the reference config; ordered so that a study cut short still spans
# the range (the measured friction first, then the two ends, then between).
STATES = [
    ("mu0.16-walls-off", {"wall_friction_while_preparing": "false"}),
    ("mu0.00-walls-off", {"compaction_friction": "0.0", "wall_friction_while_preparing": "false"}),
    ("mu0.60-walls-off", {"compaction_friction": "0.6", "wall_friction_while_preparing": "false"}),
    ("mu0.05-walls-off", {"compaction_friction": "0.05", "wall_friction_while_preparing": "false"}),
    ("mu0.30-walls-off", {"compaction_friction": "0.3", "wall_friction_while_preparing": "false"}),
    ("mu0.16-walls-on", {"wall_friction_while_preparing": "true"}),  # the former reference state
]


def config_text(keys, max_axial_strain):
    text = open(REFERENCE).read()
    lines = text.split("\n")
    out = []
    for line in lines:
        # The state's keys replace the reference config's own.
        if line.startswith(("compaction_friction", "wall_friction_while_preparing")):
            continue
        if line.startswith("max_axial_strain"):
            line = f"max_axial_strain = {max_axial_strain}"
        out.append(line)
        if line.startswith('type = "triaxial"'):
            out += [f"{k} = {v}" for k, v in keys.items()]
    return "\n".join(out)


def start_state(exe, out_dir, name, keys, max_axial_strain, threads):
    """Starts the run of one state (or resumes it); None when it has finished before."""
    d = os.path.join(out_dir, name)
    if os.path.exists(os.path.join(d, "summary.json")):
        return None
    path = os.path.join(out_dir, name + ".toml")
    if not os.path.exists(path):
        open(path, "w").write(config_text(keys, max_axial_strain))
    resumable = any(os.path.exists(os.path.join(d, f)) for f in ("checkpoint.bin", "preparation.bin"))
    args = [exe, "run", "--resume", d] if resumable else [exe, "run", path, "--out", d]
    if threads:
        args += ["--threads", str(threads)]
    print(f"study: {name}: {' '.join(args)}", file=sys.stderr, flush=True)
    return subprocess.Popen(args)


def run_states(exe, out_dir, chosen, max_axial_strain, jobs):
    """Runs the states, `jobs` at a time (each on 1 thread when jobs > 1: two single-thread runs
    on two cores go faster than two-thread runs one after the other)."""
    pending, running = list(chosen), []
    while pending or running:
        while pending and len(running) < jobs:
            name, keys = pending.pop(0)
            p = start_state(exe, out_dir, name, keys, max_axial_strain, 1 if jobs > 1 else 0)
            if p:
                running.append((name, p))
        for name, p in list(running):
            if p.poll() is not None:
                running.remove((name, p))
                if p.returncode != 0:
                    sys.exit(f"study: {name} failed (exit {p.returncode}); rerun this script to resume it")
        time.sleep(1)


def dilatancy_angle_deg(rows, peak_strain):
    """Triaxial: sin(psi) = -r / (2 - r) with r = d(eps_v)/d(eps_1) (compression positive),
    fitted over +-1 % axial strain around the peak."""
    pts = [(r["axial_strain"], r["volumetric_strain"]) for r in rows
           if abs(r["axial_strain"] - peak_strain) <= 0.01]
    if len(pts) < 3:
        return float("nan")
    n = len(pts)
    mx, my = sum(p[0] for p in pts) / n, sum(p[1] for p in pts) / n
    rate = sum((x - mx) * (y - my) for x, y in pts) / sum((x - mx) ** 2 for x, _ in pts)
    return math.degrees(math.asin(-rate / (2.0 - rate)))


def collect(out_dir, name):
    d = os.path.join(out_dir, name)
    s = json.load(open(os.path.join(d, "summary.json")))
    rows = list(csv.DictReader(open(os.path.join(d, "curve.csv"))))
    rows = [{k: float(v) for k, v in r.items()} for r in rows]
    lw = s.get("initial_love_weber_stress_Pa")
    spec = s["specimen"]
    return {
        "state": name,
        "compaction_friction": spec.get("compaction_friction"),
        "wall_friction_while_preparing": spec.get("wall_friction_while_preparing"),
        "bulk_solid_fraction": s["initial_solid_fraction"],
        "interior_solid_fraction": spec.get("interior_solid_fraction"),
        "coordination_number": spec.get("coordination_number"),
        "initial_lw_axial_over_lateral": lw[2][2] / (0.5 * (lw[0][0] + lw[1][1])) if lw else None,
        "peak_axial_stress_kPa": 1e-3 * s["peak_axial_stress_Pa"],
        "peak_vs_lab_percent": 100 * (s["peak_axial_stress_Pa"] / LAB_PEAK_PA - 1),
        "axial_strain_at_peak_percent": 100 * s["axial_strain_at_peak"],
        "strain_at_peak_vs_lab_percent": 100 * (s["axial_strain_at_peak"] / LAB_STRAIN_AT_PEAK - 1),
        "peak_friction_angle_deg": s["peak_friction_angle_deg"],
        "dilatancy_angle_at_peak_deg": dilatancy_angle_deg(rows, s["axial_strain_at_peak"]),
        "final_volumetric_strain_percent": 100 * rows[-1]["volumetric_strain"],
        "final_axial_strain_percent": 100 * rows[-1]["axial_strain"],
        "axial_stress_at_end_kPa": 1e-3 * rows[-1]["axial_stress_walls_Pa"],
        "wall_time_s": s["wall_time_s"],
    }


def fmt(v, spec):
    return "-" if v is None or (isinstance(v, float) and math.isnan(v)) else format(v, spec)


def write_outputs(out_dir, results):
    with open(os.path.join(out_dir, "study.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(results[0].keys()))
        w.writeheader()
        w.writerows(results)
    lines = ["| state | compaction friction | walls' friction while preparing | solid fraction bulk / interior "
             "| Z | LW axial / lateral at start | peak [kPa] (vs lab) | strain at peak [%] (vs lab) "
             "| phi [deg] | psi at peak [deg] | eps_v at end [%] | wall time [s] |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in results:
        lines.append(
            f"| {r['state']} | {fmt(r['compaction_friction'], '.2f')} | "
            f"{'on' if r['wall_friction_while_preparing'] else 'off'} | "
            f"{fmt(r['bulk_solid_fraction'], '.4f')} / {fmt(r['interior_solid_fraction'], '.4f')} | "
            f"{fmt(r['coordination_number'], '.2f')} | {fmt(r['initial_lw_axial_over_lateral'], '.3f')} | "
            f"{r['peak_axial_stress_kPa']:.1f} ({r['peak_vs_lab_percent']:+.1f} %) | "
            f"{r['axial_strain_at_peak_percent']:.2f} ({r['strain_at_peak_vs_lab_percent']:+.0f} %) | "
            f"{r['peak_friction_angle_deg']:.1f} | {fmt(r['dilatancy_angle_at_peak_deg'], '.1f')} | "
            f"{r['final_volumetric_strain_percent']:.2f} | {r['wall_time_s']:.0f} |")
    open(os.path.join(out_dir, "study.md"), "w").write("\n".join(lines) + "\n")
    print("\n".join(lines))

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(11, 4.5))
    for walls, marker in ((False, "o"), (True, "s")):
        sel = sorted((r for r in results if bool(r["wall_friction_while_preparing"]) == walls),
                     key=lambda r: r["bulk_solid_fraction"])
        if not sel:
            continue
        label = "walls frictional while preparing" if walls else "walls frictionless while preparing"
        x = [r["bulk_solid_fraction"] for r in sel]
        a1.plot(x, [r["peak_axial_stress_kPa"] for r in sel], marker=marker, label=label)
        a2.plot(x, [r["axial_strain_at_peak_percent"] for r in sel], marker=marker, label=label)
        for r in sel:
            a1.annotate(f"mu_c {r['compaction_friction']:.2f}", (r["bulk_solid_fraction"], r["peak_axial_stress_kPa"]),
                        fontsize=7, xytext=(3, 3), textcoords="offset points")
    if not any(r["wall_friction_while_preparing"] for r in results):
        ref = RECORDED_REFERENCE
        label = "mu_c 0.16, walls frictional while preparing (recorded run)"
        a1.plot([ref["bulk_solid_fraction"]], [ref["peak_axial_stress_kPa"]], "s", color="C1", label=label)
        a2.plot([ref["bulk_solid_fraction"]], [ref["axial_strain_at_peak_percent"]], "s", color="C1", label=label)
    a1.plot([LAB_SOLID_FRACTION], [1e-3 * LAB_PEAK_PA], "k*", ms=12, label="laboratory (342.4 kPa, bulk 0.583)")
    a2.plot([LAB_SOLID_FRACTION], [100 * LAB_STRAIN_AT_PEAK], "k*", ms=12, label="laboratory (5.11 %)")
    for a, ylabel in ((a1, "peak axial stress [kPa]"), (a2, "axial strain at peak [%]")):
        a.axvline(LAB_SOLID_FRACTION, color="gray", ls=":", lw=0.8)
        a.set_xlabel("bulk solid fraction at the start of the loading")
        a.set_ylabel(ylabel)
        a.grid(alpha=0.3)
        a.legend(fontsize=7)
    fig.suptitle("reference triaxial (11,636 beads, 150 kPa, I <= 1e-3): specimen state sensitivity")
    fig.tight_layout()
    fig.savefig(os.path.join(out_dir, "study.png"), dpi=120)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("grainlab")
    ap.add_argument("out_dir")
    ap.add_argument("--max-axial-strain", type=float, default=0.12)
    ap.add_argument("--only", default="", help="comma-separated state names (default: all)")
    ap.add_argument("--jobs", type=int, default=1, help="states run at once (each on 1 thread when > 1)")
    ap.add_argument("--collect-only", action="store_true", help="tables and figure from finished states")
    a = ap.parse_args()
    os.makedirs(a.out_dir, exist_ok=True)
    names = [n for n in a.only.split(",") if n]
    chosen = [(n, k) for n, k in STATES if not names or n in names]
    if not a.collect_only:
        run_states(os.path.abspath(a.grainlab), a.out_dir, chosen, a.max_axial_strain, a.jobs)
    done = [n for n, _ in chosen if os.path.exists(os.path.join(a.out_dir, n, "summary.json"))]
    if not done:
        sys.exit("study: no finished state to tabulate")
    write_outputs(a.out_dir, [collect(a.out_dir, n) for n in done])


if __name__ == "__main__":
    main()
