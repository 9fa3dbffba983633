#!/bin/bash
# One interleaved round of the active list's skin fraction on the plane strain loading to 0.5 %.
GL=/tmp/wt/build/release/apps/grainlab/grainlab
for f in 0.05 0.1 0.025; do
  s=$(date +%s.%N)
  GL_LSF=$f $GL run /tmp/prof/ps.toml --out /tmp/prof/lsf-$f --overwrite --threads 2 > /tmp/prof/lsf-$f.log 2>&1
  rc=$?
  e=$(date +%s.%N)
  echo "fraction $f rc $rc wall $(echo "$e - $s" | bc) s md5 $(md5sum < /tmp/prof/lsf-$f/curve.csv | cut -c1-32)"
done
