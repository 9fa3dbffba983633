#!/usr/bin/env bash
# Runs the simulated flat-throw test for every reference material (published Table 3) and prints
# material, e measured, e simulated, error.   usage: examples/paper/flat_throw_table.sh [GRAINLAB]
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
exe="${1:-$here/../../build/release/apps/grainlab/grainlab}"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
printf "%-18s %12s %12s %9s\n" material "e (Table 3)" "e simulated" error
worst=0
for config in "$here"/flat_throw_*.toml; do
  name="$(basename "$config" .toml)"; name="${name#flat_throw_}"
  "$exe" run "$config" --out "$tmp/$name" --quiet >/dev/null
  line=$(/usr/bin/python3 -c "
import json; s = json.load(open('$tmp/$name/summary.json'))
print(f\"{s['restitution_input']:.3f} {s['restitution_simulated']:.4f} {s['restitution_error']:+.4f}\")")
  read -r measured simulated error <<<"$line"
  printf "%-18s %12s %12s %9s\n" "$name" "$measured" "$simulated" "$error"
  worst=$(/usr/bin/python3 -c "print(max($worst, abs($error)))")
done
if /usr/bin/python3 -c "import sys; sys.exit(0 if $worst <= 0.005 else 1)"; then
  echo "all within 0.005 (largest |error| $worst)"
else
  echo "largest |error| $worst exceeds 0.005"; exit 1
fi
