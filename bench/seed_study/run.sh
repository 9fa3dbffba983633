#!/bin/bash
# How far realizations of the reference triaxial test scatter (docs/lab-tests.md, "Specimen
# state and the reference response"), and whether a preparation's compaction restitution changes
# the specimen beyond that scatter. The reference config (examples/triaxial/reference.toml),
# preparation included, sheared to 8 % axial strain (past the peak at about 5 %), for seeds
# 1..SEEDS with each compaction restitution given, interleaved (seed 1 with each, then seed 2 ...),
# on THREADS threads (default 2; each run's summary.json has its preparation and shearing wall
# times). About 5-6 min per run on the 2-core development machine. Resumable: finished runs are
# kept. Then prints the table (analyse.py).
#   bench/seed_study/run.sh [WORK_DIR] [SEEDS] [RESTITUTION...]   (after cmake --build --preset release)
#   e.g. bench/seed_study/run.sh build/seed-study 4 0.3 0.4
set -euo pipefail
src=$(cd "$(dirname "$0")/../.." && pwd)
exe=$src/build/release/apps/grainlab/grainlab
[ -x "$exe" ] || { echo "build first: cmake --build --preset release" >&2; exit 2; }
work=${1:-$src/build/seed-study} seeds=${2:-4}
shift $(( $# < 2 ? $# : 2 ))
restitutions=("$@"); [ ${#restitutions[@]} -gt 0 ] || restitutions=(0.3 0.4)
mkdir -p "$work" && cd "$work"
names=()
for ((seed = 1; seed <= seeds; ++seed)); do
  for e in "${restitutions[@]}"; do
    name="e${e}_seed$seed"
    names+=("$name")
    [ -f "$name/summary.json" ] && continue
    sed -e 's/^max_axial_strain = .*/max_axial_strain = 0.08/' -e '/^compaction_restitution = /d' \
        -e "/^\[test\]/a seed = $seed\ncompaction_restitution = $e" \
        "$src/examples/triaxial/reference.toml" > "$name.toml"
    grep -q '^max_axial_strain = 0.08' "$name.toml"
    echo "$(date -u +%H:%M:%S) $name" >&2
    "$exe" run "$name.toml" --out "$name" --overwrite --threads "${THREADS:-2}" --quiet
  done
done
/usr/bin/python3 "$src/bench/seed_study/analyse.py" "${names[@]}"
