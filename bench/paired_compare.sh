#!/bin/bash
# Two grainlab binaries (A: after a change, B: before it) run AT THE SAME TIME, one thread each,
# pinned to CPU 0 and CPU 1, the CPUs swapped every round. Use it on a 2-core machine whose speed
# drifts within minutes (the development VM: one binary 7.4 -> 11.9 s within minutes), where
# runs one after the other (bench/element_test_compare.sh) compare two different machines. Both
# runs see the same moment; what remains is the CPUs' own asymmetry (up to 1.4x on the VM,
# changing sign between rounds), which the swap cancels over a pair of rounds. So it prints every
# round's B/A, the geometric mean of each pair of rounds (CPU 0 and CPU 1 once each: the figure
# to read), the geometric mean over all rounds, and whether the outputs are byte-identical.
#   bench/paired_compare.sh run     A B CONFIG [ROUNDS]   element test: its loop's wall time
#                                                         (summary.json shearing_wall_time_s);
#                                                         compares curve.csv
#   bench/paired_compare.sh prepare A B CONFIG [ROUNDS]   preparation (specimen.json wall_time_s);
#                                                         compares specimen.csv
#   bench/paired_compare.sh bench   A B WORKLOAD [ROUNDS] two grainlab_bench binaries on a bench
#                                                         workload (dense-11k, ...): 1,000 steps
#                                                         after 200, ns per particle-step;
#                                                         compares the state hashes (packings
#                                                         cached in $GRAINLAB_BENCH_CACHE, by
#                                                         default build/release/bench-cache;
#                                                         docs/performance.md sec. 50)
# ROUNDS defaults to 4 (two pairs); an odd count is rounded up. Needs taskset (util-linux) and 2
# CPUs; nothing else heavy may run meanwhile. Not a thread-scaling measurement: one thread each.
# Example (short reference shear, see bench/element_test_compare.sh for the config):
#   bench/paired_compare.sh run build/release/apps/grainlab/grainlab /tmp/old/grainlab \
#       /tmp/shear-short.toml 6
set -euo pipefail
usage() {
  echo "usage: $0 run|prepare A_GRAINLAB B_GRAINLAB CONFIG [ROUNDS]" >&2
  echo "       $0 bench A_GRAINLAB_BENCH B_GRAINLAB_BENCH WORKLOAD [ROUNDS]" >&2
  exit 2
}
(($# >= 4)) || usage
mode=$1 a=$2 b=$3 config=$4 rounds=${5:-4}
case "$mode" in
  run) time_file=summary.json time_key=shearing_wall_time_s output=curve.csv ;;
  prepare) time_file=specimen.json time_key=wall_time_s output=specimen.csv ;;
  bench) output="state hash" ;;
  *) usage ;;
esac
for bin in "$a" "$b"; do [[ -x $bin ]] || { echo "$0: $bin: not an executable" >&2; exit 2; }; done
if [[ $mode == bench ]]; then
  cache=${GRAINLAB_BENCH_CACHE:-$(cd "$(dirname "$0")/.." && pwd)/build/release/bench-cache}
  mkdir -p "$cache"
else
  [[ -r $config ]] || { echo "$0: $config: cannot read the config" >&2; exit 2; }
fi
[[ $rounds =~ ^[1-9][0-9]*$ ]] || { echo "$0: ROUNDS: expected a positive integer, got '$rounds'" >&2; exit 2; }
(( rounds += rounds % 2 ))
(( $(nproc) >= 2 )) || { echo "$0: needs 2 CPUs, this machine has $(nproc)" >&2; exit 2; }
command -v taskset >/dev/null || { echo "$0: needs taskset (Debian package util-linux)" >&2; exit 2; }

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
seconds() {  # seconds DIR -> the run's own wall time (bench: ns per particle-step)
  if [[ $mode == bench ]]; then
    tail -n 1 "$1.log" | awk '{print $4}'
  else
    python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))[sys.argv[2]])' \
      "$1/$time_file" "$time_key"
  fi
}
launch() {  # launch CPU BINARY NAME: one thread, pinned; its log kept for a failure
  if [[ $mode == bench ]]; then
    # (the workload's last line: threads, rep, p-steps/s, ns/p-step, ..., state hash, ...)
    taskset -c "$1" "$2" "$config" --cache-dir "$cache" --threads 1 --steps 1000 --warmup 200 \
      --reps 1 --no-csv >"$work/$3.log" 2>&1
  else
    taskset -c "$1" "$2" "$mode" "$config" --out "$work/$3" --threads 1 --quiet --overwrite \
      >"$work/$3.log" 2>&1
  fi
}
same_output() {  # whether A's and B's outputs are the same bytes (bench: the same state hash)
  if [[ $mode == bench ]]; then
    [[ $(tail -n 1 "$work/A.log" | awk '{print $9}') == $(tail -n 1 "$work/B.log" | awk '{print $9}') ]]
  else
    cmp -s "$work/A/$output" "$work/B/$output"
  fi
}
same=identical
for ((r = 1; r <= rounds; ++r)); do
  if ((r % 2)); then cpu_a=0 cpu_b=1; else cpu_a=1 cpu_b=0; fi
  rm -rf "$work/A" "$work/B"
  launch "$cpu_a" "$a" A & pid_a=$!
  launch "$cpu_b" "$b" B & pid_b=$!
  status=0
  wait "$pid_a" || status=$?
  wait "$pid_b" || status=$((status ? status : $?))
  if ((status)); then
    echo "$0: round $r: a run failed (exit $status); its log:" >&2
    tail -n 5 "$work/A.log" "$work/B.log" >&2
    exit 1
  fi
  same_output || same=DIFFERENT
  echo "round $r of $rounds done" >&2
  echo "$r $cpu_a $(seconds "$work/A") $cpu_b $(seconds "$work/B")" >>"$work/rows"
done
python3 -c '
import math, sys
rows = [line.split() for line in open(sys.argv[1]) if line.strip()]
unit = sys.argv[2]
ratios = []
for r, cpu_a, a, cpu_b, b in rows:
    a, b = float(a), float(b)
    ratios.append(b / a)
    print(f"round {r}: A {a:.2f} {unit} (CPU {cpu_a})  B {b:.2f} {unit} (CPU {cpu_b})  B/A {b / a:.3f}")
geo = lambda xs: math.exp(sum(map(math.log, xs)) / len(xs))
pairs = [geo(ratios[k:k + 2]) for k in range(0, len(ratios) - 1, 2)]
print("pairs of rounds, B/A:", " ".join(f"{p:.3f}" for p in pairs))
print(f"all rounds, geometric mean B/A {geo(ratios):.3f} (> 1: A faster)")
' "$work/rows" "$([[ $mode == bench ]] && echo ns/p-step || echo s)"
echo "$output: $same"
