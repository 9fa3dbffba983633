#!/bin/bash
# Two grainlab binaries (A: after a change, B: before it) on one element-test config, interleaved
# (A B, then B A, ...) for ROUNDS rounds. Each run's time is the loop's own "wall time" line
# (preparation or specimen reading, plot and summary left out). Prints every round, the medians
# and the median of the per-round ratios B/A (the speed-up of A), and whether the last runs'
# curve.csv are byte-identical (the same bits).
#   bench/element_test_compare.sh A_GRAINLAB B_GRAINLAB CONFIG [ROUNDS] [THREADS]
#   e.g. a short reference shear: copy examples/triaxial/reference.toml, set
#   max_axial_strain = 0.004 and specimen = "<dir>/specimen.csv" (from `grainlab prepare`), then
#   bench/element_test_compare.sh build/release/apps/grainlab/grainlab /tmp/old/grainlab \
#       /tmp/shear-short.toml 4 2
set -euo pipefail
a=$1 b=$2 config=$3 rounds=${4:-4} threads=${5:-2}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
one() {  # one BINARY NAME -> seconds
  rm -rf "$work/$2"
  "$1" run "$config" --out "$work/$2" --threads "$threads" 2>&1 |
    awk '/wall time/ {for (k = 1; k < NF; ++k) if ($k == "time") {print $(k + 1); exit}}'
}
for ((r = 1; r <= rounds; ++r)); do
  if ((r % 2)); then ta=$(one "$a" A); tb=$(one "$b" B); else tb=$(one "$b" B); ta=$(one "$a" A); fi
  echo "$r $ta $tb"
done | python3 -c '
import statistics, sys
rows = [tuple(map(float, line.split()[1:])) for line in sys.stdin if line.strip()]
for k, (a, b) in enumerate(rows, 1):
    print(f"round {k}: A {a:.1f} s  B {b:.1f} s  B/A {b / a:.3f}")
print(f"median A {statistics.median(a for a, _ in rows):.1f} s  B {statistics.median(b for _, b in rows):.1f} s"
      f"  B/A {statistics.median(b / a for a, b in rows):.3f} (speed-up of A)")
'
if cmp -s "$work/A/curve.csv" "$work/B/curve.csv"; then echo "curve.csv identical"; else echo "curve.csv DIFFERS"; fi
