#!/bin/bash
# ABBA rounds: unchanged build and the original ring (overlay) on $1 threads; $2 rounds
T=$1; R=$2
M=/work/main/build/release/bench/grainlab_bench
H=/work/hack/build/release/bench/grainlab_bench
ARGS="dense-11k --tile 2x2x2 --cache-dir /work/main/build/release/bench-cache --threads $T --steps 500 --warmup 50 --reps 1 --no-csv"
tails=""; [ "$T" -gt 1 ] && tails="NO_TAILS=1"
a() { echo "== unchanged $(date -u +%T)"; $M $ARGS | tail -1; }
b() { echo "== ring15 overlay $(date -u +%T)"; env $tails RING_BITS=15 RING_OVERLAY=1 $H $ARGS | tail -1; }
for r in $(seq $R); do if [ $((r % 2)) = 1 ]; then a; b; else b; a; fi; done
