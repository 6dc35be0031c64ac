#!/bin/sh
# Memory and speed of a long run of the generated scaling cell (issue 21):
#   bench/scaling/long_run.sh [STATIONS (128)] [TASK_MS (1)] [VIRTUAL_TIME (3600s)] [BUILD_DIR (build/release)]
# Prints the peak resident memory, the CPU time, the real-time factor and the CPU ns per device
# per tick of `virtcom run --quiet` (GNU time, Debian package `time`).
set -eu
stations=${1:-128}
task_ms=${2:-1}
span=${3:-3600s}
build=${4:-build/release}
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
"$build/bench/make_scaling_cell" "$stations" "$dir" "$task_ms" >/dev/null
# exit code 3 = the run ended at its time limit, as intended
/usr/bin/time -f '%M %U %S' -o "$dir/time" "$build/src/cli/virtcom" run "$dir/scaling_cell.yaml" --quiet \
  --time-limit "$span" || [ $? -eq 3 ]
read -r rss_kb user_s sys_s <<EOF2
$(tail -n 1 "$dir/time")
EOF2
virtual_s=$(echo "$span" | sed 's/s$//')
awk -v kb="$rss_kb" -v u="$user_s" -v s="$sys_s" -v v="$virtual_s" -v n="$stations" -v t="$task_ms" 'BEGIN {
  cpu = u + s; ticks = v * 1000 / t; devices = n * 4
  printf "%d stations (%d devices), %s ms task, %s s virtual: peak RSS %.1f MB, CPU %.2f s (user %.2f, sys %.2f), %.0fx real time, %.1f ns per device per tick\n",
    n, devices, t, v, kb / 1024, cpu, u, s, v / cpu, cpu * 1e9 / (ticks * devices) }'
