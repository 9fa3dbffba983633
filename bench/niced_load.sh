#!/bin/bash
# Element-test runs of one or more grainlab binaries, interleaved, while a busy loop at low
# priority (nice 19) holds CPU 0: how the threads' wait and the team that follows the free CPUs
# treat a process of lower priority (docs/performance.md sec. 38). Each round runs every binary
# once without --threads (the team follows the free CPUs) and once with --threads 2. Prints per
# run the wall seconds (process start to end), curve.csv's sha256 prefix (the same in every run:
# results do not depend on the team) and the team changes the run reported on stderr.
#   bench/niced_load.sh CONFIG ROUNDS GRAINLAB...
# Example (short reference shear, see bench/element_test_compare.sh for the config):
#   bench/niced_load.sh /tmp/shear-short.toml 3 /tmp/old/grainlab build/release/apps/grainlab/grainlab
# Needs taskset and nice; the loop is stopped on exit. Nothing else heavy may run meanwhile.
set -euo pipefail
(($# >= 3)) || { echo "usage: $0 CONFIG ROUNDS GRAINLAB..." >&2; exit 2; }
config=$1 rounds=$2
shift 2
[[ -r $config ]] || { echo "$0: $config: cannot read the config" >&2; exit 2; }
[[ $rounds =~ ^[1-9][0-9]*$ ]] || { echo "$0: ROUNDS must be a positive integer, got '$rounds'" >&2; exit 2; }
for bin in "$@"; do [[ -x $bin ]] || { echo "$0: $bin: not an executable" >&2; exit 2; }; done
work=$(mktemp -d)
taskset -c 0 nice -n 19 bash -c 'while :; do :; done' &
loop=$!
trap 'kill $loop 2>/dev/null; rm -rf "$work"' EXIT
sleep 1
for ((r = 1; r <= rounds; ++r)); do
  k=0
  for bin in "$@"; do
    k=$((k + 1))
    for team in follow 2; do
      args=()
      [[ $team == 2 ]] && args=(--threads 2)
      out=$work/run
      rm -rf "$out"
      start=$(date +%s.%N)
      "$bin" run "$config" --out "$out" "${args[@]}" >/dev/null 2>"$work/err"
      end=$(date +%s.%N)
      changes=$(grep -o 'go on with [0-9]* thread' "$work/err" | tr '\n' ',' || true)
      printf 'round %d  binary %d  team %-6s  %7.2f s  curve %s  %s\n' "$r" "$k" "$team" \
        "$(echo "$end - $start" | bc)" "$(sha256sum "$out/curve.csv" | cut -c1-8)" "${changes:-}"
    done
  done
done
