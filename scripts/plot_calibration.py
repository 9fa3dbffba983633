#!/usr/bin/python3
"""Plots for `grainlab calibrate ... --plot out.png` (run with Debian's /usr/bin/python3).

Usage: plot_calibration.py ANALYSIS.json OUT.png

ANALYSIS.json is the document `grainlab calibrate ... --json` prints; its "analysis" key picks
the plot:
  restitution - e per throw for each material, with the mean and its confidence interval;
  trajectory  - tracked heights with the two fitted free-flight parabolas, and the residuals;
  friction    - per material: the F-P points and through-origin lines per speed, and the
                friction coefficient against speed with the speed fit and the quasi-static value.
The PNG is written to a temporary file and renamed, so a failed run leaves no partial file.
"""
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def plot_restitution(doc):
    fig, ax = plt.subplots(figsize=(8, 4.5))
    x0 = 0
    ticks, labels = [], []
    for i, m in enumerate(doc["materials"]):
        e = [t["e"] for t in m["throws"]]
        x = np.arange(x0, x0 + len(e))
        color = f"C{i}"
        ax.plot(x, e, "o", color=color, ms=4, label=f'{m["material"]} (n = {m["n"]})')
        ax.hlines(m["mean"], x[0] - 0.4, x[-1] + 0.4, color=color, lw=2)
        ci = m["ci"]
        if ci["low"] is not None and ci["high"] is not None and ci["low"] < ci["high"]:
            ax.fill_between([x[0] - 0.4, x[-1] + 0.4], ci["low"], ci["high"], color=color,
                            alpha=0.2, lw=0)
        ticks.append(0.5 * (x[0] + x[-1]))
        labels.append(f'{m["material"]}\ne = {m["mean"]:.3f}')
        x0 += len(e) + 3
    ax.set_xticks(ticks, labels)
    ax.set_ylabel("restitution coefficient e = sqrt(h/H)")
    level = doc["materials"][0]["ci"]["level"] if doc["materials"] else 0.95
    ax.set_title(f'{os.path.basename(doc["source"])}: e per throw, mean (line) and '
                 f'{100 * level:g} % CI (band)')
    ax.grid(alpha=0.3)
    fig.tight_layout()
    return fig


def parabola(p, t):
    tau = np.asarray(t) - p["t_ref_s"]
    return p["a_m"] + p["b_m_s"] * tau - 0.5 * p["g_m_s2"] * tau * tau


def plot_trajectory(doc):
    fig, (ax, axr) = plt.subplots(2, 1, figsize=(8, 6), sharex=True,
                                  gridspec_kw={"height_ratios": [3, 1]})
    pts = doc["points"]
    for side, color, name in (("before", "C0", "before impact"), ("after", "C1", "after impact"),
                              ("unused", "0.6", "not used")):
        sel = [p for p in pts if p["side"] == side]
        if not sel:
            continue
        t = [p["t_s"] for p in sel]
        ax.plot(t, [1e3 * p["z_m"] for p in sel], ".", color=color, ms=3, label=name)
        if side != "unused":
            axr.plot(t, [1e3 * p["residual_m"] for p in sel], ".", color=color, ms=3)
    ti = doc["impact_time_s"]["value"]
    t_all = [p["t_s"] for p in pts]
    tb = np.linspace(min(t_all), ti, 200)
    ta = np.linspace(ti, max(p["t_s"] for p in pts if p["side"] != "unused"), 200)
    ax.plot(tb, 1e3 * parabola(doc["parabola_before"], tb), "-", color="C0", lw=1)
    ax.plot(ta, 1e3 * parabola(doc["parabola_after"], ta), "-", color="C1", lw=1)
    ax.axvline(ti, color="k", lw=0.5, ls=":")
    ax.set_ylabel("bead centre height z (mm)")
    ax.set_title(f'{os.path.basename(doc["source"])}: e = {doc["e_velocity"]["value"]:.4f} '
                 f'(velocities), {doc["e_heights"]["value"]:.4f} (sqrt(h/H))')
    ax.legend()
    ax.grid(alpha=0.3)
    axr.axhline(0.0, color="k", lw=0.5)
    axr.set_xlabel("t (s)")
    axr.set_ylabel("residual (mm)")
    axr.grid(alpha=0.3)
    fig.tight_layout()
    return fig


def speed_curve(fit, v):
    c = fit["coefficients"]
    vb = fit["breakpoint_mm_per_min"]
    u = np.minimum(v, vb)
    mu = c[0] + c[1] * u + c[2] * u * u
    if fit["has_linear_part"]:
        mu = mu + c[3] * np.maximum(v - vb, 0.0)
    return mu


def plot_friction(doc):
    mats = doc["materials"]
    fig, axes = plt.subplots(len(mats), 2, figsize=(11, 4.2 * len(mats)), squeeze=False)
    level = doc["level"]
    for row, m in enumerate(mats):
        ax, axs = axes[row]
        p_max = max(p["normal_load_N"] for s in m["speeds"] for p in s["points"])
        for i, s in enumerate(m["speeds"]):
            color = f"C{i}"
            P = [p["normal_load_N"] for p in s["points"]]
            F = [p["friction_force_N"] for p in s["points"]]
            mu = s["through_origin"]["mu"]
            ax.plot(P, F, "o", color=color, ms=3.5)
            ax.plot([0, 1.05 * p_max], [0, 1.05 * p_max * mu], "-", color=color, lw=1,
                    label=f'{s["speed_mm_per_min"]:g} mm/min: mu = {mu:.4f}')
        ax.set_xlim(left=0)
        ax.set_ylim(bottom=0)
        ax.set_xlabel("normal load P (N)")
        ax.set_ylabel("friction force F (N)")
        ax.set_title(f'{m["material"]}: F-P lines through the origin')
        ax.legend(fontsize=8)
        ax.grid(alpha=0.3)

        v = np.array([s["speed_mm_per_min"] for s in m["speeds"]])
        mu = np.array([s["through_origin"]["mu"] for s in m["speeds"]])
        lo = np.array([s["through_origin"]["ci"]["low"] or np.nan for s in m["speeds"]])
        hi = np.array([s["through_origin"]["ci"]["high"] or np.nan for s in m["speeds"]])
        axs.errorbar(v, mu, yerr=[mu - lo, hi - mu], fmt="o", color="C0", capsize=3,
                     label=f"F-P slope per speed ({100 * level:g} % CI)")
        fit = m["speed_fit"]
        if fit is not None:
            vv = np.linspace(0.0, 1.05 * v.max(), 400)
            axs.plot(vv, speed_curve(fit, vv), "-", color="C1",
                     label=f'fit: quadratic below {fit["breakpoint_mm_per_min"]:g} mm/min, '
                           "linear above")
            qs = fit["quasi_static"]
            err = None
            if qs["ci"]["low"] is not None and qs["ci"]["high"] is not None:
                err = [[qs["value"] - qs["ci"]["low"]], [qs["ci"]["high"] - qs["value"]]]
            axs.errorbar([0.0], [qs["value"]], yerr=err, fmt="s", color="C3", capsize=3,
                         label=f'quasi-static mu(V->0) = {qs["value"]:.4f}')
            axs.axvline(fit["breakpoint_mm_per_min"], color="k", lw=0.5, ls=":")
        else:
            axs.text(0.02, 0.02, "no speed fit (see the text output)", transform=axs.transAxes)
        axs.set_xlabel("pulling speed V (mm/min)")
        axs.set_ylabel("friction coefficient mu")
        axs.set_title(f'{m["material"]}: friction against speed')
        axs.legend(fontsize=8)
        axs.grid(alpha=0.3)
    fig.suptitle(os.path.basename(doc["source"]))
    fig.tight_layout()
    return fig


def main(argv):
    if len(argv) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    with open(argv[1]) as f:
        doc = json.load(f)
    kind = doc.get("analysis")
    makers = {"restitution": plot_restitution, "trajectory": plot_trajectory,
              "friction": plot_friction}
    if kind not in makers:
        print(f"plot_calibration.py: unknown analysis {kind!r}", file=sys.stderr)
        return 2
    fig = makers[kind](doc)
    out = argv[2]
    root, ext = os.path.splitext(out)
    tmp = f"{root}.tmp{os.getpid()}{ext or '.png'}"
    try:
        fig.savefig(tmp, dpi=120)
        os.replace(tmp, out)
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
