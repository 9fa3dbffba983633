#!/bin/bash
# device run 8 (2026-11-27): the pair results zeroed in parallel at each list refresh ("new",
# HEAD + that change) against 60aaa66 ("now"): the full-scale plane strain test to 0.5 % on 16
# threads (a refresh every 28 steps), then the tiles.
export LD_LIBRARY_PATH=$PWD/.devlibs OMP_PLACES=cores OMP_PROC_BIND=close
D=.devlibs/bins; chmod +x $D/*
{
for b in new now; do
  SECONDS=0; timeout 90 $D/${b}_grainlab run .devlibs/ps-short.toml --out /tmp/ps-$b --threads 16 --quiet > /tmp/ps-$b.log 2>&1
  echo "$b rc $? wall $SECONDS s"
  python3 -c "import json; d=json.load(open('/tmp/ps-$b/summary.json')); print('$b', d['preparation_wall_time_s'], d['shearing_wall_time_s'], d['steps'], d['neighbor_list_refreshes'])"
  md5sum /tmp/ps-$b/curve.csv
done
for r in 1 2; do for b in now new; do echo "tile t16 1200 steps $b: $(timeout 60 $D/${b}_bench dense-11k --tile 2x2x3 --threads 16 --reps 1 --steps 1200 --warmup 50 --cache-dir .devlibs/cache --no-csv 2>/dev/null | awk '$1 ~ /^[0-9]+$/ && NF >= 9 {print $3, $4, $9}')"; done; done
} 2>&1 | tee $OUT/refresh-16.txt
