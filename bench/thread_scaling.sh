#!/bin/bash
# Thread scaling of the step loop. grainlab_bench runs dense-11k, mirrored tiles of it
# (2x2x3: 139,632 beads; 4x4x4: 744,704 beads) and, where it is cached, the lab's own 88,400-bead
# plane strain specimen (dense-88k) at 1, 2, 4, 8, 16 ... threads (powers of two up
# to the machine's processors, and the processor count itself), one thread per core
# (OMP_PLACES=cores, OMP_PROC_BIND=close unless set). Rounds are interleaved: each round runs
# every thread count once. Prints each run, then per workload and thread count the median
# rate, the speed-up and parallel efficiency against 1 thread, ns per particle-step, and whether
# every run of the workload ended in the same state hash (bit-identical results for any thread
# count). Rows go to OUT_DIR/<hostname>.csv as grainlab_bench writes them.
#   bench/thread_scaling.sh BENCH [OUT_DIR]
#   env: CACHE_DIR (packings, default build/bench-cache), ROUNDS (default 3), WORKLOADS (names
#   from the table below, default all), MAX_THREADS (default: all processors), SPECIMEN_88K (the
#   specimen.csv of `grainlab prepare examples/plane_strain/reference.toml`; dense-88k runs when
#   it is given or CACHE_DIR/dense-88k.csv exists, and is skipped with a note otherwise)
#   e.g. bench/thread_scaling.sh build/release/bench/grainlab_bench build/scaling
set -euo pipefail
bench=$1 out=${2:-build/bench-results}
cache=${CACHE_DIR:-build/bench-cache} rounds=${ROUNDS:-3}
mkdir -p "$out" "$cache"
export OMP_PLACES=${OMP_PLACES:-cores} OMP_PROC_BIND=${OMP_PROC_BIND:-close}
procs=${MAX_THREADS:-$(nproc)}
threads=() t=1
while ((t <= procs)); do threads+=("$t"); t=$((t * 2)); done
((threads[-1] == procs)) || threads+=("$procs")

# name | grainlab_bench workload | tile (empty: none) | timed steps | warm-up steps; the larger
# packings' steps keep a 1-thread run near 15 s on a 2024 server core
table=("dense-11k|dense-11k||2000|100" "dense-88k|dense-88k||600|50" "tile-2x2x3|dense-11k|2x2x3|400|50"
  "tile-4x4x4|dense-11k|4x4x4|60|10")
if [ -n "${SPECIMEN_88K:-}" ] && [ ! -f "$SPECIMEN_88K" ]; then
  echo "SPECIMEN_88K=$SPECIMEN_88K: no such file (the specimen.csv of grainlab prepare" \
    "examples/plane_strain/reference.toml)" >&2
  exit 2
fi
echo "machine: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs), $(nproc) processors," \
  "$(lscpu 2>/dev/null | awk -F: '/^Thread\(s\) per core/{gsub(/ /,"",$2); print $2}') thread(s) per core," \
  "$(lscpu 2>/dev/null | awk -F: '/^NUMA node\(s\)/{gsub(/ /,"",$2); print $2}') NUMA node(s)"
echo "threads: ${threads[*]}  rounds: $rounds  OMP_PLACES=$OMP_PLACES OMP_PROC_BIND=$OMP_PROC_BIND"
runs=$out/thread-scaling-runs.txt
: >"$runs"
for row in "${table[@]}"; do
  IFS='|' read -r name workload tile steps warmup <<<"$row"
  [ -z "${WORKLOADS:-}" ] || [[ " $WORKLOADS " == *" $name "* ]] || continue
  tile_args=()
  [ -z "$tile" ] || tile_args=(--tile "$tile")
  if [ "$workload" = dense-88k ]; then
    if [ -n "${SPECIMEN_88K:-}" ]; then
      tile_args=(--specimen "$SPECIMEN_88K")
    elif [ ! -f "$cache/dense-88k.csv" ]; then
      echo "dense-88k skipped: not in $cache and no SPECIMEN_88K given"
      continue
    fi
  fi
  for ((r = 1; r <= rounds; ++r)); do
    for t in "${threads[@]}"; do
      line=$("$bench" "$workload" "${tile_args[@]}" --threads "$t" --reps 1 --steps "$steps" \
        --warmup "$warmup" --cache-dir "$cache" --results-dir "$out" --label thread-scaling \
        2>/dev/null | awk '$1 ~ /^[0-9]+$/ && NF >= 9')
      # threads rep p-steps/s ns/p-step rebuilds Z RSS B/particle hash entries
      echo "$name round $r: $line" | tee -a "$runs"
    done
  done
done
echo
echo "workload    threads  median p-steps/s  ns/p-step  speed-up  efficiency  hashes"
awk '
  { name = $1; t = $4; rate[name, t] = rate[name, t] " " $6; hashes[name] = hashes[name] " " $12
    if (!((name, t) in seen)) { seen[name, t] = 1; order[++n] = name SUBSEP t } }
  function median(s,   v, k, i, j, x) {
    k = split(s, v, " ")
    for (i = 2; i <= k; ++i) { x = v[i]; for (j = i - 1; j >= 1 && v[j] + 0 > x + 0; --j) v[j + 1] = v[j]; v[j + 1] = x }
    return k % 2 ? v[(k + 1) / 2] : (v[k / 2] + v[k / 2 + 1]) / 2
  }
  END {
    for (i = 1; i <= n; ++i) {
      split(order[i], key, SUBSEP); name = key[1]; t = key[2]
      m = median(rate[name, t]); if (t == 1) one[name] = m
      split(hashes[name], h, " "); same = "same"
      for (j in h) if (h[j] != h[1]) same = "DIFFER"
      printf "%-11s %7d %17.4g %10.1f %9.2f %11.2f  %s\n", name, t, m, 1e9 / m,
        m / one[name], m / one[name] / t, same
    }
  }' "$runs"
