#!/usr/bin/env python3
"""Summarises drift-sharing-ab.txt (device run 12): per workload, thread count and variant
(--drift-sharing, --chunk-tail) the ns per particle-step of each round, the median, the state
hashes, the stage means (µs per step, mean over the threads), and each variant's per-round ratio
against never/even (old time / new time, > 1: faster)."""
import collections, re, statistics as st, sys

text = open(sys.argv[1] if len(sys.argv) > 1 else "drift-sharing-ab.txt").read()
runs = []
for block in text.split("## ")[1:]:
    head = block.split("\n")[0]
    m = re.search(r"^\s+(\d+)\s+0\s+\S+\s+(\S+)(?:\s+\S+){4}\s+(\S+)", block, re.M)
    if not m:
        continue
    workload = "tiles" if "--tile" in head else "dense-88k" if "dense-88k" in head else "dense-11k"
    sharing = re.search(r"--drift-sharing (\S+)", head)
    tail = re.search(r"--chunk-tail (\S+)", head)
    stages, last = {}, None
    for line in block.split("\n"):
        s = re.match(r"\s+(region start|drift|records|contacts|gather|step \(sum\))\s+([\d.]+)", line)
        if s:
            last = s.group(1)
            stages[last] = float(s.group(2))
            continue
        w = re.match(r"\s+wait\s+([\d.]+)", line)
        if w and last:
            stages[last + " wait"] = float(w.group(1))
    key = (workload, int(m.group(1)), sharing.group(1) if sharing else "automatic",
           tail.group(1) if tail else "even")
    runs.append((key, float(m.group(2)), m.group(3), stages))
groups = collections.defaultdict(list)
for key, ns, h, stages in runs:
    groups[key].append((ns, h, stages))
names = ["drift", "drift wait", "contacts", "contacts wait", "gather", "gather wait", "step (sum)"]
for key, v in groups.items():
    ns = [r[0] for r in v]
    line = f"{key[0]:9} {key[1]:2} thr  drift {key[2]:9} tail {key[3]:9}  ns/p-step " + \
        " ".join(f"{x:.1f}" for x in ns) + f"  median {st.median(ns):.2f}  hash {set(r[1] for r in v)}"
    print(line)
    if v[0][2]:
        print("      stages: " + "  ".join(f"{n} {st.mean(r[2].get(n, 0.0) for r in v):.0f}" for n in names))
    base = groups.get((key[0], key[1], "never", "even"))
    if base and key[2:] != ("never", "even") and key[2] != "automatic":
        ratios = [b[0] / x[0] for b, x in zip(base, v)]
        print("      per-round ratio against never/even: " + " ".join(f"{r:.3f}" for r in ratios) +
              f"  median {st.median(ratios):.3f}")
