#!/bin/bash
# dense-11k itself (11,636 beads, its data inside the L3): A against B8, rounds of A B8 / B8 A.
A=/work/main/build/release/bench/grainlab_bench
H=/work/hack/build/release/bench/grainlab_bench
COMMON="dense-11k --cache-dir /work/main/build/release/bench-cache --steps 4000 --warmup 100 --reps 1 --no-csv --gather-walk flat"
for round in 1 2 3 4; do
  for t in 2 1; do
    if [ $((round % 2)) = 1 ]; then order="A B8"; else order="B8 A"; fi
    for c in $order; do
      case $c in
        A) echo "A t=$t $($A $COMMON --threads $t 2>&1 | tail -1 | tr -s ' ')" ;;
        B8) echo "B8 t=$t $(GRAINLAB_TWO_STEP=8 GRAINLAB_PIPE=1 $H $COMMON --threads $t 2>&1 | tail -1 | tr -s ' ')" ;;
      esac
    done
  done
done
