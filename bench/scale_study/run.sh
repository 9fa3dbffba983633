#!/bin/sh
# The recorded scale study (bench/results/scale-study.md): three studies of the same 3,000-bead
# plane strain specimen. usage: bench/scale_study/run.sh GRAINLAB OUT_DIR
#   reference   : d = 2 mm and the published 1 ... 18 m, gravity off and on, I <= 1e-3
#   standing    : d = 0.1 ... 0.8 m, gravity on (sizes that stand under their own weight)
#   strain_rate : d = 1 ... 18 m, gravity off, a fixed strain rate of 0.2 1/s
# Each is resumable: rerunning this script continues a study that was interrupted.
set -e
exe=$1
out=$2
here=$(dirname "$0")
mkdir -p "$out"
for study in reference standing strain_rate; do
  if [ -f "$out/$study/summary.json" ]; then continue; fi
  if [ -f "$out/$study/scale_study.toml" ]; then
    "$exe" run --resume "$out/$study"
  else
    "$exe" run "$here/$study.toml" --out "$out/$study"
  fi
done
