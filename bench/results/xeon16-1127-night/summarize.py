#!/usr/bin/env python3
"""Summarises a file of interleaved grainlab_bench runs from the device (drift-sharing-ab.txt,
chunk-sharing-ab.txt, chunk-sharing-defaults-ab.txt): per workload, thread count and variant (the
flags --drift-sharing, --chunk-tail, --chunks-per-thread, --owner-keeps-last, "-" where not
given) the ns per particle-step of each round, the median, the state hashes, the stage means (µs
per step, mean over the threads, where timed), and each variant's per-round ratio against the
first variant of its workload, thread count and steps that ran interleaved with it (the one
that sets the same flags, where there is one; old time / new time, > 1: faster).
  python3 summarize.py FILE"""
import collections, re, statistics as st, sys

text = open(sys.argv[1] if len(sys.argv) > 1 else "drift-sharing-ab.txt").read()
runs = []
for block in text.split("## ")[1:]:
    head = block.split("\n")[0]
    m = re.search(r"^\s+(\d+)\s+0\s+\S+\s+(\S+)(?:\s+\S+){4}\s+(\S+)", block, re.M)
    if not m:
        continue
    workload = "tiles" if "--tile" in head else "dense-88k" if "dense-88k" in head else "dense-11k"
    flag = lambda name: (re.search(name + r" (\S+)", head) or [None, "-"])[1]
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
    key = (workload, int(m.group(1)), flag("--steps"), flag("--drift-sharing"),
           flag("--chunk-tail"), flag("--chunks-per-thread"), flag("--owner-keeps-last"))
    runs.append((key, float(m.group(2)), m.group(3), stages))
groups = collections.defaultdict(list)
where = collections.defaultdict(list)  # the runs' places in the file
for place, (key, ns, h, stages) in enumerate(runs):
    groups[key].append((ns, h, stages))
    where[key].append(place)
names = ["drift", "drift wait", "contacts", "contacts wait", "gather", "gather wait", "step (sum)"]
for key, v in groups.items():
    ns = [r[0] for r in v]
    line = (f"{key[0]:9} {key[1]:2} thr {key[2]:>4} steps  drift {key[3]:6} tail {key[4]:9} "
            f"chunks/thread {key[5]:2} owner keeps last {key[6]:3}  ns/p-step ") + \
        " ".join(f"{x:.1f}" for x in ns) + f"  median {st.median(ns):.2f}  hash {set(r[1] for r in v)}"
    print(line)
    if v[0][2]:
        print("      stages: " + "  ".join(f"{n} {st.mean(r[2].get(n, 0.0) for r in v):.0f}" for n in names))
    # (the first variant of the same workload, thread count and steps whose runs lie among this
    # one's, preferably one that sets the same flags)
    given = lambda k: tuple(x != "-" for x in k[3:])
    among = [k2 for k2 in groups if k2[:3] == key[:3] and min(where[k2]) < min(where[key]) and
             min(where[key]) < max(where[k2])]
    same = [k2 for k2 in among if given(k2) == given(key)]
    base = groups[(same or among)[0]] if among else v
    if base is not v:
        ratios = [b[0] / x[0] for b, x in zip(base, v)]
        print("      per-round ratio against the first variant: " + " ".join(f"{r:.3f}" for r in ratios) +
              f"  median {st.median(ratios):.3f}")
