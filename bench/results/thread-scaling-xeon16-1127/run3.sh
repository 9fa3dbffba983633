#!/bin/bash
# device run 3 (2026-11-27): where 16 threads spend a step. 60aaa66 with scratch timers per thread
# and stage (the patch in bench/results/thread-scaling-xeon16-1127/phase-times.patch).
export LD_LIBRARY_PATH=$PWD/.devlibs CACHE_DIR=.devlibs/cache OMP_PLACES=cores OMP_PROC_BIND=close
D=.devlibs/bins; chmod +x $D/*
one() {  # WORKLOAD THREADS STEPS WARMUP [TILE]
  local ta=(); [ -z "${5:-}" ] || ta=(--tile $5)
  echo "== $1 ${5:-} threads $2"
  timeout 60 $D/phase_bench $1 "${ta[@]}" --one-sweep never --threads $2 --reps 1 --steps $3 --warmup $4 --cache-dir $CACHE_DIR --no-csv 2>&1 | grep -v "^workload\|^threads"
}
{
for t in 1 16 8 4 2; do one dense-11k $t 400 50 2x2x3; done
for t in 1 16; do one dense-88k $t 600 50; done
for t in 1 16; do one dense-11k $t 2000 100; done
one dense-11k 16 400 50 2x2x3
} 2>&1 | tee $OUT/phase.txt
