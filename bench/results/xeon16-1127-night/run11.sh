#!/bin/bash
# device run 11 (2026-11-27 night): 9573374 (HEAD) thread scaling 1..16 and device_check.sh
export LD_LIBRARY_PATH=$PWD/.devlibs OMP_PLACES=cores OMP_PROC_BIND=close
D=.devlibs/bins; chmod +x $D/* bench/*.sh
lscpu | grep -E 'Model name|^CPU\(s\)|Thread|Socket|NUMA node|L3' > $OUT/lscpu.txt
CACHE_DIR=.devlibs/cache ROUNDS=2 WORKLOADS="tile-2x2x3 dense-88k dense-11k" \
  timeout 260 bench/thread_scaling.sh $D/cur_bench /tmp/scaling > $OUT/scaling.txt 2>&1
echo "scaling rc $?"; cp /tmp/scaling/*.csv $OUT/scaling.csv
CACHE_DIR=.devlibs/cache ROUNDS=1 GRAINLAB=$D/cur_grainlab PS_CONFIG=.devlibs/ps-short.toml \
  timeout 220 bench/device_check.sh $D/cur_bench /tmp/check > /dev/null 2>&1
echo "check rc $?"; cp /tmp/check/device-check.txt $OUT/; cp /tmp/check/plane-strain/summary.json $OUT/ps-summary.json
ls -l $OUT
