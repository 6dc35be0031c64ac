#!/bin/sh
# Event-driven time against stepping every tick (issue 21): CPU time (user + sys, the minimum of
# RUNS runs, GNU time) of `virtcom run --quiet --time-mode tick|event` on the gearbox cell
# (sequence 1, 10 ms, 1 ms and 0.1 ms task), the tank and conveyor activity cells, a press cell
# (tests/e2e/data/cells/pressing_forever.yaml, one simulated hour) and the generated
# scaling cell (bench/scaling, 8 stations, 1 ms task, 300 s), and their ratio, measured in the same
# run of this script (start-up included: the shorter runs mostly measure loading the cell):
#   bench/event_time.sh [BUILD_DIR (build/release)] [RUNS (3)]
# With CALLGRIND=1 it counts instead the instructions of the run loop alone
# (Simulation::run, start-up excluded; valgrind, deterministic, one run each). The figures in
# docs/performance.md ("Event-driven time") come from it.
set -eu
build=${1:-build/release}
runs=${2:-3}
virtcom=${VIRTCOM:-$build/src/cli/virtcom}
root=$(dirname "$0")/..
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
"$build/bench/make_scaling_cell" 8 "$dir/scaling" 1 >/dev/null
for ms in 1 0.1; do
  cp -r "$root/examples/gearbox-cell" "$dir/gearbox-$ms"
  sed -i "s/cycle_time: 10 ms/cycle_time: $ms ms/" "$dir/gearbox-$ms/cell.yaml"
done
cp -r "$root/examples/activity" "$dir/activity"
sed -i "s/cycle_time: .*/cycle_time: 1 ms/" "$dir/activity/tank-cell.yaml"
sed -i "s/cycle_time: .*/cycle_time: 0.1 ms/" "$dir/activity/conveyor-cell.yaml"

# Minimum CPU seconds of $runs runs of `virtcom run "$@" --quiet` (exit 3, the time limit, is fine).
cpu() {
  best=""
  i=0
  while [ "$i" -lt "$runs" ]; do
    /usr/bin/time -f '%U %S' -o "$dir/time" "$virtcom" run "$@" --quiet >/dev/null || [ $? -eq 3 ]
    t=$(tail -n 1 "$dir/time" | awk '{ printf "%.3f", $1 + $2 }')
    best=$(awk -v a="$best" -v b="$t" 'BEGIN { print (a == "" || b < a) ? b : a }')
    i=$((i + 1))
  done
  echo "$best"
}

# Instructions executed in Simulation::run of `virtcom run "$@" --quiet`.
instructions() {
  valgrind --tool=callgrind --toggle-collect='virtcom::sim::Simulation::run()' --callgrind-out-file="$dir/cg" \
    "$virtcom" run "$@" --quiet 2>&1 >/dev/null | awk '/refs/ { gsub(",", "", $NF); print $NF }'
}

compare() {
  name=$1
  shift
  measure=cpu
  [ "${CALLGRIND:-0}" = 1 ] && measure=instructions
  tick=$($measure "$@" --time-mode tick)
  event=$($measure "$@" --time-mode event)
  awk -v n="$name" -v t="$tick" -v e="$event" 'BEGIN {
    printf "%-34s tick %12s  event %12s  tick/event %6.2f\n", n, t, e, (e > 0 ? t / e : 0) }'
}

compare "gearbox seq 1, 10 ms task" "$root/examples/gearbox-cell/cell.yaml" --set MAIN.sequence=1
compare "gearbox seq 1, 1 ms task" "$dir/gearbox-1/cell.yaml" --set MAIN.sequence=1
compare "gearbox seq 1, 0.1 ms task" "$dir/gearbox-0.1/cell.yaml" --set MAIN.sequence=1
compare "tank cell (activity), 1 ms task" "$dir/activity/tank-cell.yaml"
compare "conveyor cell (activity), 0.1 ms" "$dir/activity/conveyor-cell.yaml"
compare "pressing forever, 10 ms, 1 h" "$root/tests/e2e/data/cells/pressing_forever.yaml" --time-limit 3600s
compare "scaling, 8 stations, 1 ms, 300 s" "$dir/scaling/scaling_cell.yaml" --time-limit 300s
