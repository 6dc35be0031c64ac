#!/bin/bash
# `make fuzz`: runs every libFuzzer target of targets.txt for SECONDS each, one after the other,
# and reports per target the CPU time, executions, coverage (libFuzzer's edges "cov" and features
# "ft"), the corpus size and the findings (crash, leak, timeout and OOM inputs).
# Each target starts from the checked-in seeds (tests/fuzz/corpus, never modified) plus the
# corpus it grew in earlier campaigns in WORK/TARGET/corpus, so campaigns add up.
# Usage: run_fuzz_campaign.sh SECONDS WORK; needs FUZZ_BUILD_DIR (the clang build of the targets).
# FUZZ_TARGETS="fuzz_a fuzz_b" runs only those.
# Exits 1 if a target is missing or found something; its inputs are in WORK/TARGET/artifacts.
set -u
seconds=$1
work=$2
here=$(cd "$(dirname "$0")" && pwd)
if [ -z "${FUZZ_BUILD_DIR:-}" ]; then
  echo "FAIL: FUZZ_BUILD_DIR is not set (the clang build with -DVIRTCOM_FUZZ_ONLY=ON; make fuzz sets it)" >&2
  exit 1
fi
mkdir -p "$work"
report="$work/report.md"
{
  echo "| target | seconds | CPU s | executions | exec/s | cov | ft | corpus | findings |"
  echo "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | --- |"
} >"$report"
status=0
TIMEFORMAT='%U %S'
while read -r target corpus; do
  case "$target" in fuzz_*) ;; *) continue ;; esac
  case " ${FUZZ_TARGETS:-$target} " in *" $target "*) ;; *) continue ;; esac
  binary="$FUZZ_BUILD_DIR/tests/fuzz/$target"
  if [ ! -x "$binary" ]; then
    echo "FAIL: $binary is missing: build the fuzz targets first" >&2
    status=1
    continue
  fi
  dir="$work/$target"
  mkdir -p "$dir/corpus" "$dir/artifacts"
  cp -n "$here/corpus/$corpus"/* "$dir/corpus/" 2>/dev/null
  echo "== $target: $seconds s" >&2
  { time "$binary" -max_total_time="$seconds" -rss_limit_mb=2048 -print_final_stats=1 \
      -artifact_prefix="$dir/artifacts/" "$dir/corpus" >"$dir/log.txt" 2>&1; } 2>"$dir/time.txt"
  read -r user sys <"$dir/time.txt"
  cpu=$(awk -v u="$user" -v s="$sys" 'BEGIN { printf "%.0f", u + s }')
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$dir/log.txt" | tail -1)
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$dir/log.txt" | tail -1)
  last=$(grep -E '^#[0-9]+' "$dir/log.txt" | tail -1)
  cov=$(echo "$last" | sed -n 's/.*cov: \([0-9]*\).*/\1/p')
  ft=$(echo "$last" | sed -n 's/.*ft: \([0-9]*\).*/\1/p')
  files=$(find "$dir/corpus" -type f | wc -l)
  findings=$(find "$dir/artifacts" -type f | sed 's|.*/||' | tr '\n' ' ')
  [ -n "$findings" ] && status=1
  echo "| $target | $seconds | $cpu | ${runs:-?} | ${rate:-?} | ${cov:-?} | ${ft:-?} | $files | ${findings:-none} |" >>"$report"
done <"$here/targets.txt"
cat "$report"
echo "(report: $report; logs and findings: $work/TARGET/)"
exit $status
