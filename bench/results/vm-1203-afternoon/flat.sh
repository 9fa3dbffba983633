#!/bin/bash
# flatness on this host: interleaved rounds, 1 and 2 threads, tiles of dense-11k
b=bench/grainlab_bench
for round in 1 2 3; do
  for t in 1 2; do
    for tile in 1x1x1 2x2x2 2x2x3 4x4x4; do
      case $tile in 1x1x1) s=2000;; 2x2x2) s=300;; 2x2x3) s=200;; 4x4x4) s=40;; esac
      [ $t = 2 ] && s=$((s*2))
      line=$(OMP_PROC_BIND=true $b dense-11k --cache-dir bench-cache --tile $tile --threads $t --reps 1 --steps $s --warmup 20 --no-csv 2>&1 | awk '$1 ~ /^[0-9]+$/ && NF >= 9')
      echo "round $round tile $tile threads $t steps $s: $line"
    done
  done
done
