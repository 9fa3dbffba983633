#!/usr/bin/env python3
"""curve.png and band.png for a plane strain run.  usage: plot_plane_strain.py DIR

curve.png: axial stress (platens and particles), lateral stress (membrane and particles), the
out-of-plane stress on the fixed walls and the volumetric strain against axial strain, with the
laboratory and published DEM peaks marked when the config gives them ([test.laboratory]).
band.png: the local shear strain since the start over the specimen's x-z face (averaged through
the thickness), with the shear band found and the Mohr-Coulomb, Roscoe and Arthur inclinations."""
import json
import math
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


def save(fig, name):
    tmp = os.path.join(d, name + ".tmp.png")
    fig.savefig(tmp, dpi=120)
    os.replace(tmp, os.path.join(d, name))


fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(7, 8), sharex=True)
strain = 100 * data["axial_strain"]
ax1.plot(strain, 1e-3 * data["axial_stress_platens_Pa"], label="axial stress (platens)")
ax1.plot(strain, 1e-3 * data["axial_stress_particles_Pa"], "--", label="axial stress (particles, Love-Weber)")
ax1.plot(strain, 1e-3 * data["lateral_stress_membrane_Pa"], label="lateral stress (membrane, applied)")
ax1.plot(strain, 1e-3 * data["lateral_stress_particles_Pa"], "--", label="lateral stress (particles)")
ax1.plot(strain, 1e-3 * data["out_of_plane_stress_walls_Pa"], label="out-of-plane stress (fixed walls)")
draw_laboratory(ax1, ref)
ax1.set_ylabel("stress [kPa] (compression positive)")
ax1.legend(fontsize=7)
ax1.grid(alpha=0.3)
ax2.plot(strain, 100 * data["volumetric_strain"], color="C3")
ax2.set_xlabel("axial strain [%]")
ax2.set_ylabel("volumetric strain [%] (compression positive)")
ax2.grid(alpha=0.3)
fig.suptitle("grainlab plane strain test")
fig.tight_layout()
save(fig, "curve.png")

band = summary["shear_band"]
grid = np.genfromtxt(os.path.join(d, "band_map.csv"), delimiter=",", names=True)
xs, zs = np.unique(grid["x_m"]), np.unique(grid["z_m"])
field = grid["shear_strain"].reshape(len(zs), len(xs))
cell = xs[1] - xs[0] if len(xs) > 1 else 1e-3
fig, ax = plt.subplots(figsize=(5.5, 7))
extent = [1e3 * (xs[0] - cell / 2), 1e3 * (xs[-1] + cell / 2), 1e3 * (zs[0] - cell / 2), 1e3 * (zs[-1] + cell / 2)]
im = ax.imshow(field, origin="lower", extent=extent, cmap="inferno", aspect="equal")
fig.colorbar(im, ax=ax, label="local shear strain since the start (x-z plane)")
title = "shear band"
if band.get("found"):
    th = math.radians(band["direction_deg"])
    low = band["map_low_m"]
    t = np.array([math.cos(th), math.sin(th)])
    n = np.array([-math.sin(th), math.cos(th)])
    s = np.linspace(-1, 1, 2) * 0.2
    p = np.array(low)[:, None] + band["offset_m"] * n[:, None] + t[:, None] * s[None, :]
    ax.plot(1e3 * p[0], 1e3 * p[1], "c--", lw=1, label="band found")
    ax.set_xlim(extent[0], extent[1])
    ax.set_ylim(extent[2], extent[3])
    th_ = band["theories_deg"]

    def one(x):  # before the peak a theory has no angle yet (null in summary.json)
        return "n/a" if x is None else f"{x:.1f}"

    title = (f"band at {one(band['inclination_to_horizontal_deg'])} deg, "
             f"{one(band['thickness_in_diameters'])} d thick\n"
             f"Mohr-Coulomb {one(th_['mohr_coulomb_45_plus_phi_over_2'])}, "
             f"Roscoe {one(th_['roscoe_45_plus_psi_over_2'])}, "
             f"Arthur {one(th_['arthur_45_plus_phi_plus_psi_over_4'])} deg")
    ax.legend(fontsize=8, loc="lower right")
ax.set_title(title, fontsize=9)
ax.set_xlabel("x (width) [mm]")
ax.set_ylabel("z (height) [mm]")
fig.tight_layout()
save(fig, "band.png")
