#!/bin/bash
# device run 4 (2026-11-27): the walls' totals inside the force region ("wt") against 60aaa66
# ("now"), interleaved, order alternating.
export LD_LIBRARY_PATH=$PWD/.devlibs CACHE_DIR=.devlibs/cache OMP_PLACES=cores OMP_PROC_BIND=close
D=.devlibs/bins; chmod +x $D/*
one() {  # BIN WORKLOAD THREADS STEPS WARMUP [TILE]
  local ta=(); [ -z "${6:-}" ] || ta=(--tile $6)
  timeout 60 $D/$1_bench $2 "${ta[@]}" --threads $3 --reps 1 --steps $4 --warmup $5 --cache-dir $CACHE_DIR --no-csv 2>/dev/null | awk '$1 ~ /^[0-9]+$/ && NF >= 9 {print $3, $4, $9}'
}
{
for r in 1 2 3 4 5; do o="now wt"; ((r % 2)) || o="wt now"
  for b in $o; do echo "tile-2x2x3 t16 $b round $r: $(one $b dense-11k 16 400 50 2x2x3)"; done
  for b in $o; do echo "dense-88k t16 $b round $r: $(one $b dense-88k 16 600 50)"; done
done
for r in 1 2 3; do o="now wt"; ((r % 2)) || o="wt now"
  for b in $o; do echo "tile-2x2x3 t8 $b round $r: $(one $b dense-11k 8 400 50 2x2x3)"; done
done
for r in 1 2; do o="now wt"; ((r % 2)) || o="wt now"
  for b in $o; do echo "tile-4x4x4 t16 $b round $r: $(one $b dense-11k 16 60 10 4x4x4)"; done
done
} 2>&1 | tee $OUT/wall-totals-16.txt
