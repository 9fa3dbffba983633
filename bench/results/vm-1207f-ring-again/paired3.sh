#!/bin/bash
# sec. 55's two-thread protocol (--steps 1000 --warmup 100): unchanged (tails on), scratch with
# the tails off and no ring, scratch with the tails off and the ring of 2^15 (overlay, the
# original patch); orders A B C and C B A alternate; $1 rounds
R=$1
M=/work/main/build/release/bench/grainlab_bench
H=/work/hack/build/release/bench/grainlab_bench
ARGS="dense-11k --tile 2x2x2 --cache-dir /work/main/build/release/bench-cache --threads 2 --steps 1000 --warmup 100 --reps 1 --no-csv"
a() { echo "== unchanged $(date -u +%T)"; $M $ARGS | tail -1; }
b() { echo "== notails $(date -u +%T)"; env NO_TAILS=1 $H $ARGS | tail -1; }
c() { echo "== ring15 $(date -u +%T)"; env NO_TAILS=1 RING_BITS=15 RING_OVERLAY=1 $H $ARGS | tail -1; }
for r in $(seq $R); do if [ $((r % 2)) = 1 ]; then a; b; c; else c; b; a; fi; done
