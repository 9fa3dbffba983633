#!/bin/bash
# The vectorised pair kernel is compiled once per instruction set (src/core/CMakeLists.txt). An
# inline function or template instantiated in one of those objects would be a weak symbol that
# the linker may keep for the whole program, so that code built for AVX-512 could run on a CPU
# without it. Each object must define exactly three global symbols, its own pair_rows,
# particle_records and wall_law, and no weak ones.
#   kernel_symbols.sh OBJECT...
set -euo pipefail
status=0
for object in "$@"; do
  defined=$(nm --defined-only --extern-only -C "$object" | awk '{ $1 = ""; print substr($0, 2) }')
  count=$(printf '%s\n' "$defined" | grep -c . || true)
  if [[ $count -ne 3 ]] || ! grep -q '^T grainlab::simd_[a-z0-9]*::pair_rows(' <<<"$defined" ||
     ! grep -q '^T grainlab::simd_[a-z0-9]*::particle_records(' <<<"$defined" ||
     ! grep -q '^T grainlab::simd_[a-z0-9]*::wall_law(' <<<"$defined"; then
    echo "$object: expected only 'T grainlab::simd_*::pair_rows(...)'," \
         "'T grainlab::simd_*::particle_records(...)' and 'T grainlab::simd_*::wall_law(...)'," \
         "found:" >&2
    printf '  %s\n' "$defined" >&2
    status=1
  fi
done
[[ $status -eq 0 ]] && echo "$# kernel objects define only their pair_rows, particle_records and wall_law"
exit $status
