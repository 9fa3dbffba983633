#!/bin/bash
# device run 3 (2026-11-26 evening): thread scaling of d7f4664 on the lab's 88k plane strain
# specimen (dense-88k, 2 rounds) and on the 4x4x4 tiles of dense-11k (744,704 beads, 1 round).
export LD_LIBRARY_PATH=$PWD/.devlibs CACHE_DIR=.devlibs/cache
B=.devlibs/bins/head_bench; chmod +x $B
SPECIMEN_88K=.devlibs/spec88k/specimen.csv WORKLOADS="dense-88k" ROUNDS=2 bench/thread_scaling.sh $B /tmp/s88 2>&1 | tee $OUT/scaling-88k.txt
WORKLOADS="tile-4x4x4" ROUNDS=1 bench/thread_scaling.sh $B /tmp/s744 2>&1 | tee $OUT/scaling-744k.txt
cp /tmp/s88/*.csv $OUT/scaling-88k-rows.csv 2>/dev/null; cp /tmp/s744/*.csv $OUT/scaling-744k-rows.csv 2>/dev/null
true
