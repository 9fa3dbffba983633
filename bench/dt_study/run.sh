#!/bin/bash
# The time-step convergence study of the element tests (docs/time-step.md). One specimen per
# size, prepared once, then sheared at several steps, each on one thread:
#   - 2,000 beads (examples/triaxial/small.toml with count 2000 in a 22.2 x 22.2 x 44.4 mm box)
#     at dt_fraction 0.05, 0.1, 0.2, 0.3 with I <= 1e-3, and 0.05, 0.1 with I <= 3e-4;
#   - the reference specimen (examples/triaxial/reference.toml, 11,636 beads) at dt_fraction
#     0.3, 0.2, 0.1, 0.05 with I <= 1e-3, to 8 % axial strain (past the peak at about 5 %).
# Each set also reruns one step on the specimen with one bead moved by 1e-15 m (the chaos floor).
# About 45 min for the small set and 90 min for the reference set on one core of the 2-core
# development machine. Resumable: finished runs are kept, interrupted ones continue from their
# checkpoint. Then prints the tables (analyse.py).
#   bench/dt_study/run.sh [WORK_DIR]     (after cmake --build --preset release)
set -euo pipefail
src=$(cd "$(dirname "$0")/../.." && pwd)
exe=$src/build/release/apps/grainlab/grainlab
[ -x "$exe" ] || { echo "build first: cmake --build --preset release" >&2; exit 2; }
work=${1:-$src/build/dt-study}
mkdir -p "$work" && cd "$work"
export OMP_NUM_THREADS=1

# run NAME BASE_CONFIG SPECIMEN_DIR DT_FRACTION MAX_INERTIAL_NUMBER
run() {
  local name=$1 base=$2 spec=$3 dt=$4 inertial=$5
  [ -f "$name/summary.json" ] && return 0
  if [ -f "$name/checkpoint.bin" ]; then "$exe" run --resume "$name" --quiet; return; fi
  sed -e "s/^max_inertial_number = .*/max_inertial_number = $inertial/" \
      -e "/^\[test\]/a specimen = \"$spec\"\ndt_fraction = $dt" "$base" > "$name.toml"
  "$exe" run "$name.toml" --out "$name" --overwrite --quiet
}
prepare() {  # prepare CONFIG DIR
  [ -f "$2/specimen.csv" ] || "$exe" prepare "$1" --out "$2" --overwrite --quiet
}
# perturb DIR: DIR_perturbed, the same specimen with bead 0 moved by 1e-15 m along x (the floor
# set by the packing's chaos: how far apart two runs end for a rounding-size difference).
perturb() {
  mkdir -p "$1_perturbed"
  /usr/bin/python3 - "$1" <<'PY'
import sys
d = sys.argv[1]
lines = open(f"{d}/specimen.csv").read().split("\n")
f = lines[2].split(",")
f[3] = repr(float(f[3]) + 1e-15)
lines[2] = ",".join(f)
open(f"{d}_perturbed/specimen.csv", "w").write("\n".join(lines))
PY
}

sed -e 's/^count = 500/count = 2000/' \
    -e 's/^box = \["14 mm", "14 mm", "28 mm"\]/box = ["22.2 mm", "22.2 mm", "44.4 mm"]/' \
    "$src/examples/triaxial/small.toml" > small.toml
grep -q '^count = 2000' small.toml && grep -q '22.2 mm' small.toml
prepare small.toml small_specimen
for spec in "0.05 1e-3" "0.1 1e-3" "0.2 1e-3" "0.3 1e-3" "0.1 3e-4" "0.05 3e-4"; do
  set -- $spec
  run "small_dt$1_I$2" small.toml small_specimen "$1" "$2"
done
perturb small_specimen
run small_dt0.05_I1e-3_perturbed small.toml small_specimen_perturbed 0.05 1e-3

sed -e 's/^max_axial_strain = .*/max_axial_strain = 0.08/' "$src/examples/triaxial/reference.toml" > reference.toml
grep -q '^max_axial_strain = 0.08' reference.toml
prepare reference.toml reference_specimen
for dt in 0.3 0.2 0.1 0.05; do run "reference_dt$dt" reference.toml reference_specimen "$dt" 1e-3; done
perturb reference_specimen
run reference_dt0.1_perturbed reference.toml reference_specimen_perturbed 0.1 1e-3

echo "## 2,000 beads, against dt = 0.05 t_c, I <= 3e-4"
/usr/bin/python3 "$src/bench/dt_study/analyse.py" small_dt0.05_I3e-4 small_dt0.05_I1e-3 small_dt0.1_I1e-3 \
  small_dt0.2_I1e-3 small_dt0.3_I1e-3 small_dt0.1_I3e-4
echo "## 2,000 beads, I <= 1e-3, against dt = 0.05 t_c"
/usr/bin/python3 "$src/bench/dt_study/analyse.py" small_dt0.05_I1e-3 small_dt0.05_I1e-3_perturbed \
  small_dt0.1_I1e-3 small_dt0.2_I1e-3 small_dt0.3_I1e-3
echo "## reference specimen, I <= 1e-3, against dt = 0.05 t_c"
/usr/bin/python3 "$src/bench/dt_study/analyse.py" reference_dt0.05 reference_dt0.1 reference_dt0.1_perturbed \
  reference_dt0.2 reference_dt0.3
echo "## reference specimen: the perturbed run against its own twin"
/usr/bin/python3 "$src/bench/dt_study/analyse.py" reference_dt0.1 reference_dt0.1_perturbed
