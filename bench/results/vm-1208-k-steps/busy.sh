#!/bin/bash
# A fixed team of 2 beside a busy loop pinned to CPU 1: the unchanged build (A) against k = 8 steps
# per pass as a pipeline (B8), whose threads spin while they wait for the other's step.
A=/work/main/build/release/bench/grainlab_bench
H=/work/hack/build/release/bench/grainlab_bench
COMMON="dense-11k --tile 2x2x2 --cache-dir /work/main/build/release/bench-cache --steps 500 --warmup 50 --reps 1 --no-csv --gather-walk flat --threads 2"
taskset -c 1 bash -c 'while :; do :; done' & LOOP=$!
for c in A B8 B8 A; do
  case $c in
    A) echo "A busy $(timeout 300 $A $COMMON 2>&1 | tail -1 | tr -s ' ')" ;;
    B8) echo "B8 busy $(GRAINLAB_TWO_STEP=8 GRAINLAB_PIPE=1 timeout 300 $H $COMMON 2>&1 | tail -1 | tr -s ' ')" ;;
  esac
done
kill $LOOP
