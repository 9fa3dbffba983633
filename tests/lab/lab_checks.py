#!/usr/bin/env python3
"""End-to-end checks of virtual laboratory tests.  usage: lab_checks.py GRAINLAB SOURCE_DIR CHECK"""
import json
import os
import subprocess
import sys
import tempfile

EXE, SRC, CHECK = sys.argv[1], sys.argv[2], sys.argv[3]


def run(*args):
    return subprocess.run([EXE, *args], capture_output=True, text=True, timeout=600)


def flat_throw_trajectory_round_trip():
    with tempfile.TemporaryDirectory() as d:
        for name in ("rubber_membrane", "porous_stone"):
            out = os.path.join(d, name)
            r = run("run", os.path.join(SRC, "examples/paper", f"flat_throw_{name}.toml"), "--out", out, "--quiet")
            assert r.returncode == 0, r.stderr
            summary = json.load(open(os.path.join(out, "summary.json")))
            r = run("calibrate", "restitution", "--trajectory", os.path.join(out, "trajectory.csv"), "--json")
            assert r.returncode == 0, r.stderr
            analysed = json.loads(r.stdout)["e_velocity"]["value"]
            print(name, "e_sim", summary["restitution_simulated"], "from trajectory", analysed)
            assert abs(analysed - summary["restitution_simulated"]) <= 0.005
            assert abs(summary["restitution_simulated"] - summary["restitution_input"]) <= 0.005


def unknown_test_type():
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "t.toml")
        open(path, "w").write('[test]\ntype = "flat_trow"\n')
        r = run("run", path, "--out", os.path.join(d, "o"))
        assert r.returncode == 2 and "flat_trow" in r.stderr and "flat_throw" in r.stderr, r.stderr
        assert not os.path.exists(os.path.join(d, "o"))


TRIAXIAL = open(os.path.join(SRC, "examples/triaxial/small.toml")).read()


def expect_bad_triaxial(old, new, *fragments):
    assert old in TRIAXIAL, old
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "tri.toml")
        open(path, "w").write(TRIAXIAL.replace(old, new, 1))
        for command in (["run"], ["prepare"]):
            r = run(*command, path, "--out", os.path.join(d, "o"))
            assert r.returncode == 2, (r.returncode, r.stderr)
            for f in ("tri.toml",) + fragments:
                assert f in r.stderr, (f, r.stderr)
            assert not os.path.exists(os.path.join(d, "o"))
        print("refused:", r.stderr.strip())


def triaxial_negative_pressure():
    expect_bad_triaxial('confining_stress = "150 kPa"', 'confining_stress = "-150 kPa"', "test.confining_stress", "> 0")


def triaxial_box_smaller_than_particle():
    expect_bad_triaxial('box = ["14 mm", "14 mm", "28 mm"]', 'box = ["1 mm", "14 mm", "28 mm"]', "test.box",
                        "two particle diameters")


def triaxial_more_particles_than_fit():
    expect_bad_triaxial("count = 500", "count = 5000", "test.count", "more particles than fit")


def triaxial_unknown_key():
    expect_bad_triaxial("count = 500", "count = 500\nconfinig_stress = 1", "test.confinig_stress", "unknown key")


globals()[CHECK]()
print("ok:", CHECK)
