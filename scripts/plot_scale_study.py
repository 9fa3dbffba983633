#!/usr/bin/env python3
"""scale.png for a scale study.  usage: plot_scale_study.py DIR

Left: the peak axial stress against the bead diameter d for each gravity setting, with the
published fit (Eq. 12, read with d in m and sigma in MPa, the only reading that gives its 313 kPa
at 2 mm) and the laboratory's 276.83 kPa at 2 mm. Right: the peaks made dimensionless,
sigma_peak / sigma_3 against the self-weight ratio rho g H / sigma_3, with the fitted
dimensional-analysis form."""
import csv
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

d = sys.argv[1]
rows = list(csv.DictReader(open(os.path.join(d, "scale.csv"))))
summary = json.load(open(os.path.join(d, "summary.json")))
s3 = summary["confining_stress_Pa"]

ok_all = [r for r in rows if r["status"] == "ok"]
inertia = [float(r["max_inertial_number"]) for r in ok_all]
# Right panel: against the self-weight ratio, or against I where the loading rate changes with d.
by_rate = bool(inertia) and max(inertia) > 2 * min(inertia)
x_key = "max_inertial_number" if by_rate else "self_weight_over_confining_stress"
fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(12, 5))
for on, marker, label in ((False, "o", "gravity off"), (True, "s", "gravity on")):
    sel = [r for r in rows if (float(r["gravity_m_per_s2"]) > 0) == on]
    ok = [r for r in sel if r["status"] == "ok"]
    bad = [r for r in sel if r["status"] != "ok" and r["peak_axial_stress_Pa"] not in ("", "nan")]
    if ok:
        x = np.array([float(r["diameter_m"]) for r in ok])
        y = np.array([float(r["peak_axial_stress_Pa"]) for r in ok])
        order = np.argsort(x)
        ax1.plot(x[order], 1e-3 * y[order], marker=marker, label=label)
        ax2.plot([float(r[x_key]) for r in ok],
                 [float(r["peak_over_confining_stress"]) for r in ok], marker, label=label)
    if bad:
        ax1.plot([float(r["diameter_m"]) for r in bad], [1e-3 * float(r["peak_axial_stress_Pa"]) for r in bad],
                 "x", color="red", label=f"{label}: run flagged (see status)")
fit_on = summary["fits"].get("gravity_on", {}).get("dimensional_form", {})
fit_rate = summary["fits"].get("gravity_off", {}).get("inertial_form", {})
if by_rate and "C" in fit_rate:
    ii = np.linspace(0, max(inertia), 50)
    c = [fit_rate[k]["value"] for k in ("A", "B", "C")]
    ax2.plot(ii, c[0] + c[1] * ii + c[2] * ii ** 2, "k--", lw=0.8,
             label=f"fit: {c[0]:.3g} {c[1]:+.4g} I {c[2]:+.4g} I^2")
elif "B" in fit_on:
    xs = [float(r["self_weight_over_confining_stress"]) for r in rows if float(r["gravity_m_per_s2"]) > 0]
    xx = np.linspace(0, max(xs) if xs else 1, 50)
    ax2.plot(xx, fit_on["A"]["value"] + fit_on["B"]["value"] * xx, "k--", lw=0.8,
             label=f"fit: {fit_on['A']['value']:.3f} + {fit_on['B']['value']:.3f} rho g H / sigma_3")
dd = np.linspace(0.002, max(float(r["diameter_m"]) for r in rows), 200)
ax1.plot(dd, 1e3 * (0.4469 * dd ** 2 + 5.311 * dd + 0.3033), "g:",
         label="published fit (Eq. 12, d in m, sigma in MPa)")
ax1.plot([0.002], [276.83], "k*", ms=12, label="laboratory (276.83 kPa, d = 2 mm)")
ax1.set_yscale("log")
ax1.set_xlabel("bead diameter d [m] (the model scaled with it)")
ax1.set_ylabel("peak axial stress [kPa]")
ax1.grid(alpha=0.3, which="both")
ax1.legend(fontsize=7)
ax2.set_xlabel("maximum inertial number I of the run" if by_rate else "self-weight ratio rho_bulk g H / sigma_3")
ax2.set_ylabel("sigma_peak / sigma_3")
ax2.grid(alpha=0.3)
ax2.legend(fontsize=7)
fig.suptitle(f"scale study: plane strain, sigma_3 = {1e-3 * s3:.0f} kPa; {summary['loading']}", fontsize=9)
fig.tight_layout()
tmp = os.path.join(d, "scale.png.tmp.png")
fig.savefig(tmp, dpi=120)
os.replace(tmp, os.path.join(d, "scale.png"))
