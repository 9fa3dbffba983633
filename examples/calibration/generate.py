#!/usr/bin/python3
"""Synthesise the example laboratory data of examples/calibration/ (SYNTHETIC, not measured).

The files imitate the measurements of Tang, Song, Dong & Song (2019), Materials 12, 3170, so
that `grainlab calibrate` can be tried end to end. True values are the published ones:

* throws.csv  - flat-throw test (docs/calibration.md): 20 throws per plate material, launch height
  H about 300 mm (measured per throw to 1 mm), true restitution per Table 3 (glass 0.926,
  glass plate with rubber membrane 0.580, porous stone 0.730), throw-to-throw scatter of e
  (sd 0.012 / 0.030 / 0.025) and a 0.5 mm reading error on the rebound height h.
* slide.csv   - sliding-friction test: for each material and speed, a slider under five normal
  loads (0.25 ... 1.25 N, each twice) pulled at 0.5, 1, 2.5, 5, 12.5 and 25 mm/min (the paper
  tested 2.5 ... 25; the two slower speeds are added because a curve quadratic below 5 mm/min
  needs three speeds there). The friction coefficient follows a curve shaped like the published
  Eq. 2 - quadratic below 5 mm/min with Eq. 2's ratio of V^2 to V coefficients, linear above,
  continuous at 5 mm/min - through the published Table 4 values: rubber membrane 0.2116 at
  V -> 0 and 0.2443 at 25 mm/min, filter paper 0.1791 and 0.2166; the dip at 5 mm/min is 4 %
  of the quasi-static value. Rope force F = mu(V) P + noise (sd 0.003 N).
* track_rubber_membrane.csv - a camera track (500 frames/s, 0.2 mm noise) of one throw of a
  2 mm bead from H = 300 mm (centre height above the plate) onto the rubber membrane, e = 0.58
  (ratio of vertical velocities), g = 9.81 m/s^2. The centre touches at z = 1 mm (the radius).

Random numbers come from numpy's PCG64 with fixed seeds. The seeds were picked among the first
few so that each published value lies inside the 95 % interval the tool reports (a 95 %
interval misses the truth one time in twenty; an example should not be that one time).

Run:  /usr/bin/python3 examples/calibration/generate.py   (rewrites the CSVs beside it)
"""
import math
import os

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
G = 9.81

RESTITUTION = {"glass": (0.926, 0.012), "rubber_membrane": (0.580, 0.030),
               "porous_stone": (0.730, 0.025)}  # true e, throw-to-throw sd
FRICTION = {"rubber_membrane": (0.2116, 0.2443), "filter_paper": (0.1791, 0.2166)}  # V->0, 25
SPEEDS_MM_PER_MIN = [25.0, 12.5, 5.0, 2.5, 1.0, 0.5]
LOADS_N = [0.25, 0.5, 0.75, 1.0, 1.25]
BREAKPOINT = 5.0
EQ2_Q2_OVER_Q1 = 0.0003 / -0.0044  # shape of the published Eq. 2 below 5 mm/min
DIP = 0.04                           # mu(5) = (1 - DIP) mu(0)


def friction_curve(v, mu0, mu25):
    """mu(V): quadratic below the breakpoint (Eq. 2 shape), linear above, continuous."""
    mu_b = (1.0 - DIP) * mu0
    a = (mu_b - mu0) / (BREAKPOINT + EQ2_Q2_OVER_Q1 * BREAKPOINT**2)
    b = EQ2_Q2_OVER_Q1 * a
    if v <= BREAKPOINT:
        return mu0 + a * v + b * v * v
    return mu_b + (mu25 - mu_b) / (25.0 - BREAKPOINT) * (v - BREAKPOINT)


def write(name, header, rows, comment):
    path = os.path.join(HERE, name)
    with open(path + ".tmp", "w") as f:
        for line in comment:
            f.write(f"# {line}\n")
        f.write(",".join(header) + "\n")
        for r in rows:
            f.write(",".join(r) + "\n")
    os.replace(path + ".tmp", path)


def throws(seed):
    rng = np.random.Generator(np.random.PCG64(seed))
    rows = []
    for material, (e_true, e_sd) in RESTITUTION.items():
        for _ in range(20):
            H = 0.300 + rng.normal(0.0, 0.002)
            e = e_true + rng.normal(0.0, e_sd)
            h = e * e * H + rng.normal(0.0, 0.0005)
            rows.append([material, f"{1e3 * H:.0f}", f"{1e3 * h:.1f}"])
    write("throws.csv", ["material", "H_mm", "h_mm"], rows,
          ["SYNTHETIC flat-throw data (examples/calibration/generate.py), not measurements.",
           "H_mm: launch height above the plate; h_mm: rebound apex height (both in mm)."])


def slide(seed):
    rng = np.random.Generator(np.random.PCG64(seed))
    rows = []
    for material, (mu0, mu25) in FRICTION.items():
        for v in SPEEDS_MM_PER_MIN:
            mu = friction_curve(v, mu0, mu25)
            for p in LOADS_N:
                for _ in range(2):
                    f = mu * p + rng.normal(0.0, 0.003)
                    rows.append([material, f"{v:g}", f"{p:.2f}", f"{f:.4f}"])
    write("slide.csv", ["material", "speed_mm_per_min", "normal_load_N", "friction_force_N"],
          rows,
          ["SYNTHETIC sliding-friction data (examples/calibration/generate.py), not measurements.",
           "speed in mm/min, normal load P and rope force F in N."])


def track(seed):
    rng = np.random.Generator(np.random.PCG64(seed))
    H, r, e, vx0, fps, noise = 0.300, 0.001, 0.58, 0.5, 500.0, 0.0002
    t_fall = math.sqrt(2.0 * (H - r) / G)
    v_in = G * t_fall
    v_out = e * v_in
    t_end = t_fall + 1.6 * v_out / G  # past the rebound apex, before the second impact
    t = np.arange(rng.uniform(0.0, 1.0 / fps) + 0.01, t_end, 1.0 / fps)
    rows = []
    for ti in t:
        if ti < t_fall:
            x, z = vx0 * ti, H - 0.5 * G * ti * ti
        else:
            s = ti - t_fall
            x = vx0 * t_fall + 0.8 * vx0 * s
            z = r + v_out * s - 0.5 * G * s * s
        rows.append([f"{ti:.6f}", f"{x + rng.normal(0, noise):.5f}",
                     f"{z + rng.normal(0, noise):.5f}"])
    write("track_rubber_membrane.csv", ["t_s", "x_m", "z_m"], rows,
          ["SYNTHETIC camera track of one throw onto the rubber membrane (generate.py).",
           "e = 0.58 (vertical velocity ratio), H = 0.300 m, bead radius 1 mm, plate at z = 0."])


if __name__ == "__main__":
    throws(seed=1)
    slide(seed=1)
    track(seed=1)
