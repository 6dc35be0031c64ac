#!/bin/sh
# Tiered execution (issue 17): whole-process CPU time (user + sys of virtcom and of the C
# compiler it waits for, start-up included; the minimum of RUNS runs, GNU time) of
# `virtcom run --quiet` on the gearbox cell (10 ms task, the example, and a 1 ms task) and of
# `virtcom exec bench/st/arith.st --cycles 20000` (a CPU-bound program) with --backend interp,
# aot and auto, the AOT cache warm and cold (a fresh empty cache per run),
# and the ratios to interp, measured in the same run of this script; then, from
# $VIRTCOM_TIER_LOG, when auto's machine code was ready (wall ms after load) and at which
# virtual time the PLC switched. The figures in docs/performance.md ("Tiered execution") come
# from it:
#   bench/tiered.sh [BUILD_DIR (build/release)] [RUNS (3)]
set -eu
build=${1:-build/release}
runs=${2:-3}
virtcom=${VIRTCOM:-$build/src/cli/virtcom}
root=$(dirname "$0")/..
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
cp -r "$root/examples/gearbox-cell" "$dir/gearbox-1"
sed -i "s/cycle_time: 10 ms/cycle_time: 1 ms/" "$dir/gearbox-1/cell.yaml"
warm="$dir/warm-cache"

# Minimum CPU seconds of $runs runs of `virtcom CASE --backend B` (B = $1, case = $2: a cell file
# to run, or a .st file to exec); with COLD=1 every run gets an empty cache.
command_of() {
  case "$1" in
    *.st) echo "exec $1 --cycles 20000" ;;
    *) echo "run $1 --quiet" ;;
  esac
}

cpu() {
  best=""
  i=0
  while [ "$i" -lt "$runs" ]; do
    cache=$warm
    if [ "${COLD:-0}" = 1 ]; then cache="$dir/cold-$i-$$"; rm -rf "$cache"; fi
    VIRTCOM_AOT_CACHE=$cache /usr/bin/time -f '%U %S' -o "$dir/time" "$virtcom" $(command_of "$2") --backend "$1" >/dev/null 2>&1
    t=$(tail -n 1 "$dir/time" | awk '{ printf "%.3f", $1 + $2 }')
    best=$(awk -v a="$best" -v b="$t" 'BEGIN { print (a == "" || b < a) ? b : a }')
    i=$((i + 1))
  done
  echo "$best"
}

echo "case | interp s | aot warm s | auto warm s | auto cold s | aot cold s | auto warm/interp | auto cold/interp | aot warm/interp"
for cell in "$root/examples/gearbox-cell/cell.yaml" "$dir/gearbox-1/cell.yaml" "$root/bench/st/arith.st"; do
  VIRTCOM_AOT_CACHE=$warm "$virtcom" $(command_of "$cell") --backend aot >/dev/null  # fills the warm cache
  interp=$(cpu interp "$cell")
  aotWarm=$(cpu aot "$cell")
  autoWarm=$(cpu auto "$cell")
  autoCold=$(COLD=1 cpu auto "$cell")
  aotCold=$(COLD=1 cpu aot "$cell")
  name=$(basename "$(dirname "$cell")")/$(basename "$cell")
  awk -v n="$name" -v i="$interp" -v aw="$aotWarm" -v uw="$autoWarm" -v uc="$autoCold" -v ac="$aotCold" \
    'BEGIN { printf "%s | %s | %s | %s | %s | %s | %.2fx | %.2fx | %.2fx\n", n, i, aw, uw, uc, ac, uw / i, uc / i, aw / i }'
  for c in warm cold; do
    cache=$warm
    [ "$c" = cold ] && cache="$dir/log-cold" && rm -rf "$cache"
    printf '%s, %s cache: ' "$name" "$c"
    VIRTCOM_TIER_LOG=1 VIRTCOM_AOT_CACHE=$cache "$virtcom" $(command_of "$cell") 2>&1 >/dev/null | grep '^tier:' || echo
  done
done
