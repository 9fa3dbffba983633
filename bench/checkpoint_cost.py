#!/usr/bin/env python3
"""What periodic checkpoints cost: the same runs with a checkpoint every INTERVAL seconds of wall
time and with none, interleaved, on an idle machine.

usage: checkpoint_cost.py GRAINLAB [--interval 0.5] [--rounds 3]

Runs (each round: with checkpoints, then without, then the next round):
  * plane strain loading: examples/plane_strain/small.toml (2,000 beads) to 2 % axial strain on a
    specimen prepared once, so only the loading (with the membrane's state) is timed;
  * scene: examples/scenes/bead_pour.toml (3,000 beads poured into a box), 20 ms.
For each: the median wall time with and without, the number of checkpoints written (counted by
watching checkpoint.bin's modification time), the checkpoint's size, and the cost of one
checkpoint = (median with - median without) / count. The overhead at the default interval
(300 s) is that cost / 300 s.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.join(HERE, "..")


def timed_run(args, out_dir):
    """Runs `args`, counting checkpoint.bin writes; returns (wall s, checkpoints, largest size)."""
    start = time.monotonic()
    p = subprocess.Popen(args, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    seen, size = set(), 0
    path = os.path.join(out_dir, "checkpoint.bin")
    while p.poll() is None:
        try:
            st = os.stat(path)
            seen.add(st.st_mtime_ns)
            size = max(size, st.st_size)
        except FileNotFoundError:
            pass
        time.sleep(0.005)
    wall = time.monotonic() - start
    if p.returncode != 0:
        sys.exit(f"{' '.join(args)} failed: {p.stderr.read()}")
    return wall, len(seen), size


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("grainlab")
    ap.add_argument("--interval", type=float, default=0.5)
    ap.add_argument("--rounds", type=int, default=3)
    a = ap.parse_args()
    exe = os.path.abspath(a.grainlab)
    with tempfile.TemporaryDirectory() as d:
        ps = open(os.path.join(ROOT, "examples/plane_strain/small.toml")).read()
        ps = ps.replace("max_axial_strain = 0.10", "max_axial_strain = 0.02")
        spec = os.path.join(d, "spec")
        base = os.path.join(d, "base.toml")
        open(base, "w").write(ps)
        subprocess.run([exe, "prepare", base, "--out", spec, "--quiet"], check=True)
        scene = open(os.path.join(ROOT, "examples/scenes/bead_pour.toml")).read()
        scene = scene.replace('duration = "60 ms"', 'duration = "20 ms"')
        configs = {}
        for with_cp in (True, False):
            interval = f'"{a.interval} s"' if with_cp else '"1e6 s"'
            path = os.path.join(d, f"ps_{with_cp}.toml")
            open(path, "w").write(ps.replace("[test]\n", f'[test]\nspecimen = "{spec}"\ncheckpoint_interval = {interval}\n', 1))
            configs[("plane strain loading, 2,000 beads", with_cp)] = path
            path = os.path.join(d, f"scene_{with_cp}.toml")
            open(path, "w").write(scene.replace("[output]", f"[output]\ncheckpoint_interval = {interval}", 1))
            configs[("scene (bead pour), 3,000 beads", with_cp)] = path
        results = {k: [] for k in configs}
        for r in range(a.rounds):
            for key, path in configs.items():
                out = os.path.join(d, f"o{r}_{abs(hash(key))}")
                results[key].append(timed_run([exe, "run", path, "--out", out, "--quiet"], out))
        rows = []
        for name in dict.fromkeys(k[0] for k in configs):
            w = results[(name, True)]
            wo = results[(name, False)]
            t_with = statistics.median(x[0] for x in w)
            t_without = statistics.median(x[0] for x in wo)
            count = statistics.median(x[1] for x in w)
            size = max(x[2] for x in w)
            per = (t_with - t_without) / count if count else float("nan")
            rows.append({"run": name, "wall_with_s": t_with, "wall_without_s": t_without,
                         "checkpoints": count, "checkpoint_bytes": size, "seconds_per_checkpoint": per,
                         "overhead_at_300s_percent": 100 * per / 300.0,
                         "overhead_at_interval_percent": 100 * (t_with / t_without - 1)})
        print(f"| run | wall, checkpoint every {a.interval:g} s [s] | wall, none [s] | checkpoints | size [MB] "
              f"| per checkpoint [s] | overhead at {a.interval:g} s | overhead at 300 s |")
        print("|---|---|---|---|---|---|---|---|")
        for x in rows:
            print(f"| {x['run']} | {x['wall_with_s']:.2f} | {x['wall_without_s']:.2f} | {x['checkpoints']:.0f} | "
                  f"{x['checkpoint_bytes'] / 1e6:.2f} | {x['seconds_per_checkpoint']:.4f} | "
                  f"{x['overhead_at_interval_percent']:+.1f} % | {x['overhead_at_300s_percent']:.4f} % |")
        print(json.dumps(rows))


if __name__ == "__main__":
    main()
