#!/bin/bash
# device run (2026-11-27): thread scaling of HEAD 60aaa66 (sec. 26-30 included) on 16 cores, the
# full-scale plane strain test to 0.5 % at 16 threads, and HEAD against 1478e3a (11-26 evening).
export LD_LIBRARY_PATH=$PWD/.devlibs CACHE_DIR=.devlibs/cache OMP_PLACES=cores OMP_PROC_BIND=close
D=.devlibs/bins; chmod +x $D/*
{ lscpu; nproc; free -g; } > $OUT/lscpu.txt 2>&1; grep -m1 "Model name" $OUT/lscpu.txt
mkdir -p /tmp/scal /tmp/scal4 /tmp/r
echo "== 1. thread scaling $(date +%T)"
WORKLOADS="dense-11k dense-88k tile-2x2x3" ROUNDS=2 timeout 230 bench/thread_scaling.sh $D/now_bench /tmp/scal 2>&1 | tee $OUT/scaling.txt
cp /tmp/scal/*.csv $OUT/scaling-rows.csv
echo "== 2. plane strain to 0.5 %, 16 threads $(date +%T)"
SECONDS=0; timeout 150 $D/now_grainlab run .devlibs/ps-short.toml --out /tmp/ps16 --threads 16 > $OUT/ps16.log 2>&1
echo "ps16 rc $? wall $SECONDS s"; grep -v "re-equilibrating\|loading:" $OUT/ps16.log | tail -3
cp /tmp/ps16/summary.json $OUT/ps16-summary.json; cp /tmp/ps16/curve.csv $OUT/ps16-curve.csv
echo "== 3. HEAD (now) against 1478e3a (head), interleaved $(date +%T)"
one() {  # one BIN WORKLOAD THREADS STEPS WARMUP [TILE]
  local ta=(); [ -z "${6:-}" ] || ta=(--tile $6)
  timeout 60 $D/$1_bench $2 "${ta[@]}" --threads $3 --reps 1 --steps $4 --warmup $5 --cache-dir $CACHE_DIR --results-dir /tmp/r 2>/dev/null | awk '$1 ~ /^[0-9]+$/ && NF >= 9 {print $3, $4, $9}'
}
{
for r in 1 2 3; do o="head now"; ((r % 2)) || o="now head"
  for b in $o; do echo "t1-11k $b round $r: $(one $b dense-11k 1 2000 100)"; done; done
for r in 1 2 3; do o="head now"; ((r % 2)) || o="now head"
  for b in $o; do echo "t16-tile $b round $r: $(one $b dense-11k 16 400 50 2x2x3)"; done; done
} 2>&1 | tee $OUT/ab.txt
echo "== 4. 4x4x4 tiles, 1 round $(date +%T)"
WORKLOADS="tile-4x4x4" ROUNDS=1 timeout 100 bench/thread_scaling.sh $D/now_bench /tmp/scal4 2>&1 | tail -8 | tee $OUT/scaling-744k.txt
echo "end $(date +%T)"
