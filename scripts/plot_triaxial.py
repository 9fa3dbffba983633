#!/usr/bin/env python3
"""curve.png for a triaxial run: axial stress (walls and particles) and volumetric strain against
axial strain, with the laboratory and published DEM peaks marked when the config gives them
([test.laboratory]).  usage: plot_triaxial.py DIR"""
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

d = sys.argv[1]
data = np.genfromtxt(os.path.join(d, "curve.csv"), delimiter=",", names=True)
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from laboratory_marks import draw_laboratory  # noqa: E402

summary = json.load(open(os.path.join(d, "summary.json")))
ref = summary.get("reference")  # only with [test.laboratory] in the config
fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(7, 8), sharex=True)
strain = 100 * data["axial_strain"]
ax1.plot(strain, 1e-3 * data["axial_stress_walls_Pa"], label="axial stress (platens)")
ax1.plot(strain, 1e-3 * data["axial_stress_particles_Pa"], "--", label="axial stress, specimen average (Love-Weber)")
ax1.plot(strain, 1e-3 * 0.5 * (data["lateral_stress_x_walls_Pa"] + data["lateral_stress_y_walls_Pa"]),
         label="lateral stress (walls)")
draw_laboratory(ax1, ref)
ax1.set_ylabel("stress [kPa] (compression positive)")
ax1.legend(fontsize=8)
ax1.grid(alpha=0.3)
ax2.plot(strain, 100 * data["volumetric_strain"], color="C3")
ax2.set_xlabel("axial strain [%]")
ax2.set_ylabel("volumetric strain [%] (compression positive)")
ax2.grid(alpha=0.3)
fig.suptitle("grainlab triaxial test")
fig.tight_layout()
tmp = os.path.join(d, "curve.png.tmp.png")
fig.savefig(tmp, dpi=120)
os.replace(tmp, os.path.join(d, "curve.png"))
