#!/bin/bash
# device run 13 (2026-11-27 night): chunk sharing at 8 and 16 threads, A/B interleaved:
# --owner-keeps-last yes/no x --chunks-per-thread 8/16 (drift shared, the default at 16); then
# the drift shared or not, more rounds.
export LD_LIBRARY_PATH=$PWD/.devlibs OMP_PLACES=cores OMP_PROC_BIND=close
D=.devlibs/bins C=.devlibs/cache; chmod +x $D/*
o=$OUT/ab2.txt
b() { echo "## $*" >> $o; timeout 60 $D/new2_bench --cache-dir $C --reps 1 --no-csv --phase-times "$@" >> $o 2>&1; }
T="dense-11k --tile 2x2x3"
V=("yes 8" "no 8" "yes 16" "no 16")
for r in 1 2 3 4 5 6; do for v in "${V[@]}"; do set -- $v
  b $T --threads 16 --steps 620 --warmup 30 --owner-keeps-last $1 --chunks-per-thread $2; done; done
echo "part1 done $SECONDS" >> $o
for r in 1 2 3 4 5; do for v in "${V[@]}"; do set -- $v
  b dense-88k --threads 16 --steps 1000 --warmup 30 --owner-keeps-last $1 --chunks-per-thread $2; done; done
echo "part2 done $SECONDS" >> $o
for r in 1 2 3; do for v in "${V[@]}"; do set -- $v
  b $T --threads 8 --steps 400 --warmup 30 --owner-keeps-last $1 --chunks-per-thread $2; done; done
echo "part3 done $SECONDS" >> $o
for r in 1 2 3 4 5; do for d in never always; do
  b $T --threads 16 --steps 620 --warmup 30 --drift-sharing $d
  b dense-88k --threads 16 --steps 1000 --warmup 30 --drift-sharing $d; done; done
echo "all done $SECONDS" >> $o
