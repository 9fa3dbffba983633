#!/bin/bash
# ABBA: default spin (1000) vs GOMP_SPINCOUNT=20000, team following the free CPUs (no --threads)
cfg=$1; tag=$2; rounds=$3
for r in $(seq $rounds); do for s in 20000 default default 20000; do
  out=/work/runs/spin-$tag; rm -rf $out
  if [ $s = default ]; then /work/runs/grainlab-trial run $cfg --out $out --quiet >/dev/null 2>&1
  else GOMP_SPINCOUNT=$s /work/runs/grainlab-trial run $cfg --out $out --quiet >/dev/null 2>&1; fi
  echo "$s $(python3 -c "import json;d=json.load(open('$out/summary.json'));print(round(d['wall_time_s'],2), round(d['shearing_wall_time_s'],2))") $(md5sum < $out/curve.csv | cut -c1-8) $(date -u +%H:%M:%S)"
done; done
