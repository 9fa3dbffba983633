#!/usr/bin/env bash
# What a session on a many-core machine measures in one command (about 4 minutes on a 16-core
# Xeon; docs/performance.md sec. 33): where the threads of a step spend their time, whether the
# force stages' shrinking chunk tails pay, and the list updates at every thread count.
#   1. 139,632 beads (dense-11k in 2x2x3 tiles), 1 thread, then the largest thread count with
#      --phase-times, chunk tails even and shrinking in turn, the largest thread count with the
#      chunks of fewer than 8 threads (sec. 34), with the drift's blocks whole, and with every
#      possible step as one sweep (its blocks' tails shared), ROUNDS rounds (default 2);
#   2. the list's refresh and rebuild at 1, 2, 4 ... threads (--refresh-cost 20 --rebuild-cost 5);
#   3. with GRAINLAB and PS_CONFIG set: that plane strain config (e.g. the reference test cut to
#      max_axial_strain = 0.005) on the largest thread count, its curve's md5 and the stages' times
#      from its summary.json.
#   bench/device_check.sh BENCH [OUT_DIR]
#   env: CACHE_DIR (packings, default build/bench-cache), ROUNDS, MAX_THREADS (default: all
#   processors), GRAINLAB (the grainlab binary), PS_CONFIG (a plane strain config)
# Each run prints its state hash: the same for every thread count and chunk tail.
set -euo pipefail
bench=${1:?usage: bench/device_check.sh BENCH [OUT_DIR]}
out=${2:-build/device-check}
cache=${CACHE_DIR:-build/bench-cache} rounds=${ROUNDS:-2}
procs=${MAX_THREADS:-$(nproc)}
mkdir -p "$out" "$cache"
export OMP_PLACES=${OMP_PLACES:-cores} OMP_PROC_BIND=${OMP_PROC_BIND:-close}
[[ -x $bench ]] || { echo "$bench: not an executable grainlab_bench" >&2; exit 2; }
if [[ -n ${PS_CONFIG:-} ]]; then
  [[ -f $PS_CONFIG ]] || { echo "PS_CONFIG=$PS_CONFIG: no such file" >&2; exit 2; }
  [[ -x ${GRAINLAB:-} ]] || { echo "PS_CONFIG needs GRAINLAB, the grainlab binary" >&2; exit 2; }
fi
run() { "$bench" dense-11k --tile 2x2x3 --cache-dir "$cache" --reps 1 --no-csv "$@"; }
{
  echo "machine: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs), $(nproc) processors"
  echo "== 1. stages per thread, 139,632 beads"
  for r in $(seq 1 "$rounds"); do
    for tail in even shrinking; do
      for t in 1 "$procs"; do
        steps=$((t == 1 ? 100 : 600))
        echo "-- round $r, $t threads, chunk tail $tail, $steps steps"
        run --threads "$t" --steps "$steps" --warmup 20 --phase-times --chunk-tail "$tail"
      done
      # the chunks of fewer than 8 threads (8 a block, the owner's last kept; sec. 34)
      echo "-- round $r, $procs threads, chunk tail $tail, 8 chunks a block kept, 600 steps"
      run --threads "$procs" --steps 600 --warmup 20 --phase-times --chunk-tail "$tail" \
        --chunks-per-thread 8 --owner-keeps-last yes
      # the drift's blocks whole (the drift shares its chunks from 4 threads; sec. 34)
      echo "-- round $r, $procs threads, chunk tail $tail, drift not shared, 600 steps"
      run --threads "$procs" --steps 600 --warmup 20 --phase-times --chunk-tail "$tail" \
        --drift-sharing never
      # every possible step as one sweep, with its shared tails (automatic keeps it to 2 threads)
      echo "-- round $r, $procs threads, one sweep always, chunk tail $tail, 600 steps"
      run --threads "$procs" --steps 600 --warmup 20 --phase-times --chunk-tail "$tail" \
        --one-sweep always
    done
  done
  echo "== 2. list updates, 139,632 beads"
  t=1
  while ((t <= procs)); do
    echo "-- $t threads"
    run --threads "$t" --steps 10 --warmup 20 --refresh-cost 20 --rebuild-cost 5
    t=$((t * 2))
  done
  if [[ -n ${PS_CONFIG:-} ]]; then
    echo "== 3. $PS_CONFIG on $procs threads"
    SECONDS=0
    "$GRAINLAB" run "$PS_CONFIG" --out "$out/plane-strain" --overwrite --threads "$procs" --quiet
    echo "wall time $SECONDS s"
    md5sum "$out/plane-strain/curve.csv"
    python3 -c "import json, sys; d = json.load(open(sys.argv[1])); \
print({k: v for k, v in d.items() if k.endswith('wall_time_s') or k in ('steps', 'neighbor_list_refreshes')})" \
      "$out/plane-strain/summary.json"
  fi
} 2>&1 | tee "$out/device-check.txt"
