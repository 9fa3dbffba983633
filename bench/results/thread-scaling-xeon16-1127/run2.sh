#!/bin/bash
# device run 2 (2026-11-27): the one sweep (--one-sweep always) against the stages (never, what
# automatic does above 2 threads) at 8 and 16 threads, HEAD 60aaa66, interleaved rounds.
export LD_LIBRARY_PATH=$PWD/.devlibs CACHE_DIR=.devlibs/cache OMP_PLACES=cores OMP_PROC_BIND=close
D=.devlibs/bins; chmod +x $D/*; mkdir -p /tmp/r
one() {  # one MODE WORKLOAD THREADS STEPS WARMUP [TILE]
  local ta=(); [ -z "${6:-}" ] || ta=(--tile $6)
  timeout 60 $D/now_bench $2 "${ta[@]}" --one-sweep $1 --threads $3 --reps 1 --steps $4 --warmup $5 --cache-dir $CACHE_DIR --results-dir /tmp/r 2>/dev/null | awk '$1 ~ /^[0-9]+$/ && NF >= 9 {print $3, $4, $9}'
}
{
for r in 1 2 3; do o="never always"; ((r % 2)) || o="always never"
  for t in 16 8; do
    for m in $o; do echo "tile-2x2x3 t$t $m round $r: $(one $m dense-11k $t 400 50 2x2x3)"; done
    for m in $o; do echo "dense-88k t$t $m round $r: $(one $m dense-88k $t 600 50)"; done
  done
done
for r in 1 2; do o="never always"; ((r % 2)) || o="always never"
  for m in $o; do echo "tile-4x4x4 t16 $m round $r: $(one $m dense-11k 16 60 10 4x4x4)"; done
  for m in $o; do echo "dense-11k t16 $m round $r: $(one $m dense-11k 16 2000 100)"; done
done
for m in never always; do echo "tile-2x2x3 t1 $m: $(one $m dense-11k 1 400 50 2x2x3)"; done
} 2>&1 | tee $OUT/one-sweep-16.txt
echo "end $(date +%T)"
