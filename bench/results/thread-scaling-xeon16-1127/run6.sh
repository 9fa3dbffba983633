#!/bin/bash
# device run 6 (2026-11-27): the clock's cost, and per-stage times with the walls' totals after
# the region (phase) and inside it (phasewt), tile 2x2x3.
export LD_LIBRARY_PATH=$PWD/.devlibs OMP_PLACES=cores OMP_PROC_BIND=close
D=.devlibs/bins; chmod +x $D/*
{
cat /sys/devices/system/clocksource/clocksource0/current_clocksource
$D/wtime; $D/wtime
for r in 1 2; do for b in phase phasewt; do
  echo "== $b 16 threads round $r"
  timeout 60 $D/${b}_bench dense-11k --tile 2x2x3 --one-sweep never --threads 16 --reps 1 --steps 400 --warmup 50 --cache-dir .devlibs/cache --no-csv 2>&1 | grep -v "^workload\|^threads\|^packing"
done; done
for b in phase phasewt; do
  echo "== $b 1 thread"
  timeout 60 $D/${b}_bench dense-11k --tile 2x2x3 --one-sweep never --threads 1 --reps 1 --steps 200 --warmup 20 --cache-dir .devlibs/cache --no-csv 2>&1 | grep -v "^workload\|^threads\|^packing"
done
} 2>&1 | tee $OUT/phase-wt.txt
