#!/bin/sh
# What the first `--backend aot` load costs as programs grow (issue 21), with an empty cache:
#   bench/aot_compile/compile_cost.sh [BUILD_DIR (build/release)] [CASE ...]
# A CASE is SHAPE:LINES (SHAPE pou or fbs, see make_aot_program.cpp) or `gearbox` (the example
# cell's first load). Default cases: pou:1000 pou:10000 fbs:1000 fbs:10000 fbs:50000 gearbox.
# Prints, per case, the CPU time of virtcom and every compiler process it ran (user + sys, GNU
# time, Debian package `time`), the wall time and the peak resident memory of the largest single
# process (the C compiler's cc1 in practice). VIRTCOM=path measures another build of virtcom on
# the same programs (before/after comparisons in one run); COMPILE_MODULE=path measures
# aot_compile_module (bench/aot_compile/compile_module.cpp) instead of virtcom (the same load, without the rest of a run).
set -eu
build=${1:-build/release}
[ $# -gt 0 ] && shift
cases=${*:-pou:1000 pou:10000 fbs:1000 fbs:10000 fbs:50000 gearbox}
virtcom=${VIRTCOM:-$build/src/cli/virtcom}
root=$(cd "$(dirname "$0")/../.." && pwd)
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
printf '%-12s %8s %10s %8s %10s\n' case lines cpu_s wall_s peak_MB
for c in $cases; do
  rm -rf "$dir/cache"
  if [ "$c" = gearbox ]; then
    cell=$root/examples/gearbox-cell
    files=$(sed -n 's/^ *sources: \[\(.*\)\]/\1/p' "$cell/cell.yaml" | tr -d ' ' | tr ',' '\n' | sed "s|^|$cell/|")
    lines=$(cat $files | wc -l)
    set -- run "$cell/cell.yaml" --quiet --backend aot
  else
    "$build/bench/make_aot_program" "${c%%:*}" "${c#*:}" >"$dir/program.st"
    files=$dir/program.st
    lines=$(wc -l <"$files")
    set -- exec "$files" --cycles 1 --backend aot
  fi
  [ -n "${COMPILE_MODULE:-}" ] && set -- $files
  VIRTCOM_AOT_CACHE="$dir/cache" /usr/bin/time -f '%U %S %e %M' -o "$dir/time" ${COMPILE_MODULE:-$virtcom} "$@" \
    >/dev/null 2>"$dir/err" || true
  if grep -q 'notice\|aot_compile_module:' "$dir/err"; then
    echo "$c: the AOT compile failed: $(cat "$dir/err")" >&2
    exit 1
  fi
  read -r user_s sys_s wall_s rss_kb <<EOF
$(tail -n 1 "$dir/time")
EOF
  awk -v c="$c" -v l="$lines" -v u="$user_s" -v s="$sys_s" -v w="$wall_s" -v kb="$rss_kb" \
    'BEGIN { printf "%-12s %8d %10.2f %8.2f %10.1f\n", c, l, u + s, w, kb / 1024 }'
done
