#!/bin/bash
# one interleaved round: unchanged build, ring, ring + write-through; threads $1
T=$1
M=/work/main/build/release/bench/grainlab_bench
H=/work/hack/build/release/bench/grainlab_bench
ARGS="dense-11k --tile 2x2x2 --cache-dir /work/main/build/release/bench-cache --threads $T --steps 500 --warmup 50 --reps 1 --no-csv"
tails=""; [ "$T" -gt 1 ] && tails="NO_TAILS=1"
echo "== unchanged"; $M $ARGS | tail -1
echo "== ring15"; env $tails RING_BITS=15 $H $ARGS | tail -1
echo "== ring15+wt"; env $tails RING_BITS=15 RING_WT=1 $H $ARGS | tail -1
[ "$T" -gt 1 ] && { echo "== notails"; env NO_TAILS=1 $H $ARGS | tail -1; }
true
