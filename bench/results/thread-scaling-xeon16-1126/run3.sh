#!/bin/bash
# device run 3 (2026-11-26): thread scaling of the lab's 88k specimen, then the 744,704-bead tiles
export LD_LIBRARY_PATH=$PWD/.devlibs CACHE_DIR=.devlibs/cache
B=build/release/bench/grainlab_bench; chmod +x $B
WORKLOADS="dense-88k" ROUNDS=2 bench/thread_scaling.sh $B /tmp/s88 2>&1 | tee $OUT/scaling-88k.txt
WORKLOADS="tile-4x4x4" ROUNDS=1 bench/thread_scaling.sh $B /tmp/s744 2>&1 | tee $OUT/scaling-744k.txt
