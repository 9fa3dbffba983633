#!/bin/bash
# Two grainlab_bench binaries (A: after a change, B: before it) on one workload, interleaved
# A B A B ... in ROUNDS rounds per thread count, each run timing STEPS steps after a warm-up.
# Prints every run's particle-steps/s and state hash (equal hashes: bit-identical results), then
# per thread count the median of each and the median of the per-round ratios A/B. With
# BUSY=1 a busy loop holds one core for the whole measurement (a machine shared with another
# process). TILE=NXxNYxNZ runs mirrored tiles of the workload (grainlab_bench --tile);
# WARMUP sets the untimed steps before each run (default 200).
#   bench/step_loop_compare.sh A_BENCH B_BENCH [WORKLOAD] [ROUNDS] [STEPS] [THREADS...]
#   e.g. bench/step_loop_compare.sh build/release/bench/grainlab_bench /tmp/old_bench dense-11k 5 2000 1 2
set -euo pipefail
a=$1 b=$2 workload=${3:-dense-11k} rounds=${4:-5} steps=${5:-2000}
shift $(( $# < 5 ? $# : 5 ))
threads=("$@"); [ ${#threads[@]} -gt 0 ] || threads=(1 2)
cache=${CACHE_DIR:-build/bench-cache}
busy_pid=
if [ "${BUSY:-0}" = 1 ]; then (while :; do :; done) & busy_pid=$!; fi
trap '[ -n "$busy_pid" ] && kill $busy_pid 2>/dev/null || true' EXIT
one() {  # one BINARY THREADS -> "p-steps/s hash"
  "$1" "$workload" ${TILE:+--tile "$TILE"} --threads "$2" --reps 1 --steps "$steps" \
      --warmup "${WARMUP:-200}" --cache-dir "$cache" --results-dir "${RESULTS_DIR:-build/bench-results}" 2>/dev/null |
    awk '$1 ~ /^[0-9]+$/ && NF >= 9 {print $3, $9}'
}
for t in "${threads[@]}"; do
  ra=(); rb=(); ratios=()
  for ((r = 1; r <= rounds; ++r)); do
    read -r sa ha <<<"$(one "$a" "$t")"
    read -r sb hb <<<"$(one "$b" "$t")"
    echo "threads $t round $r: A $sa ($ha)  B $sb ($hb)"
    ra+=("$sa"); rb+=("$sb"); ratios+=("$(awk -v x="$sa" -v y="$sb" 'BEGIN{print x/y}')")
  done
  med() { printf '%s\n' "$@" | sort -g | awk '{v[NR]=$1} END{print (NR%2 ? v[(NR+1)/2] : (v[NR/2]+v[NR/2+1])/2)}'; }
  echo "threads $t: median A $(med "${ra[@]}")  B $(med "${rb[@]}")  A/B $(med "${ratios[@]}") (busy core: ${BUSY:-0})"
done
