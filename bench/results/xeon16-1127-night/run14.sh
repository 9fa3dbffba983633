#!/bin/bash
# device run 14 (2026-11-27 night): the automatic chunk sharing (16 chunks per thread, the owner's
# last given up, on 8 threads or more) against the old one (8, kept), 16 threads, interleaved;
# efficiency 1 vs 16 threads; the plane strain test to 0.5 % at the new defaults.
export LD_LIBRARY_PATH=$PWD/.devlibs OMP_PLACES=cores OMP_PROC_BIND=close
D=.devlibs/bins C=.devlibs/cache; chmod +x $D/*
o=$OUT/ab3.txt
b() { echo "## $*" >> $o; timeout 60 $D/new3_bench --cache-dir $C --reps 1 --no-csv "$@" >> $o 2>&1; }
T="dense-11k --tile 2x2x3"
for r in 1 2 3 4 5; do
  b $T --threads 16 --steps 620 --warmup 30 --chunks-per-thread 8 --owner-keeps-last yes
  b $T --threads 16 --steps 620 --warmup 30
  b dense-88k --threads 16 --steps 1000 --warmup 30 --chunks-per-thread 8 --owner-keeps-last yes
  b dense-88k --threads 16 --steps 1000 --warmup 30; done
echo "part1 done $SECONDS" >> $o
for r in 1 2 3; do
  b $T --threads 1 --steps 150 --warmup 10; b $T --threads 16 --steps 600 --warmup 30
  b dense-88k --threads 1 --steps 200 --warmup 10; b dense-88k --threads 16 --steps 900 --warmup 30; done
echo "part2 done $SECONDS" >> $o
S=$SECONDS; timeout 80 $D/new3_grainlab run .devlibs/ps-short.toml --out /tmp/ps-n --overwrite --threads 16 --quiet > /tmp/ps-n.log 2>&1
echo "ps new3 rc $? wall $((SECONDS-S)) s $(md5sum < /tmp/ps-n/curve.csv)" >> $o
python3 -c "import json; d=json.load(open('/tmp/ps-n/summary.json')); print('ps new3', d['preparation_wall_time_s'], d['shearing_wall_time_s'], d['steps'], d['neighbor_list_refreshes'])" >> $o 2>&1
echo "all done $SECONDS" >> $o
