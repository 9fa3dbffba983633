#!/bin/bash
# Byte-identity guard for restructurings: runs the quick examples with a given grainlab binary and
# records a SHA-256 of every deterministic output (curves, traces, final states, specimen files),
# one line per file. Compare two records with diff: any line that differs is a changed result.
#   bench/guard/record.sh BUILD/grainlab OUT_DIR > record.txt
# Wall times and version strings are left out (summary.json files are reduced to their numbers
# minus the *_wall_time_s / particle_steps_per_s / threads / version keys).
set -euo pipefail
bin=$(realpath "$1"); out=$2; src=$(cd "$(dirname "$0")/../.." && pwd)
rm -rf "$out"; mkdir -p "$out"; cd "$out"
tmp=$(mktemp -d)
run() { local name=$1; shift; OMP_NUM_THREADS=${THREADS:-2} "$bin" run "$@" --out "$name" --quiet >/dev/null 2>&1 || echo "$name: exit $?" >&2; }
# scenes
run bead_pour "$src/examples/scenes/bead_pour.toml"
run single_bounce "$src/examples/scenes/single_bounce.toml"
# flat throws
for m in glass porous_stone rubber_membrane; do run flat_throw_$m "$src/examples/paper/flat_throw_$m.toml"; done
# sliding friction on fixed beads (Coulomb check) and on a small bed
sed 's/slide_distance = "8 mm"/slide_distance = "4 mm"\nfixed_bed = true/' \
  "$src/examples/paper/sliding_friction_rubber_membrane.toml" > "$tmp/fixed.toml"
run sliding_fixed "$tmp/fixed.toml"
sed -e 's/bed_length = "32 mm"/bed_length = "20 mm"/' -e 's/bed_width = "16 mm"/bed_width = "10 mm"/' \
    -e 's/layers = 4/layers = 3/' -e 's/slide_distance = "8 mm"/slide_distance = "4 mm"/' \
  "$src/examples/paper/sliding_friction_rubber_membrane.toml" > "$tmp/bed.toml"
run sliding_bed "$tmp/bed.toml"
# small triaxial (prepared and sheared)
run triaxial_small "$src/examples/triaxial/small.toml"
[ -n "${EXTRA:-}" ] && for e in $EXTRA; do run "$(basename "$e" .toml)" "$e"; done
rm -rf "$tmp"
find . -type f \( -name '*.csv' -o -name 'summary.json' -o -name 'specimen.json' \) | sort | while read -r f; do
  if [[ $f == *.json ]]; then
    /usr/bin/python3 - "$f" <<'PY'
import json, sys, hashlib
drop = ("wall_time", "particle_steps_per_s", "threads", "version", "config_file")
def clean(x):
    if isinstance(x, dict):
        return {k: clean(v) for k, v in x.items() if not any(d in k for d in drop)}
    if isinstance(x, list):
        return [clean(v) for v in x]
    return x
j = clean(json.load(open(sys.argv[1])))
print(hashlib.sha256(json.dumps(j, sort_keys=True).encode()).hexdigest(), sys.argv[1])
PY
  else
    sha256sum "$f"
  fi
done
