#!/bin/bash
# device run (2026-11-26): thread scaling of HEAD (226fe22), then the full-scale plane strain
# at 16 threads: loading to 0.5 % from the VM's 88k specimen, then the preparation (capped).
export LD_LIBRARY_PATH=$PWD/.devlibs
G=build/release/apps/grainlab/grainlab B=build/release/bench/grainlab_bench
chmod +x $G $B
{ lscpu; nproc; free -g; } > $OUT/lscpu.txt 2>&1
head -20 $OUT/lscpu.txt
mkdir -p $OUT/scal
WORKLOADS="dense-11k tile-2x2x3" ROUNDS=2 CACHE_DIR=.devlibs/cache bench/thread_scaling.sh $B $OUT/scal 2>&1 | tee $OUT/scaling.txt
echo "== plane strain loading to 0.5 %, 16 threads"
SECONDS=0; OMP_PLACES=cores OMP_PROC_BIND=close $G run .devlibs/ps-short.toml --out /tmp/ps16 --threads 16 > $OUT/ps16.log 2>&1
echo "ps16 rc $? wall ${SECONDS} s"; tail -4 $OUT/ps16.log
cp /tmp/ps16/summary.json $OUT/ps16-summary.json
echo "== plane strain preparation, 16 threads (capped at 290 s)"
OMP_PLACES=cores OMP_PROC_BIND=close timeout 290 $G prepare examples/plane_strain/reference.toml --out /tmp/prep16 --threads 16 > $OUT/prep16.log 2>&1
echo "prepare rc $?"; tail -3 $OUT/prep16.log
cp /tmp/prep16/specimen.json $OUT/prep16-specimen.json 2>/dev/null
true
