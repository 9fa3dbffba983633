#!/usr/bin/env python3
"""End-to-end checks of the grainlab command line: bad input is refused with exit code 2, a
message naming the file and the key, and nothing written; good input gives the documented files.

usage: cli_checks.py GRAINLAB_EXE CHECK_NAME   (run by ctest, one check per test)
"""
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

EXE = sys.argv[1]

BASE = """
[simulation]
duration = 2e-5
dt_fraction = 0.1
gravity = [0.0, 0.0, -9.81]
seed = 3

[[material]]
name = "glass"
youngs_modulus = 46.2e9
poisson_ratio = 0.245
density = 2500.0

[[material]]
name = "steel"

[[pair]]
materials = ["glass", "glass"]
restitution = 0.926
friction = 0.16

[[pair]]
materials = ["glass", "steel"]
restitution = 0.8
friction = 0.2

[[particle]]
material = "glass"
radius = 1e-3
position = [0.0, 0.0, 0.0015]
velocity = [0.0, 0.0, -0.5]

[[particles]]
material = "glass"
count = 600
diameter_min = 1.8e-3
diameter_max = 2.2e-3
region = {type = "box", min = [-0.013, -0.013, 0.004], max = [0.013, 0.013, 0.04]}

[[wall]]
type = "plane"
material = "steel"
point = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]

[[wall]]
type = "cylinder"
material = "steel"
point = [0.0, 0.0, 0.0]
axis = [0.0, 0.0, 1.0]
radius = 0.02

[output]
interval = 5e-6
trace = [0, 1, 2]
vtk = true
"""


def run(args, cwd):
    return subprocess.run([EXE] + args, cwd=cwd, capture_output=True, text=True, timeout=600)


def expect_bad(config_text, *fragments, extra_args=()):
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "scene.toml")
        with open(path, "w") as f:
            f.write(config_text)
        out = os.path.join(d, "out")
        r = run(["run", path, "--out", out, *extra_args], d)
        assert r.returncode == 2, f"exit code {r.returncode}, expected 2; stderr: {r.stderr}"
        for frag in ("scene.toml",) + fragments:
            assert frag in r.stderr, f"message lacks {frag!r}: {r.stderr}"
        assert not os.path.exists(out), "nothing may be written for bad input"
        print("refused as expected:", r.stderr.strip())


def replace(old, new, text=BASE):
    assert old in text, old
    return text.replace(old, new, 1)


CHECKS = {}


def check(f):
    CHECKS[f.__name__] = f
    return f


@check
def run_that_would_never_end():
    """A duration or a material constant off by orders of magnitude would need more steps than
    grainlab runs: refused up front with the step count, not left running."""
    expect_bad(replace("duration = 2e-5", 'duration = "1e300 s"'), "simulation.duration", "steps")
    # A material constant off by orders of magnitude is refused by its physical range first.
    expect_bad(replace("density = 2500.0", 'density = "2.5e-30 kg/m3"'), "material[1].density",
               "[1, 100000] kg/m^3")
    expect_bad(replace("density = 2500.0", 'density = "1e-300 kg/m3"'), "material[1].density",
               "[1, 100000] kg/m^3")
    expect_bad(replace("youngs_modulus = 46.2e9", 'youngs_modulus = "9e27 GPa"'),
               "material[1].youngs_modulus", "10 TPa")


@check
def unknown_key():
    expect_bad(replace("seed = 3", "seed = 3\nsede = 4"), "simulation.sede", "unknown key", "line 7")


@check
def unknown_top_level_table():
    expect_bad(BASE + "\n[outptu]\ninterval = 1\n", "outptu", "unknown top-level key")


@check
def wrong_type():
    expect_bad(replace("count = 600", 'count = "many"'), "particles[1].count", "integer")


@check
def missing_key():
    expect_bad(replace("friction = 0.16\n", "\n"), "pair[1].friction", "missing")


@check
def restitution_zero():
    expect_bad(replace("restitution = 0.926", "restitution = 0.0"), "pair[1].restitution", "(0, 1]")


@check
def restitution_above_one():
    expect_bad(replace("restitution = 0.926", "restitution = 1.2"), "pair[1].restitution", "(0, 1]")


@check
def negative_friction():
    expect_bad(replace("friction = 0.16", "friction = -0.1"), "pair[1].friction", ">= 0")


@check
def nonpositive_youngs_modulus():
    expect_bad(replace("youngs_modulus = 46.2e9", "youngs_modulus = 0.0"), "material[1].youngs_modulus", "E > 0")


@check
def nonpositive_radius():
    expect_bad(replace("radius = 1e-3\n", "radius = -1e-3\n"), "particle[1].radius", "> 0")


@check
def pair_with_unknown_material():
    expect_bad(replace('materials = ["glass", "steel"]', 'materials = ["glass", "stel"]'),
               "pair[2].materials", 'unknown material "stel"', "glass, steel")


@check
def missing_pair_for_touching_materials():
    text = replace('[[pair]]\nmaterials = ["glass", "steel"]\nrestitution = 0.8\nfriction = 0.2\n', "")
    expect_bad(text, "no [[pair]]", '"glass" and "steel"')


@check
def overlapping_particles():
    extra = '\n[[particle]]\nmaterial = "glass"\nradius = 1e-3\nposition = [0.0, 0.0, 0.0034]\n'
    expect_bad(replace("[[particles]]", extra + "\n[[particles]]"), "overlaps particle[1]", "1 %")


@check
def small_overlap_of_prepared_specimen_is_accepted():
    # two beads overlapping by 1e-5 of a radius, as in a compressed specimen: not an error
    extra = '\n[[particle]]\nmaterial = "glass"\nradius = 1e-3\nposition = [0.0, 0.0, 0.00349999999]\n'
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "scene.toml")
        with open(path, "w") as f:
            f.write(replace("[[particles]]", extra + "\n[[particles]]"))
        r = run(["run", path, "--out", os.path.join(d, "out"), "--quiet"], d)
        assert r.returncode == 0, r.stderr


@check
def particle_outside_wall():
    expect_bad(replace("position = [0.0, 0.0, 0.0015]", "position = [0.0, 0.0, -0.002]"), "outside wall[1]")


@check
def too_many_particles_for_region():
    expect_bad(replace("count = 600", "count = 50000"), "particles.count", "fit")


@check
def bad_unit():
    expect_bad(replace("duration = 2e-5", 'duration = "20 parsec"'), "simulation.duration", "unknown unit")


@check
def non_finite_quantity_string():
    # a string with a unit skipped the finite check: "inf s" ran forever
    expect_bad(replace("duration = 2e-5", 'duration = "inf s"'), "simulation.duration", "finite")


@check
def toml_syntax_error():
    expect_bad(replace("seed = 3", "seed = = 3"), "TOML syntax error", "line 6")


@check
def missing_config_file():
    with tempfile.TemporaryDirectory() as d:
        r = run(["run", "nope.toml", "--out", os.path.join(d, "out")], d)
        assert r.returncode == 2 and "nope.toml" in r.stderr, r.stderr
        assert not os.path.exists(os.path.join(d, "out"))


@check
def bad_command_line():
    with tempfile.TemporaryDirectory() as d:
        r = run(["run", "x.toml"], d)  # --out missing
        assert r.returncode == 2 and "--out" in r.stderr, r.stderr
        r = run(["run", "x.toml", "--out", "o", "--threads", "0"], d)
        assert r.returncode == 2 and "--threads" in r.stderr, r.stderr


@check
def existing_output_not_overwritten():
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "scene.toml")
        with open(path, "w") as f:
            f.write(BASE)
        out = os.path.join(d, "out")
        os.makedirs(out)
        with open(os.path.join(out, "precious.txt"), "w") as f:
            f.write("keep me")
        r = run(["run", path, "--out", out, "--quiet"], d)
        assert r.returncode == 2 and "--overwrite" in r.stderr, r.stderr
        assert os.listdir(out) == ["precious.txt"]
        r = run(["run", path, "--out", out, "--overwrite", "--quiet"], d)
        assert r.returncode == 0, r.stderr
        assert open(os.path.join(out, "precious.txt")).read() == "keep me", "foreign files survive"


@check
def overwrite_removes_only_what_grainlab_wrote():
    """--overwrite removes the files listed in the directory's manifest and nothing else: a
    user's vtk/ directory with a ParaView state, a checkpoint.bin-like draft, *.tmp notes survive
    a scene run that writes none of them; the scene's own results are replaced; a user's file with
    the name of a result is refused, not overwritten; the manifest lists what was written."""
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "scene.toml")
        with open(path, "w") as f:
            f.write(BASE)
        out = os.path.join(d, "out")
        assert run(["run", path, "--out", out, "--quiet"], d).returncode == 0
        listed = open(os.path.join(out, ".grainlab-outputs")).read().split()
        assert "summary.json" in listed and "trace.csv" in listed, listed
        os.makedirs(os.path.join(out, "vtk"), exist_ok=True)
        mine = {"vtk/view.pvsm": "paraview state", "draft.tmp": "notes", "curve.png": "my plot",
                "checkpoint.bin": "not grainlab's"}
        for name, text in mine.items():
            with open(os.path.join(out, name), "w") as f:
                f.write(text)
        r = run(["run", path, "--out", out, "--overwrite", "--quiet"], d)
        # curve.png and checkpoint.bin carry names of grainlab results: refused, left as they are
        assert r.returncode == 2 and "not written by grainlab" in r.stderr, r.stderr
        for name in ("curve.png", "checkpoint.bin"):
            assert open(os.path.join(out, name)).read() == mine.pop(name)
            os.remove(os.path.join(out, name))
        r = run(["run", path, "--out", out, "--overwrite", "--quiet"], d)
        assert r.returncode == 0, r.stderr
        for name, text in mine.items():
            assert open(os.path.join(out, name)).read() == text, name
        assert os.path.exists(os.path.join(out, "summary.json"))


def expect_blow_up(config_text, *fragments):
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "scene.toml")
        with open(path, "w") as f:
            f.write(config_text)
        r = run(["run", path, "--out", os.path.join(d, "out"), "--quiet"], d)
        assert r.returncode == 1, (r.returncode, r.stderr)
        for frag in ("blew up",) + fragments:
            assert frag in r.stderr, (frag, r.stderr)
        print("stopped as expected:", r.stderr.strip())


@check
def blow_up_on_speed():
    expect_blow_up(replace("velocity = [0.0, 0.0, -0.5]", "velocity = [0.0, 0.0, -150.0]"), "150 m/s",
                   "simulation.max_speed", "dt_fraction")


@check
def blow_up_on_overlap():
    # rubber-soft beads hitting the plate at 0.5 m/s sink deeper than 5 % of a radius
    expect_blow_up(replace("youngs_modulus = 46.2e9", "youngs_modulus = 1e5").replace("duration = 2e-5", "duration = 5e-3"),
                   "overlap", "5.00 %", "dt_fraction")


def run_base(d, threads, text=BASE):
    path = os.path.join(d, "scene.toml")
    with open(path, "w") as f:
        f.write(text)
    out = os.path.join(d, f"out{threads}")
    r = run(["run", path, "--out", out, "--threads", str(threads), "--quiet"], d)
    assert r.returncode == 0, r.stderr
    return out


@check
def outputs_are_complete():
    with tempfile.TemporaryDirectory() as d:
        out = run_base(d, 2)
        names = sorted(os.listdir(out))
        assert names == [".grainlab-outputs", "final.csv", "particles.pvd", "summary.json", "trace.csv", "vtk",
                         "walls.csv"], names
        # the manifest lists every result file (and the vtk directory), nothing else
        written = {os.path.relpath(os.path.join(r, f), out) for r, _, fs in os.walk(out) for f in fs}
        listed = open(os.path.join(out, ".grainlab-outputs")).read().split()
        assert set(listed) == (written - {".grainlab-outputs"}) | {"vtk/"}, (sorted(listed), sorted(written))
        trace = open(os.path.join(out, "trace.csv")).read().splitlines()
        assert trace[0] == "t,id,x,y,z,vx,vy,vz,wx,wy,wz", trace[0]
        assert len(trace) == 1 + 3 * 5, len(trace)  # 3 traced particles at t = 0, 5, 10, 15, 20 us
        final = open(os.path.join(out, "final.csv")).read().splitlines()
        assert len(final) == 1 + 601 and final[1].startswith("0,"), final[:2]
        s = json.load(open(os.path.join(out, "summary.json")))
        for key in ("inputs", "derived", "steps", "wall_time_s", "grainlab_version"):
            assert key in s, key
        assert s["inputs"]["simulation"]["seed"] == 3
        assert abs(s["derived"]["time_step_s"] - 0.1 * s["derived"]["collision_duration_s"]) < 1e-20


@check
def threads_give_identical_results():
    # 601 particles: above the size where the loops go parallel (core/particles.hpp)
    with tempfile.TemporaryDirectory() as d:
        one, two = run_base(d, 1), run_base(d, 2)
        for name in ("final.csv", "trace.csv", "walls.csv"):
            a = open(os.path.join(one, name)).read()
            b = open(os.path.join(two, name)).read()
            assert a == b, f"{name} differs between 1 and 2 threads"


@check
def vtk_files_open_in_vtk():
    import vtk  # Debian python3-vtk9

    with tempfile.TemporaryDirectory() as d:
        out = run_base(d, 2)
        reader = vtk.vtkXMLUnstructuredGridReader()
        snaps = re.findall(r'file="([^"]+)"', open(os.path.join(out, "particles.pvd")).read())
        assert len(snaps) == 5, snaps
        reader.SetFileName(os.path.join(out, snaps[-1]))
        reader.Update()
        grid = reader.GetOutput()
        assert grid.GetNumberOfPoints() == 601, grid.GetNumberOfPoints()
        for name in ("radius", "velocity", "displacement", "rotation", "id"):
            assert grid.GetPointData().GetArray(name) is not None, name
        walls = vtk.vtkXMLUnstructuredGridReader()
        walls.SetFileName(os.path.join(out, "vtk", "walls.vtu"))
        walls.Update()
        assert walls.GetOutput().GetNumberOfCells() == 1 + 32
        collection = vtk.vtkXMLCollectionReader() if hasattr(vtk, "vtkXMLCollectionReader") else None
        if collection is not None:
            collection.SetFileName(os.path.join(out, "particles.pvd"))
            collection.Update()


@check
def params_shows_reference_constants():
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "scene.toml")
        text = replace("diameter_min = 1.8e-3\ndiameter_max = 2.2e-3", 'diameter = "2 mm"')
        with open(path, "w") as f:
            f.write(text)
        r = run(["params", path, "--json"], d)
        assert r.returncode == 0, r.stderr
        p = json.loads(r.stdout)
        glass = [x for x in p["pairs"] if x["materials"] == ["glass", "glass"]][0]
        assert abs(glass["k_n_N_per_m"] - 7.257e7) < 0.001e7, glass["k_n_N_per_m"]
        assert abs(glass["collision_duration_s"] - 8.44e-7) < 0.01e-7, glass["collision_duration_s"]
        assert glass["damping_ratio_used"] > glass["damping_ratio_textbook"]
        r = run(["params", path], d)
        assert r.returncode == 0 and "7.2571e+07" in r.stdout and "zeta" in r.stdout, r.stdout


# --- packings read from CSV ([[particles]] file = ...) ----------------------------------------

# BASE's materials and pairs, a packing file instead of its particles, and its plate
MATERIALS_AND_PAIRS = BASE[BASE.index("[[material]]"):BASE.index("[[particle]]")]
PACKED = """
[simulation]
duration = 2e-5
gravity = [0.0, 0.0, -9.81]

""" + MATERIALS_AND_PAIRS + """[[particles]]
file = "packing.csv"
material = "glass"

[[wall]]
type = "plane"
material = "steel"
point = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]
"""

# a 4 x 4 x 3 cubic stack of 2 mm beads, 1 % apart, resting just above the plate
LATTICE = "# a small stack\nradius,x,y,z\n" + "".join(
    f"1e-3,{i * 2.02e-3},{j * 2.02e-3},{1.001e-3 + k * 2.02e-3}\n"
    for k in range(3) for j in range(4) for i in range(4))


def run_packed(d, csv_text, toml_text=PACKED, args=("--quiet",), out_name="out"):
    with open(os.path.join(d, "scene.toml"), "w") as f:
        f.write(toml_text)
    with open(os.path.join(d, "packing.csv"), "w") as f:
        f.write(csv_text)
    out = os.path.join(d, out_name)
    return run(["run", "scene.toml", "--out", out, *args], d), out


def expect_bad_packing(csv_text, *fragments, toml_text=PACKED):
    with tempfile.TemporaryDirectory() as d:
        r, out = run_packed(d, csv_text, toml_text)
        assert r.returncode == 2, f"exit code {r.returncode}, expected 2; stderr: {r.stderr}"
        for frag in fragments:
            assert frag in r.stderr, f"message lacks {frag!r}: {r.stderr}"
        assert not os.path.exists(out), "nothing may be written for bad input"
        print("refused as expected:", r.stderr.strip())


@check
def packing_file_runs_and_reads_back():
    with tempfile.TemporaryDirectory() as d:
        r, out = run_packed(d, LATTICE)
        assert r.returncode == 0, r.stderr
        final = open(os.path.join(out, "final.csv")).read()
        assert len(final.splitlines()) == 1 + 48
        # grainlab's own final.csv (id, material index, velocities) is a packing file too
        r2, out2 = run_packed(d, final, PACKED.replace('material = "glass"\n\n[[wall]]', "\n[[wall]]"),
                              out_name="out2")
        assert r2.returncode == 0, r2.stderr
        trace = open(os.path.join(out2, "trace.csv")).read().splitlines()
        first = {line.split(",")[1]: line.split(",")[2:8] for line in trace[1:49]}
        for row in final.splitlines()[1:]:
            f = row.split(",")
            assert [float(v) for v in first[f[0]]] == [float(v) for v in f[3:9]], (f, first[f[0]])


@check
def packing_file_bad_number():
    bad = LATTICE.replace("1e-3,0.00202,0.0,0.001001", "1e-3,0.00202,zero,0.001001")
    expect_bad_packing(bad, "packing.csv line 4", "column 'y'", "not a finite number")


@check
def packing_file_wrong_field_count():
    expect_bad_packing(LATTICE + "1e-3,0.1,0.1\n", "packing.csv line 51", "expected 4 fields")


@check
def packing_file_unknown_and_missing_columns():
    expect_bad_packing(LATTICE.replace("radius,x,y,z", "radius,x,y,zz"), "packing.csv line 2",
                       "unknown column 'zz'")
    expect_bad_packing(LATTICE.replace("radius,x,y,z", "x,y,z,vx").replace("\n1e-3,", "\n0.0,"),
                       "packing.csv line 2", "no 'radius' column")


@check
def packing_file_ids_and_materials():
    rows = "id,material,radius,x,y,z\n0,glass,1e-3,0,0,0.002\n0,glass,1e-3,0.005,0,0.002\n"
    expect_bad_packing(rows, "packing.csv line 3", "id 0 appears twice (first on line 2)")
    rows = "id,material,radius,x,y,z\n0,glass,1e-3,0,0,0.002\n1,basalt,1e-3,0.005,0,0.002\n"
    expect_bad_packing(rows, "packing.csv line 3", "'basalt'")
    rows = "id,material,radius,x,y,z\n0,steel,1e-3,0,0,0.002\n"
    expect_bad_packing(rows, "packing.csv line 2", "no density")
    rows = "id,radius,x,y,z\n5,1e-3,0,0,0.002\n"
    expect_bad_packing(rows, "packing.csv line 2", "id 5 is out of range")


@check
def packing_file_overlap_and_missing_file():
    expect_bad_packing(LATTICE + "1e-3,0.0005,0,0.001001\n", "packing.csv line 51",
                       "overlaps particle[1] (packing.csv line 3)")
    expect_bad_packing(LATTICE, "scene.toml", "particles[1].count",
                       toml_text=PACKED.replace('file = "packing.csv"', 'file = "packing.csv"\ncount = 3'))
    with tempfile.TemporaryDirectory() as d:
        with open(os.path.join(d, "scene.toml"), "w") as f:
            f.write(PACKED)
        r = run(["run", "scene.toml", "--out", "out"], d)
        assert r.returncode == 2 and "packing.csv" in r.stderr and "cannot read" in r.stderr, r.stderr


# --- the stable step of every spring-dashpot (contact/stability.hpp) ---------------------------

DAMPED = PACKED.replace("restitution = 0.8\nfriction = 0.2", "restitution = 0.5\nfriction = 0.2\nrzs = 50")


@check
def damped_pair_lowers_the_step():
    with tempfile.TemporaryDirectory() as d:
        r, out = run_packed(d, LATTICE, DAMPED, args=())
        assert r.returncode == 0, r.stderr
        assert "dt lowered" in r.stderr and "sliding" in r.stderr and "rzs" in r.stderr, r.stderr
        s = json.load(open(os.path.join(out, "summary.json")))["derived"]
        assert s["time_step_limited_by_stability"] is True
        assert s["time_step_s"] == s["stable_step_s"] < 0.1 * s["collision_duration_s"]
        r = run(["params", "scene.toml"], d)
        assert r.returncode == 0 and "lowered below dt_fraction" in r.stdout, r.stdout
        assert "critical steps: normal" in r.stdout, r.stdout


@check
def explicit_step_above_the_stable_step_is_refused():
    text = DAMPED.replace("duration = 2e-5", "duration = 2e-5\ndt = 8e-8")
    expect_bad_packing(LATTICE, "scene.toml", "simulation.dt", "stable step", "rzs", toml_text=text)


# --- wall loads ([[wall]] mass, force, target_stress, area, max_speed) and walls.csv -----------

# BASE's plate and sleeve, and two walls far above the beads: a free piston with an initial
# velocity and a constant force, and a servo-held lid that touches nothing yet
LOADED = BASE.replace("[output]", """[[wall]]
name = "piston"
type = "plane"
material = "steel"
point = [0.0, 0.0, 0.1]
normal = [0.0, 0.0, -1.0]
velocity = [0.0, 0.0, -0.1]
mass = "2 kg"
force = [0.0, 0.0, -3.0]

[[wall]]
name = "lid"
type = "rectangle"
material = "steel"
point = [0.0, 0.0, 0.09]
normal = [0.0, 0.0, -1.0]
size = ["30 mm", "20 mm"]
target_stress = "10 kPa"
max_speed = "0.5 m/s"

[output]""")


@check
def wall_force_without_mass():
    expect_bad(replace('mass = "2 kg"\n', "", LOADED), "wall[3].force", "mass")


@check
def wall_target_stress_on_cylinder():
    expect_bad(replace("radius = 0.02\n", 'radius = 0.02\ntarget_stress = "10 kPa"\n', LOADED),
               "wall[2].target_stress", "cylinder")


@check
def wall_target_stress_on_plane_without_area():
    text = replace('type = "rectangle"', 'type = "plane"', LOADED)
    expect_bad(replace('size = ["30 mm", "20 mm"]\n', "", text), "wall[4].area", "target_stress")
    with tempfile.TemporaryDirectory() as d:  # with its area it runs
        run_base(d, 2, replace('size = ["30 mm", "20 mm"]\n', 'area = "6 cm2"\n', text))


@check
def wall_target_stress_excludes_mass_force_velocity():
    for extra in ('mass = "1 kg"', "force = [0.0, 0.0, 1.0]", "velocity = [0.0, 0.0, -0.1]"):
        key = extra.split(" ")[0]
        expect_bad(replace('max_speed = "0.5 m/s"', 'max_speed = "0.5 m/s"\n' + extra, LOADED),
                   "wall[4].target_stress", f"excludes `{key}`")


@check
def wall_bad_loads():
    expect_bad(replace('mass = "2 kg"', "mass = 0.0", LOADED), "wall[3].mass", "> 0 kg")
    expect_bad(replace('target_stress = "10 kPa"', 'target_stress = "-10 kPa"', LOADED),
               "wall[4].target_stress", "> 0 Pa")
    expect_bad(replace('max_speed = "0.5 m/s"', "max_speed = 0.0", LOADED), "wall[4].max_speed", "> 0 m/s")
    expect_bad(replace('mass = "2 kg"', 'mass = "2 kg"\nmax_speed = 1.0', LOADED), "wall[3].max_speed",
               "target_stress")
    expect_bad(replace('max_speed = "0.5 m/s"', 'max_speed = "0.5 m/s"\narea = 1e-4', LOADED),
               "wall[4].area", "rectangle")
    expect_bad(replace("radius = 0.02\n", 'radius = 0.02\narea = 1e-4\n', LOADED), "wall[2].area",
               "cylinder")
    expect_bad(replace('target_stress = "10 kPa"', 'target_stress = "10 kN"', LOADED),
               "wall[4].target_stress", "unknown unit")


@check
def wall_names_head_walls_csv_columns():
    expect_bad(replace('name = "lid"', 'name = "piston"', LOADED), "wall[4].name", "wall[3]")
    expect_bad(replace('name = "lid"', 'name = "wall1"', LOADED), "wall[4].name", "wall[1]")
    expect_bad(replace('name = "lid"', 'name = "lid,top"', LOADED), "wall[4].name", "commas")


@check
def walls_csv_and_wall_loads():
    """walls.csv columns and schedule; the free piston follows z0 + v0 t + F t^2 / (2 m) (velocity
    Verlet is exact for a constant force); the lid, touching nothing, approaches at max_speed."""
    with tempfile.TemporaryDirectory() as d:
        out = run_base(d, 2, LOADED)
        lines = open(os.path.join(out, "walls.csv")).read().splitlines()
        names = ["wall1", "wall2", "piston", "lid"]
        columns = ["time_s"] + [f"{n}_{c}" for n in names for c in (
            "force_x_N", "force_y_N", "force_z_N", "normal_stress_Pa", "contacts", "x_m", "y_m", "z_m")]
        assert lines[0].split(",") == columns, lines[0]
        rows = [dict(zip(columns, line.split(","))) for line in lines[1:]]
        trace_times = sorted({float(line.split(",")[0]) for line in
                              open(os.path.join(out, "trace.csv")).read().splitlines()[1:]})
        assert [float(r["time_s"]) for r in rows] == trace_times, "same schedule as trace.csv"
        assert len(rows) == 5, len(rows)
        for r in rows:
            t = float(r["time_s"])
            assert r["wall2_normal_stress_Pa"] == "", "a cylinder has no area"
            assert r["wall1_normal_stress_Pa"] == "", "a plane without area has no stress"
            z = 0.1 - 0.1 * t - 0.5 * 3.0 / 2.0 * t * t
            assert abs(float(r["piston_z_m"]) - z) < 1e-13, (t, r["piston_z_m"], z)  # F t^2/2m: 3e-10 m
            z = 0.09 - 0.5 * t
            assert abs(float(r["lid_z_m"]) - z) < 1e-13, (t, r["lid_z_m"], z)
            assert float(r["lid_normal_stress_Pa"]) == 0.0 and r["lid_contacts"] == "0", r
        # a bead resting on the plate (gravity on, overlap 1e-12 m, about its weight): with an area
        # the plate reports -(F . n) / A, compressive positive
        resting = replace("position = [0.0, 0.0, 0.0015]\nvelocity = [0.0, 0.0, -0.5]",
                          "position = [0.0, 0.0, 0.000999999999]", LOADED)
        out = run_base(d, 1, replace("normal = [0.0, 0.0, 1.0]\n",
                                     'normal = [0.0, 0.0, 1.0]\narea = "4 cm2"\n', resting))
        for line in open(os.path.join(out, "walls.csv")).read().splitlines()[1:]:
            r = dict(zip(columns, line.split(",")))
            force, stress = float(r["wall1_force_z_N"]), float(r["wall1_normal_stress_Pa"])
            assert r["wall1_contacts"] == "1" and force < 0.0, r
            assert abs(stress - (-force / 4e-4)) <= 1e-15 * stress and stress > 0.0, (force, stress)


@check
def calibration_material_names_must_be_utf8():
    """A material name that is not UTF-8 text (in the data or on the command line) would make the
    materials file invalid TOML: refused with exit 2 naming the file and line (or the option),
    nothing written."""
    throws = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "examples",
                          "calibration", "throws.csv")
    with tempfile.TemporaryDirectory() as d:
        bad = os.path.join(d, "throws.csv")
        data = open(throws, "rb").read()
        assert b"\nglass," in data
        open(bad, "wb").write(data.replace(b"\nglass,", b"\ngl\xffass,", 1))
        out = os.path.join(d, "pairs.toml")
        r = subprocess.run([EXE, "calibrate", "restitution", bad, "--materials-out", out],
                           capture_output=True, timeout=600)
        err = r.stderr.decode("utf-8", "replace")
        assert r.returncode == 2 and "throws.csv line" in err and "UTF-8" in err, (r.returncode, err)
        assert not os.path.exists(out)
        r = subprocess.run([EXE, "calibrate", "restitution", throws, "--materials-out", out,
                            "--bead-material", b"gl\xe9ass"], capture_output=True, timeout=600)
        err = r.stderr.decode("utf-8", "replace")
        assert r.returncode == 2 and "--bead-material" in err and "UTF-8" in err, (r.returncode, err)
        assert not os.path.exists(out)
        print("refused as expected:", err.strip())


@check
def scene_checkpoint_survives_kill():
    """A scene run (examples/scenes/bead_pour.toml, 3,000 beads poured into a box, shortened to
    12 ms) killed with SIGKILL after a periodic checkpoint and resumed with --resume (on 2 threads
    instead of 1) writes the same trace.csv, walls.csv, final.csv, snapshots and step count, byte
    for byte, as a run straight through; Ctrl-C (SIGINT) writes a checkpoint and exits with 130;
    a resume with a changed config is refused; a finished run cannot be resumed."""
    import signal
    import time
    src = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "examples", "scenes",
                       "bead_pour.toml")
    text = open(src).read()
    assert 'duration = "60 ms"' in text and "[output]" in text
    text = text.replace('duration = "60 ms"', 'duration = "12 ms"').replace(
        "[output]", '[output]\ncheckpoint_interval = "1 s"')
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "pour.toml")
        open(path, "w").write(text)
        a, b = os.path.join(d, "a"), os.path.join(d, "b")
        assert run(["run", path, "--out", a, "--quiet", "--threads", "1"], d).returncode == 0
        p = subprocess.Popen([EXE, "run", path, "--out", b, "--quiet", "--threads", "1"], cwd=d)
        while not os.path.exists(os.path.join(b, "checkpoint.bin")) and p.poll() is None:
            time.sleep(0.01)
        time.sleep(0.3)
        p.kill()
        p.wait()
        assert os.path.exists(os.path.join(b, "checkpoint.bin")), "a periodic checkpoint must exist"
        assert not os.path.exists(os.path.join(b, "summary.json")), "killed after the end"
        r = run(["run", "--resume", b, "--threads", "2"], d)
        assert r.returncode == 0 and "resuming" in r.stderr, r.stderr
        for f in ("trace.csv", "walls.csv", "final.csv", "particles.pvd"):
            assert open(os.path.join(a, f), "rb").read() == open(os.path.join(b, f), "rb").read(), f
        for f in sorted(os.listdir(os.path.join(a, "vtk"))):
            assert open(os.path.join(a, "vtk", f), "rb").read() == open(os.path.join(b, "vtk", f), "rb").read(), f
        sa, sb = (json.load(open(os.path.join(x, "summary.json"))) for x in (a, b))
        assert sa["steps"] == sb["steps"] and sa["kinetic_energy_final_J"] == sb["kinetic_energy_final_J"]
        assert not os.path.exists(os.path.join(b, "checkpoint.bin"))
        r = run(["run", "--resume", b], d)
        assert r.returncode == 2, (r.returncode, r.stderr)
        # Ctrl-C: a checkpoint and exit code 130; with the config changed the resume is refused.
        c = os.path.join(d, "c")
        p = subprocess.Popen([EXE, "run", path, "--out", c, "--quiet"], cwd=d, stderr=subprocess.PIPE, text=True)
        time.sleep(1.0)
        p.send_signal(signal.SIGINT)
        _, err = p.communicate()
        assert p.returncode == 130 and "--resume" in err, (p.returncode, err)
        open(path, "a").write("\n# edited\n")
        r = run(["run", "--resume", c], d)
        assert r.returncode == 2 and "has changed" in r.stderr, r.stderr
        print("scene resumed bit-identically after SIGKILL;", err.strip())


@check
def barrier_spin_is_bounded():
    """OpenMP threads waiting at a barrier spin 1,000 rounds, not GCC's 300,000 (which collapse a
    run when another process holds a core; docs/performance.md sec. 15); a user's own
    GOMP_SPINCOUNT or OMP_WAIT_POLICY is kept. OMP_DISPLAY_ENV makes the runtime print its
    settings each time it starts: the last print is what the run uses."""
    def spin_counts(**extra):
        env = {k: v for k, v in os.environ.items() if k not in ("OMP_WAIT_POLICY", "GOMP_SPINCOUNT")}
        env.update(OMP_DISPLAY_ENV="verbose", **extra)
        r = subprocess.run([EXE, "--version"], capture_output=True, text=True, env=env, timeout=60)
        assert r.returncode == 0 and "grainlab" in r.stdout, (r.returncode, r.stdout, r.stderr)
        return re.findall(r"GOMP_SPINCOUNT = '(\d+)'", r.stdout + r.stderr)
    got = spin_counts()
    assert got and got[-1] == "1000", got
    got = spin_counts(GOMP_SPINCOUNT="77")
    assert got == ["77"], got
    got = spin_counts(OMP_WAIT_POLICY="active")
    assert len(got) == 1 and got[0] != "1000", got
    print("barrier spin:", spin_counts())


@check
def bound_threads_keep_every_cpu():
    """With OMP_PROC_BIND (or OMP_PLACES) set, libgomp binds grainlab's first thread before main;
    a restart to set the wait policy would inherit that one CPU and run all threads on it. So a
    bound run starts its runtime once, its places list every usable CPU, and it says which wait
    policy it keeps. (With one usable CPU the places check cannot tell; the single start still
    can.)"""
    env = {k: v for k, v in os.environ.items()
           if k not in ("OMP_WAIT_POLICY", "GOMP_SPINCOUNT", "GOMP_CPU_AFFINITY")}
    env.update(OMP_PROC_BIND="spread", OMP_PLACES="threads", OMP_DISPLAY_ENV="true")
    with tempfile.TemporaryDirectory() as d:
        c = os.path.join(d, "scene.toml")
        with open(c, "w") as f:
            f.write(BASE)
        r = subprocess.run([EXE, "run", c, "--out", os.path.join(d, "out"), "--threads", "2"],
                           capture_output=True, text=True, env=env, timeout=300, cwd=d)
    out = r.stdout + r.stderr
    assert r.returncode == 0, (r.returncode, out[-2000:])
    places = re.findall(r"OMP_PLACES = '([^']*)'", out)
    assert len(places) == 1, ("the runtime started more than once", places)
    usable = len(os.sched_getaffinity(0))
    assert places[0].count("{") == usable, (places, usable)
    assert "threads are bound" in r.stderr, r.stderr
    print("bound run, places:", places[0])


if __name__ == "__main__":
    CHECKS[sys.argv[2]]()
    print("ok:", sys.argv[2])
