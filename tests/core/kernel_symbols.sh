#!/bin/bash
# The vectorised pair kernel and the particle passes are compiled once per instruction set
# (src/core/CMakeLists.txt). An inline function or template instantiated in one of those objects
# would be a weak symbol that the linker may keep for the whole program, so that code built for
# AVX-512 could run on a CPU without it. Each pair kernel object must define exactly two global
# symbols, its own pair_rows and particle_records; each wall kernel object three, its wall_law,
# plane_wall_rows and wall_totals; each particle passes object two, its kick_and_drift and
# half_kick; each gather object one, its gather; none any weak ones.
#   kernel_symbols.sh OBJECT...
set -euo pipefail
status=0
for object in "$@"; do
  case "$(basename "$object")" in
    pair_kernel_simd*) entry_points=(pair_rows particle_records) ;;
    wall_kernel_simd*) entry_points=(wall_law plane_wall_rows wall_totals) ;;
    particle_passes_simd*) entry_points=(kick_and_drift half_kick) ;;
    gather_simd*) entry_points=(gather) ;;
    *) echo "$object: not a kernel object" >&2; status=1; continue ;;
  esac
  defined=$(nm --defined-only --extern-only -C "$object" | awk '{ $1 = ""; print substr($0, 2) }')
  count=$(printf '%s\n' "$defined" | grep -c . || true)
  ok=1
  [[ $count -eq ${#entry_points[@]} ]] || ok=0
  for name in "${entry_points[@]}"; do
    grep -q "^T grainlab::simd_[a-z0-9]*::$name(" <<<"$defined" || ok=0
  done
  if [[ $ok -ne 1 ]]; then
    echo "$object: expected only the entry points ${entry_points[*]}" \
         "('T grainlab::simd_*::NAME(...)'), found:" >&2
    printf '  %s\n' "$defined" >&2
    status=1
  fi
done
[[ $status -eq 0 ]] && echo "$# kernel objects define only their entry points"
exit $status
