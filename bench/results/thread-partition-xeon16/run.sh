#!/bin/bash
# device run (2026-11-26 evening): the thread partition (924681d, sec. 24) at 16 threads.
# B = HEAD build (build/release), A = ffd851a (before the partition, .devlibs/A).
export LD_LIBRARY_PATH=$PWD/.devlibs CACHE_DIR=.devlibs/cache
export OMP_PLACES=cores OMP_PROC_BIND=close
B=build/release/bench/grainlab_bench A=.devlibs/A/grainlab_bench
chmod +x $A $B build/release/apps/grainlab/grainlab
{ lscpu; nproc; free -g; } > $OUT/lscpu.txt 2>&1
grep -m1 "Model name" $OUT/lscpu.txt
echo "== A/B at 16 threads, interleaved (A B B A ...)"
for r in 1 2 3; do
  for w in "dense-11k|2000|100|" "dense-11k|400|50|2x2x3"; do
    IFS='|' read -r wl st wu tile <<<"$w"; ta=(); [ -z "$tile" ] || ta=(--tile $tile)
    order="A B"; ((r % 2 == 0)) && order="B A"
    for which in $order; do
      bin=$A; [ $which = B ] && bin=$B
      line=$($bin $wl "${ta[@]}" --threads 16 --reps 1 --steps $st --warmup $wu --cache-dir $CACHE_DIR --results-dir /tmp/ab 2>/dev/null | awk '$1 ~ /^[0-9]+$/ && NF >= 9')
      echo "ab $which $wl$tile round $r: $line"
    done
  done
done 2>&1 | tee $OUT/ab16.txt
echo "== thread scaling of B"
WORKLOADS="dense-11k tile-2x2x3" ROUNDS=2 bench/thread_scaling.sh $B $OUT/scal 2>&1 | tee $OUT/scaling.txt
true
