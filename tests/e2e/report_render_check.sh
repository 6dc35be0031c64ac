#!/bin/sh
# Renders the example assembly-cell Trace with every report writer (target
# report_render_example) and, when /usr/bin/chromium exists, screenshots the HTML report headless
# so a person can check the Gantt chart really looks like one.
#   tests/e2e/report_render_check.sh [BUILD_DIR] [OUT_DIR]
# BUILD_DIR defaults to build/h-report (a configured build tree), OUT_DIR to /tmp/virtcom-report.
# Writes OUT_DIR/{report.html,report.json,report.vcd,changes.csv,summary.txt}, the long-run
# variant (2000 cycles, one-cycle view) in OUT_DIR/long/, and report.png / report-full.png /
# long/report.png when chromium is there. Exits non-zero if a file is missing or malformed.
set -eu

root=$(cd "$(dirname "$0")/../.." && pwd)
build=${1:-$root/build/h-report}
out=${2:-/tmp/virtcom-report}

cmake --build "$build" --target report_render_example >/dev/null
exe="$build/tests/unit/report_render_example"
"$exe" "$out"
"$exe" "$out/long" --long 2000 --cycle-only

fail() { echo "report_render_check: $*" >&2; exit 1; }
for f in report.html report.json report.vcd changes.csv summary.txt; do
  test -s "$out/$f" || fail "$out/$f is missing or empty"
done
head -n 1 "$out/report.html" | grep -q '^<!DOCTYPE html>$' || fail "report.html has no doctype"
tail -n 1 "$out/report.html" | grep -q '^</html>$' || fail "report.html is truncated"
grep -q 'class="chart gantt"' "$out/report.html" || fail "report.html has no Gantt chart"
grep -q '"schema": "virtcom.report"' "$out/report.json" || fail "report.json has no schema"
grep -q '^\$enddefinitions \$end$' "$out/report.vcd" || fail "report.vcd has no definitions"
head -n 1 "$out/changes.csv" | grep -q '^time_s,signal,value$' || fail "changes.csv has no header"

shot() {  # shot HTML PNG HEIGHT
  profile=$(mktemp -d)
  timeout 120 /usr/bin/chromium --headless --no-sandbox --disable-gpu --disable-quic --no-first-run \
    --disable-background-networking --disable-component-update --disable-sync \
    --run-all-compositor-stages-before-draw --hide-scrollbars \
    --user-data-dir="$profile" --screenshot="$2" --window-size=1400,"$3" "file://$1" >/dev/null 2>&1 || true
  rm -rf "$profile"
  test -s "$2" || fail "chromium wrote no screenshot $2"
  echo "screenshot: $2"
}
if [ -x /usr/bin/chromium ]; then
  shot "$out/report.html" "$out/report.png" 900
  shot "$out/report.html" "$out/report-full.png" 1750
  shot "$out/long/report.html" "$out/long/report.png" 900
else
  echo "report_render_check: /usr/bin/chromium not installed, no screenshots"
fi
