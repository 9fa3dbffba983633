#!/bin/bash
# The long fuzzing run: every input target of tests/fuzz/fuzz_inputs.cpp with N mutated inputs
# (default 1,000,000 each; about 16 minutes on one core of the 2-core development machine, the
# checkpoint target being the slowest at about 2,400 inputs/s). Prints the table (inputs, inputs/s,
# refused, accepted, findings) and exits non-zero on any finding; a finding's input is saved in
# WORK_DIR.
#   bench/fuzz/run.sh [N] [SEED] [WORK_DIR]    (after cmake --build --preset release)
set -euo pipefail
cd "$(dirname "$0")/../.."
n=${1:-1000000}
seed=${2:-1}
work=${3:-build/release/fuzz-long}
exe=build/release/tests/fuzz/fuzz_inputs
[ -x "$exe" ] || { echo "build first: cmake --build --preset release" >&2; exit 2; }
mkdir -p "$work"
"$exe" --source . --work "$work" --inputs "$n" --seed "$seed"
