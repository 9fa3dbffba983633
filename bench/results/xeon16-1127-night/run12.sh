#!/bin/bash
# device run 12 (2026-11-27 night): the drift through a chunk queue (--drift-sharing) and the
# chunk tails at 16 threads, A/B interleaved; efficiency 1 vs 16 threads; ps-short new vs HEAD.
export LD_LIBRARY_PATH=$PWD/.devlibs OMP_PLACES=cores OMP_PROC_BIND=close
D=.devlibs/bins C=.devlibs/cache; chmod +x $D/*
o=$OUT/ab.txt
b() { echo "## $*" >> $o; timeout 60 $D/new_bench --cache-dir $C --reps 1 --no-csv "$@" >> $o 2>&1; }
T="dense-11k --tile 2x2x3"
for r in 1 2 3 4 5; do for v in "never even" "always even" "never shrinking" "always shrinking"; do set -- $v
  b $T --threads 16 --steps 620 --warmup 30 --phase-times --drift-sharing $1 --chunk-tail $2; done; done
echo "part1 done $SECONDS" >> $o
for r in 1 2 3 4; do for v in "never even" "always even" "never shrinking" "always shrinking"; do set -- $v
  b dense-88k --threads 16 --steps 1000 --warmup 30 --phase-times --drift-sharing $1 --chunk-tail $2; done; done
echo "part2 done $SECONDS" >> $o
for r in 1 2 3; do for t in 4 8; do for v in never always; do
  b $T --threads $t --steps 400 --warmup 30 --phase-times --drift-sharing $v; done; done; done
echo "part3 done $SECONDS" >> $o
for r in 1 2 3; do
  b $T --threads 1 --steps 150 --warmup 10; b $T --threads 16 --steps 600 --warmup 30
  b dense-88k --threads 1 --steps 200 --warmup 10; b dense-88k --threads 16 --steps 900 --warmup 30; done
echo "part4 done $SECONDS" >> $o
for g in new cur; do S=$SECONDS
  timeout 90 $D/${g}_grainlab run .devlibs/ps-short.toml --out /tmp/ps-$g --overwrite --threads 16 --quiet > /tmp/ps-$g.log 2>&1
  echo "ps $g rc $? wall $((SECONDS-S)) s $(md5sum < /tmp/ps-$g/curve.csv)" >> $o
  python3 -c "import json; d=json.load(open('/tmp/ps-$g/summary.json')); print('ps $g', d['preparation_wall_time_s'], d['shearing_wall_time_s'], d['steps'], d['neighbor_list_refreshes'])" >> $o 2>&1
done
echo "all done $SECONDS" >> $o
