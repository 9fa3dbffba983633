#!/usr/bin/env python3
"""CPU microseconds per loading step of the plane strain test's serial per-step functions, from a
`perf record -e cpu-clock -F 2000` of `grainlab run ps-short.toml` and that run's summary.json.

The samples of the last WINDOW of the run's wall time (all of it in the loading: the loading is
the last 44-48 % of a ps-short run on 2 threads) over the loading steps in that time (15,448 in
the loading's shearing_wall_time_s).

usage: perf_per_step.py PERF_DATA SUMMARY_JSON
"""
import json
import re
import subprocess
import sys

WINDOW = 0.40
LOADING_STEPS = 15448  # 0.5 % axial strain at the reference config's strain rate and step
FUNCTIONS = ["Membrane::surface", "Membrane::applied_stress", "Membrane::apply",
             "love_weber_stress", "boundary_stress"]
SAMPLE_HZ = 2000

perf_data, summary_json = sys.argv[1], sys.argv[2]
summary = json.load(open(summary_json))
steps = LOADING_STEPS * WINDOW * summary["wall_time_s"] / summary["shearing_wall_time_s"]
report = subprocess.run(
    ["perf", "report", "-i", perf_data, "--no-children", "--sort", "symbol",
     "--time", f"{round(100 - 100 * WINDOW)}%-100%", "-F", "sample,symbol"],
    capture_output=True, text=True, check=True).stdout
samples = dict.fromkeys(FUNCTIONS, 0)
for line in report.splitlines():
    m = re.match(r"\s+(\d+)\s+\[\.\]\s+(\S+)", line)
    if m and m.group(2).startswith("grainlab::") and m.group(2)[10:] in samples:
        samples[m.group(2)[10:]] += int(m.group(1))
print(f"loading steps in the window: {steps:.0f}")
for name, count in samples.items():
    print(f"{name:28s} {count / SAMPLE_HZ / steps * 1e6:7.1f} us per step")
