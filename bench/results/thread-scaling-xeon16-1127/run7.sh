#!/bin/bash
# device run 7 (2026-11-27): the serial time of a 16-thread step, split into the master's three
# stretches outside the regions (920d30f's walls' totals, scratch timers).
export LD_LIBRARY_PATH=$PWD/.devlibs OMP_PLACES=cores OMP_PROC_BIND=close
D=.devlibs/bins; chmod +x $D/*
{
for r in 1 2; do echo "== tile 16 threads round $r"
  timeout 60 $D/phases_bench dense-11k --tile 2x2x3 --one-sweep never --threads 16 --reps 1 --steps 400 --warmup 50 --cache-dir .devlibs/cache --no-csv 2>&1 | grep -v "^workload\|^threads\|^packing"; done
echo "== dense-88k 16 threads"
timeout 60 $D/phases_bench dense-88k --one-sweep never --threads 16 --reps 1 --steps 600 --warmup 50 --cache-dir .devlibs/cache --no-csv 2>&1 | grep -v "^workload\|^threads\|^packing"
echo "== tile 1 thread"
timeout 60 $D/phases_bench dense-11k --tile 2x2x3 --one-sweep never --threads 1 --reps 1 --steps 200 --warmup 20 --cache-dir .devlibs/cache --no-csv 2>&1 | grep -v "^workload\|^threads\|^packing"
} 2>&1 | tee $OUT/phase-serial.txt
