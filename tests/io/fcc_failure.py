#!/usr/bin/env python3
"""Failure stress ratio of a face-centred cubic (FCC) array of equal spheres, composed as a plain
scene (no [test] table): a packing file, six plane walls, the four lateral ones servo-held with
`target_stress`, the top one driven with `velocity`; the stresses are read from walls.csv.

Analytical result (Rowe 1962; Thornton 1979), for an unbounded array: cube axes along x, y, z,
compression along z with the lateral stress held. Every sphere has 12 contacts along <110>: four in
the xy plane and eight inclined at 45 degrees. At failure the in-plane contacts have opened and the
inclined ones slide, T = mu N, without rotation (by symmetry). A plane normal to z is crossed by 4
inclined contacts per sphere, a plane normal to x by 2, so with the contact angle theta = 45 deg

    sigma_1 / sigma_3 = 2 tan(theta) tan(theta + atan(mu)) = 2 (1 + mu) / (1 - mu).

The set-up, and why each detail is there:
- An n x n x n cube of lattice spacings (n even) of the cubic lattice of spacing s = d / sqrt(2)
  (sites (i, j, k) s with i + j + k even), so every face is a (100) plane of spheres touching its
  wall. The area that turns a wall force into the stress of the bulk is set by the contacts that
  cross a plane, not by the span of the centres: a plane normal to z is crossed by 2 n (n + 1)
  inclined contacts (4 per 2 s^2 in the bulk), one normal to x by n (n + 1) inclined ones at
  failure (2 per 2 s^2), so A = n (n + 1) s^2 for every face of the cube. That is the `area` of
  each plane wall, and walls.csv reports the stresses directly. The ratio does not depend on this
  choice: all six faces of the cube have the same area.
- The array starts at the isotropic stress sigma_3: the lattice is shrunk by the overlap a contact
  needs to carry N_0 = sigma_3 s^2 / sqrt(2) (k_n = pi E r* of the linear model,
  docs/contact-model.md), the walls pressed in by the overlap of a face sphere's wall contact
  (2 sqrt(2) N_0 on a contact twice as stiff). No preparation stage is needed.
- Wall contacts are frictionless, so boundary friction adds nothing to sigma_1; gravity is off.
- The lateral walls hold sigma_3 through their servos; the bottom is fixed and the top moves down
  at an axial strain rate of 2e-2 /s: inertial number I = rate d sqrt(rho / p) = 6e-6. The strain
  to failure is of the order of the contact overlap over d (5e-6 to 6e-6 here), so the run is
  short (1e-5 axial strain, 1.4e4 steps). The peak does not depend on the rate: it moved by 0.05 %
  between 1.5e-3 /s and 1.5e-2 /s (n = 8) and by 0.03 % between 1e-2 /s and 2e-2 /s (n = 16). A
  moderate restitution (0.5) damps the waves the start sends.
- The time step is the default 0.1 t_c. The peak is the same within 0.02 % at 0.05, 0.08 and
  0.11 t_c; at 0.127 t_c (the stable step grainlab derives for a sphere held by four contacts,
  which it falls back to when dt_fraction asks for more) the twelve contacts of an FCC sphere are
  not integrated stably: the friction mobilisation is scrambled and the peak comes out 26 % low.
- The wall areas are fixed; the test checks from the wall positions in walls.csv that no face
  changes its area by more than 0.1 %, so the fixed areas are those of the deformed array.

Bounded arrays fail below the analytical value, by a boundary effect that scales as 1/n: the
spheres on the edges where a platen meets a lateral wall lack the contacts that balance the moment
of the friction on their inclined contact into the array; they rotate and mobilise about half of
mu N there, and the imbalance spreads some rotation into the array, so the inclined contacts are
not all at T = mu N at the peak (about 97 % of mu N on average at n = 8). With mu = 0.3 the peak
was 7.6, 4.5, 3.1, 2.4, 2.0 and 1.4 % low for n = 4, 6, 8, 10, 12 and 16: n times the deficit tends
to a constant (about 21 %). Stopping most rotation with a large rolling resistance (arf = 300) did
not raise the peak (3.6 % low at n = 8). The test therefore runs two sizes and checks
- the peak of the larger array (n = 16) within 2 % of the analytical ratio;
- the peak extrapolated to an unbounded array, linearly in 1/n from the two sizes, within 1 %;
- that the mechanism of the analysis formed: at the end every in-plane (xy) neighbour pair is apart
  and every inclined pair still touches (final.csv); and that failure was reached: the ratio rose by
  less than 0.5 % over the last fifth of the run.

usage: fcc_failure.py GRAINLAB_EXE [MU ...]   (default: 0.3 and 0.1)
"""
import csv
import math
import os
import subprocess
import sys
import tempfile

import numpy as np

EXE = sys.argv[1]
FRICTIONS = [float(x) for x in sys.argv[2:]] or [0.3, 0.1]

DIAMETER = 2e-3  # m
RADIUS = 0.5 * DIAMETER
YOUNGS_MODULUS = 46.2e9  # Pa
DENSITY = 2500.0  # kg/m^3
SIGMA_3 = 100e3  # Pa
SIZES = (8, 16)  # lattice spacings per edge of the cube (even)
STRAIN_RATE = 2e-2  # 1/s, axial
FINAL_STRAIN = 1e-5  # axial strain at the end of the run, about twice that of the peak
TOLERANCE = 0.02  # on the peak of the larger array
EXTRAPOLATION_TOLERANCE = 0.01  # on the peak extrapolated to an unbounded array
LATERAL = ("x_low", "x_high", "y_low", "y_high")


def lattice_sites(n):
    return [(i, j, k) for k in range(n + 1) for j in range(n + 1) for i in range(n + 1)
            if (i + j + k) % 2 == 0]


def write_scene(d, n, mu):
    """Writes scene.toml and packing.csv into directory d."""
    k_pair = math.pi * YOUNGS_MODULUS * 0.5 * RADIUS  # N/m, r* = R/2
    k_wall = math.pi * YOUNGS_MODULUS * RADIUS  # r* = R
    s0 = DIAMETER / math.sqrt(2.0)
    contact_force = SIGMA_3 * s0 * s0 / math.sqrt(2.0)  # N_0
    s = (DIAMETER - contact_force / k_pair) / math.sqrt(2.0)
    wall_overlap = 2.0 * math.sqrt(2.0) * contact_force / k_wall
    area = n * (n + 1) * s * s
    with open(os.path.join(d, "packing.csv"), "w") as f:
        f.write("# FCC array, cube axes along x, y, z\nradius,x,y,z\n")
        for i, j, k in lattice_sites(n):
            f.write(f"{RADIUS!r},{i * s!r},{j * s!r},{k * s!r}\n")
    low, high = -RADIUS + wall_overlap, n * s + RADIUS - wall_overlap
    duration = FINAL_STRAIN / STRAIN_RATE
    text = f"""
[simulation]
duration = {duration!r}
dt_fraction = 0.1

[[material]]
name = "glass"
youngs_modulus = {YOUNGS_MODULUS!r}
poisson_ratio = 0.245
density = {DENSITY!r}

[[material]]
name = "platen"

[[pair]]
materials = ["glass", "glass"]
restitution = 0.5
friction = {mu!r}

[[pair]]
materials = ["glass", "platen"]
restitution = 0.5
friction = 0.0

[[particles]]
file = "packing.csv"
material = "glass"

[output]
interval = {duration / 200!r}
trace = "none"
"""
    walls = [("x_low", (low, 0, 0), (1, 0, 0)), ("x_high", (high, 0, 0), (-1, 0, 0)),
             ("y_low", (0, low, 0), (0, 1, 0)), ("y_high", (0, high, 0), (0, -1, 0)),
             ("bottom", (0, 0, low), (0, 0, 1)), ("top", (0, 0, high), (0, 0, -1))]
    for name, point, normal in walls:
        text += f"""
[[wall]]
name = "{name}"
type = "plane"
material = "platen"
point = [{point[0]!r}, {point[1]!r}, {point[2]!r}]
normal = [{normal[0]}.0, {normal[1]}.0, {normal[2]}.0]
area = {area!r}
"""
        if name in LATERAL:
            text += f"target_stress = {SIGMA_3!r}\n"
        elif name == "top":
            text += f"velocity = [0.0, 0.0, {-STRAIN_RATE * (high - low)!r}]\n"
    with open(os.path.join(d, "scene.toml"), "w") as f:
        f.write(text)


def read_walls_csv(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return {key: np.array([float(r[key]) for r in rows]) for key in rows[0]}


def end_gaps(final_csv, n):
    """Surface gaps (m) of every in-plane (xy) and every inclined neighbour pair at the end."""
    data = np.genfromtxt(final_csv, delimiter=",", names=True)
    index = {site: m for m, site in enumerate(lattice_sites(n))}  # ids follow the file order
    x = np.column_stack([data["x"], data["y"], data["z"]])
    in_plane, inclined = [], []
    for (i, j, k), a in index.items():
        for di, dj, dk in ((1, 1, 0), (1, -1, 0), (1, 0, 1), (1, 0, -1), (0, 1, 1), (0, 1, -1)):
            b = index.get((i + di, j + dj, k + dk))
            if b is not None:
                (in_plane if dk == 0 else inclined).append(np.linalg.norm(x[a] - x[b]) - DIAMETER)
    return np.array(in_plane), np.array(inclined)


def peak_ratio(n, mu):
    """Runs the n-spacing cube; checks the run itself; returns the peak sigma_1 / sigma_3."""
    with tempfile.TemporaryDirectory() as d:
        write_scene(d, n, mu)
        out = os.path.join(d, "out")
        r = subprocess.run([EXE, "run", "scene.toml", "--out", out, "--quiet"], cwd=d,
                           capture_output=True, text=True, timeout=600)
        assert r.returncode == 0, r.stderr
        w = read_walls_csv(os.path.join(out, "walls.csv"))
        sigma_1 = 0.5 * (w["top_normal_stress_Pa"] + w["bottom_normal_stress_Pa"])
        sigma_3 = 0.25 * sum(w[f"{name}_normal_stress_Pa"] for name in LATERAL)
        ratio = sigma_1 / sigma_3
        peak = int(np.argmax(ratio))
        spans = {"x": w["x_high_x_m"] - w["x_low_x_m"], "y": w["y_high_y_m"] - w["y_low_y_m"],
                 "z": w["top_z_m"] - w["bottom_z_m"]}
        strain = {axis: (v[0] - v) / v[0] for axis, v in spans.items()}
        area_change = max(np.max(np.abs(strain[a])) + np.max(np.abs(strain[b]))
                          for a, b in (("x", "y"), ("y", "z"), ("z", "x")))
        in_plane, inclined = end_gaps(os.path.join(out, "final.csv"), n)
        print(f"mu = {mu}, n = {n}: peak sigma_1/sigma_3 = {ratio[peak]:.5f} at axial strain "
              f"{strain['z'][peak]:.3e} (sigma_1 = {sigma_1[peak]:.5g} Pa, sigma_3 = "
              f"{sigma_3[peak]:.5g} Pa); at the end {ratio[-1]:.5f}, axial strain "
              f"{strain['z'][-1]:.3e}; largest face area change {100 * area_change:.4f} %; "
              f"in-plane gaps {in_plane.min():.3e} .. {in_plane.max():.3e} m, inclined gaps "
              f"{inclined.min():.3e} .. {inclined.max():.3e} m")
        assert area_change < 1e-3, f"face areas changed by {100 * area_change:.3f} %"
        rise = ratio[peak] / np.max(ratio[:len(ratio) * 4 // 5]) - 1.0
        assert rise < 0.005, f"the ratio still rose by {100 * rise:.2f} % in the last fifth"
        assert np.all(in_plane > 0.0), "an in-plane contact is still closed"
        assert np.all(inclined < 0.0), "an inclined contact opened"
        return ratio[peak]


def check(mu):
    expected = 2.0 * (1.0 + mu) / (1.0 - mu)
    (n1, n2) = SIZES
    r1, r2 = peak_ratio(n1, mu), peak_ratio(n2, mu)
    unbounded = (n2 * r2 - n1 * r1) / (n2 - n1)  # R(n) = R_unbounded + a / n
    print(f"mu = {mu}: analytical 2(1+mu)/(1-mu) = {expected:.5f}; peak n = {n1}: "
          f"{100 * (r1 / expected - 1):+.2f} %, n = {n2}: {100 * (r2 / expected - 1):+.2f} %, "
          f"extrapolated to an unbounded array {unbounded:.5f} "
          f"({100 * (unbounded / expected - 1):+.2f} %)")
    assert abs(r2 / expected - 1.0) < TOLERANCE, (r2, expected)
    assert abs(unbounded / expected - 1.0) < EXTRAPOLATION_TOLERANCE, (unbounded, expected)


if __name__ == "__main__":
    for mu in FRICTIONS:
        check(mu)
    print("ok")
