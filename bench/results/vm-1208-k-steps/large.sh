#!/bin/bash
# The 745k cube (dense-11k --tile 4x4x4, 744,704 beads), 2 threads, 300 steps after 30 of
# warm-up: A against the pipeline at k = 4 and 8, rounds of A B4 B8 / B8 B4 A.
A=/work/main/build/release/bench/grainlab_bench
H=/work/hack/build/release/bench/grainlab_bench
COMMON="dense-11k --tile 4x4x4 --cache-dir /work/main/build/release/bench-cache --steps 300 --warmup 30 --reps 1 --no-csv --gather-walk flat --threads 2"
for round in 1 2 3; do
  if [ $((round % 2)) = 1 ]; then order="A B4 B8"; else order="B8 B4 A"; fi
  for c in $order; do
    case $c in
      A) echo "A t=2 $($A $COMMON 2>&1 | tail -1 | tr -s ' ')" ;;
      B4) echo "B4 t=2 $(GRAINLAB_TWO_STEP=4 GRAINLAB_PIPE=1 $H $COMMON 2>&1 | tail -1 | tr -s ' ')" ;;
      B8) echo "B8 t=2 $(GRAINLAB_TWO_STEP=8 GRAINLAB_PIPE=1 $H $COMMON 2>&1 | tail -1 | tr -s ' ')" ;;
    esac
  done
done
