#!/usr/bin/env bash
# Side-by-side benchmark: grainlab vs LAMMPS (and LIGGGHTS when a deck for it exists) on the
# same dense packing, interleaved, >= 3 repetitions, 1 and 2 threads / MPI ranks.
# Prints the medians and the ratio grainlab/peer; appends them to bench/results/compare-<host>.csv.
# grainlab runs with the pair kernel the CPU allows (core/pair_kernel_simd.hpp); the row
# "grainlab-scalar" is the same binary with GRAINLAB_SIMD=off (the scalar pair loop).
#
#   bench/compare.sh [--build DIR] [--workload dense-11k] [--steps 2000] [--reps 3]
#
# The peer codes come from Debian (apt-get install lammps liggghts) and are never committed.
# Run it on an idle machine: OpenMP threads and MPI ranks both busy-wait at barriers, and with
# another process on one of the 2 cores the 2-thread figures collapse (docs/performance.md).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(dirname "$here")
build=$root/build/native
workload=dense-11k
steps=2000
warmup=200
reps=3
while [[ $# -gt 0 ]]; do
  case $1 in
    --build) build=$2; shift 2 ;;
    --workload) workload=$2; shift 2 ;;
    --steps) steps=$2; shift 2 ;;
    --reps) reps=$2; shift 2 ;;
    *) echo "unknown option $1" >&2; exit 2 ;;
  esac
done
# absolute: the peers run in $build/compare and read the data file from there
build=$(realpath -m "$build")

if ! command -v lmp >/dev/null; then
  echo "installing LAMMPS from Debian..." >&2
  apt-get install -y lammps >&2 || { echo "cannot install lammps" >&2; exit 1; }
fi
if ! command -v liggghts >/dev/null; then apt-get install -y liggghts >&2 || echo "liggghts not available" >&2; fi
mpirun_cmd=(mpirun)
if command -v mpirun >/dev/null; then
  [[ $(id -u) == 0 ]] && mpirun_cmd+=(--allow-run-as-root)
  mpirun_cmd+=(--bind-to core)
else
  echo "no mpirun: peers run on 1 rank only" >&2
  mpirun_cmd=()
fi

if [[ ! -x $build/bench/grainlab_bench ]]; then
  (cd "$root" && cmake --preset native -G Ninja >/dev/null && cmake --build --preset native -j2 --target grainlab_bench)
fi
bench=$build/bench/grainlab_bench
work=$build/compare
mkdir -p "$work"
data=$work/$workload.data
"$bench" "$workload" --cache-dir "$build/bench-cache" --write-lammps-data "$data"

# particle-steps/s of one run of each code (last "Loop time" line: the timed run)
run_grainlab() {  # threads
  OMP_PROC_BIND=true "$bench" "$workload" --cache-dir "$build/bench-cache" --threads "$1" --reps 1 \
    --steps "$steps" --warmup "$warmup" --label compare | awk '$1 ~ /^[0-9]+$/ && NF >= 9 {print $3}'
}
run_peer() {  # code threads
  # grainlab's own scalar pair loop (GRAINLAB_SIMD=off), to show what the vectorised kernel gains
  if [[ $1 == grainlab-scalar ]]; then GRAINLAB_SIMD=off run_grainlab "$2"; return; fi
  local exe=$1 ranks=$2 log=$work/$1-$2.log deck=$here/$1/dense.in peer_data=$data
  local cmd=("$exe")
  [[ $exe == lammps ]] && cmd=(lmp)
  # LIGGGHTS declares the walls as atom type 2
  [[ $exe == liggghts ]] && peer_data=$work/$workload-2types.data && sed 's/^1 atom types/2 atom types/' "$data" > "$peer_data"
  if [[ $ranks -gt 1 ]]; then cmd=("${mpirun_cmd[@]}" -np "$ranks" "${cmd[@]}"); fi
  (cd "$work" && OMP_NUM_THREADS=1 "${cmd[@]}" -in "$deck" -var data "$peer_data" -var params "$data.params" -var steps "$steps" \
     -var warmup "$warmup" -log "$log" -screen none) || { echo nan; return; }
  awk '/^Loop time of/ {t=$4; n=$9; m=$12} END {if (t > 0) printf "%.6g\n", m * n / t; else print "nan"}' "$log"
}

peers=(grainlab-scalar lammps)
[[ -f $here/liggghts/dense.in ]] && command -v liggghts >/dev/null && peers+=(liggghts)
declare -A samples
for rep in $(seq 1 "$reps"); do
  for t in 1 2; do
    r=$(run_grainlab "$t"); samples[grainlab,$t]+="$r "
    echo "rep $rep threads $t grainlab $r" >&2
    for peer in "${peers[@]}"; do
      r=$(run_peer "$peer" "$t"); samples[$peer,$t]+="$r "
      echo "rep $rep threads $t $peer $r" >&2
    done
  done
done

median() { tr ' ' '\n' | grep -v '^$' | sort -g | awk '{a[NR]=$1} END {if (NR%2) print a[(NR+1)/2]; else print (a[NR/2]+a[NR/2+1])/2}'; }
# "median (min-max)" of the repetitions' own ratios grainlab / peer ("nan" pairs left out)
paired_ratios() {  # grainlab_samples peer_samples
  local ratios
  ratios=$(awk -v g="$1" -v p="$2" 'BEGIN {
    n = split(g, a, " "); split(p, b, " ")
    for (k = 1; k <= n; ++k) if (a[k] + 0 > 0 && b[k] + 0 > 0) print a[k] / b[k] }' | sort -g)
  [[ -n $ratios ]] || { echo "pairs: none"; return; }
  printf '%.2f (%.2f-%.2f)' "$(echo "$ratios" | median)" "$(head -n 1 <<<"$ratios")" "$(tail -n 1 <<<"$ratios")"
}
host=$(hostname)
csv=$root/bench/results/compare-$host.csv
[[ -f $csv ]] || echo "date_utc,workload,steps,reps,code,threads,median_particle_steps_per_s,samples,ratio_grainlab_over_code" > "$csv"
date=$(date -u +%Y-%m-%dT%H:%M:%SZ)
printf '\n%s, %s steps, %s repetitions, medians in particle-steps/s (grainlab: OpenMP threads; peers: MPI ranks)\n' \
  "$workload" "$steps" "$reps"
printf '%-10s %8s %14s %14s %10s   %s\n' code threads median grainlab ratio "repetitions' own ratios: median (min-max)"
for t in 1 2; do
  g=$(echo "${samples[grainlab,$t]}" | median)
  echo "$date,$workload,$steps,$reps,grainlab,$t,$g,\"${samples[grainlab,$t]% }\",1" >> "$csv"
  for peer in "${peers[@]}"; do
    p=$(echo "${samples[$peer,$t]}" | median)
    ratio=$(awk -v g="$g" -v p="$p" 'BEGIN {printf "%.2f", g / p}')
    # each repetition's own pair (grainlab, then this peer, minutes apart at most): a slow spell
    # of the machine that spans both runs cancels in their ratio, so the pairs' spread shows how
    # far the medians' ratio can be trusted
    paired=$(paired_ratios "${samples[grainlab,$t]}" "${samples[$peer,$t]}")
    printf '%-10s %8s %14.4g %14.4g %10s   %s\n' "$peer" "$t" "$p" "$g" "$ratio" "$paired"
    echo "$date,$workload,$steps,$reps,$peer,$t,$p,\"${samples[$peer,$t]% }\",$ratio" >> "$csv"
  done
done
g1=$(echo "${samples[grainlab,1]}" | median); g2=$(echo "${samples[grainlab,2]}" | median)
awk -v a="$g1" -v b="$g2" 'BEGIN {printf "grainlab speed-up 1 -> 2 threads: %.2f\n", b / a}'
