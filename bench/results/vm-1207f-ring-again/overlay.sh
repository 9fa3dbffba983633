#!/bin/bash
T=$1
M=/work/main/build/release/bench/grainlab_bench
H=/work/hack/build/release/bench/grainlab_bench
ARGS="dense-11k --tile 2x2x2 --cache-dir /work/main/build/release/bench-cache --threads $T --steps 500 --warmup 50 --reps 1 --no-csv"
echo "== unchanged"; $M $ARGS | tail -1
echo "== ring15 appended"; env RING_BITS=15 $H $ARGS | tail -1
echo "== ring15 overlay"; env RING_BITS=15 RING_OVERLAY=1 $H $ARGS | tail -1
