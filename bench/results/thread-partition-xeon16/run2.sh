#!/bin/bash
# device run 2 (2026-11-26 evening): the pair kernel's lane masks, unrolled result stores and
# spring stores ("all"), and those with two divisions fewer per batch ("div"), against HEAD
# 1478e3a ("base"). Interleaved rounds, order rotated each round.
export LD_LIBRARY_PATH=$PWD/.devlibs CACHE_DIR=.devlibs/cache OMP_PLACES=cores OMP_PROC_BIND=close
D=.devlibs/bins; chmod +x $D/*
lscpu | grep -m1 "Model name"
one() {  # one BIN WORKLOAD THREADS STEPS WARMUP [TILE]
  local ta=(); [ -z "${6:-}" ] || ta=(--tile $6)
  $D/$1_bench $2 "${ta[@]}" --threads $3 --reps 1 --steps $4 --warmup $5 --cache-dir $CACHE_DIR --results-dir /tmp/r 2>/dev/null | awk '$1 ~ /^[0-9]+$/ && NF >= 9 {print $4, $9}'
}
for r in 1 2 3 4 5 6; do
  case $((r % 3)) in 0) o="base all div";; 1) o="all div base";; 2) o="div base all";; esac
  for b in $o; do echo "t1 $b round $r: $(one $b dense-11k 1 2000 100)"; done
done
for r in 1 2 3 4; do
  case $((r % 3)) in 0) o="base all div";; 1) o="all div base";; 2) o="div base all";; esac
  for b in $o; do echo "t2 $b round $r: $(one $b dense-11k 2 2000 100)"; done
done
for r in 1 2 3 4; do
  o="base div"; ((r % 2)) || o="div base"
  for b in $o; do echo "t16tile $b round $r: $(one $b dense-11k 16 400 50 2x2x3)"; done
done
for r in 1 2 3; do
  o="base div"; ((r % 2)) || o="div base"
  for b in $o; do
    rm -rf /tmp/ss-$b
    echo "shear2 $b round $r: $($D/${b}_grainlab run .devlibs/shear/shear-short.toml --out /tmp/ss-$b --threads 2 2>&1 | grep -o 'wall time [0-9.]* s' | head -1)"
  done
  cmp /tmp/ss-base/curve.csv /tmp/ss-div/curve.csv && echo "shear curves identical"
done
