#!/bin/bash
# Paired rounds (ABBA order alternating): the unchanged build (A, /work/main) against the scratch
# build with k steps per pass (B, /work/hack, GRAINLAB_TWO_STEP=k, GRAINLAB_PIPE=1 on 2 threads).
# dense-11k --tile 2x2x2 (93,088 beads), 1000 timed steps after 50 of warm-up, flat gather walk.
A=/work/main/build/release/bench/grainlab_bench
H=/work/hack/build/release/bench/grainlab_bench
COMMON="dense-11k --tile 2x2x2 --cache-dir /work/main/build/release/bench-cache --steps 1000 --warmup 50 --reps 1 --no-csv --gather-walk flat"
run() { # label threads env...
  local label=$1 t=$2; shift 2
  local line; line=$(env "$@" ${BIN} $COMMON --threads $t 2>&1 | tail -1 | tr -s ' ')
  echo "$label t=$t $line"
}
for round in 1 2 3 4 5 6; do
  for t in 2 1; do
    if [ $((round % 2)) = 1 ]; then order="A B8 B4"; else order="B4 B8 A"; fi
    for c in $order; do
      case $c in
        A) BIN=$A run A $t X=1 ;;
        B8) BIN=$H run B8 $t GRAINLAB_TWO_STEP=8 GRAINLAB_PIPE=1 ;;
        B4) [ $t = 2 ] && BIN=$H run B4 $t GRAINLAB_TWO_STEP=4 GRAINLAB_PIPE=1 ;;
      esac
    done
  done
done
