#!/bin/sh
# Deterministic interpreter cost per PLC scan (issue 17, "A faster interpreter"), for the five
# bench/st cases: x86 instructions per scan (valgrind callgrind, inclusive cost of
# plc::Runtime::tick over exactly SCANS calls from the cold start), VM instructions
# per scan and a hash of the memory image after the run (equal hashes: the same results), from
# bench/interp_scan.cpp; if virtcom_bench is built, also the x86 instructions per call of each
# C++ twin (`<case>/native`, -O2) and the ratio, and the gearbox cell (sequence 1, 1 ms task,
# repeated scans skipped as in `virtcom run`). Counts do not depend on the machine's load.
#   bench/interp_counts.sh [BUILD_DIR (build/release)] [SCANS (200)]
# The tables of docs/performance.md ("Interpreter (issue 17)") come from it.
set -eu
build=${1:-build/release}
scans=${2:-200}
root=$(dirname "$0")/..
scan=$build/bench/virtcom_interp_scan
bench=$build/bench/virtcom_bench
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT

. "$root/bench/callgrind_counts.sh"

printf '%-10s %10s %10s %12s %9s  %s\n' case x86/scan vm/scan native-x86 x86-ratio memory-hash
for c in arith:arithNative fb_calls:fbCallsScan bits:bitsScan strings:stringsScan cell:cellScan; do
  name=${c%%:*}
  set -- $(callgrind 'virtcom::plc::Runtime::tick()' "$scan" "$root/bench/st/$name.st" "$scans")
  x86=$1
  hash=$(awk '/memory_hash/ { print $2 }' "$dir/out")
  vm=$("$scan" "$root/bench/st/$name.st" "$scans" count | awk '/vm_instr_per_scan/ { print $2 }')
  native=0
  if [ -x "$bench" ]; then
    set -- $(callgrind "$(twin "${c#*:}")" "$bench" --benchmark_filter="^$name/native\$")
    native=$1
  fi
  awk -v n="$name" -v x="$x86" -v v="$vm" -v t="$native" -v h="$hash" 'BEGIN {
    printf "%-10s %10s %10s %12s %8.1fx  %s\n", n, x, v, t, (t > 0 ? x / t : 0), h }'
done
[ -x "$bench" ] || exit 0
# The gearbox benchmark's vm_instr counter is per cycle: per scan = per cycle * iterations / scans.
# Its x86 count includes the counting of VM instructions (one x86 instruction each).
# (The benchmark's name carries its minimum time: gearbox/cycle_1ms/min_time:1.000.)
set -- $(callgrind 'virtcom::plc::Runtime::tick()' "$bench" --benchmark_filter='^gearbox/cycle_1ms(/min_time:[0-9.]+)?$' \
  --benchmark_format=json)
vm=$(grep '"vm_instr"' "$dir/out" | tail -n 1 | sed 's/.*: *//; s/,$//')
it=$(grep '"iterations"' "$dir/out" | tail -n 1 | sed 's/.*: *//; s/,$//')
awk -v x="$1" -v calls="$2" -v it="$it" -v v="$vm" 'BEGIN {
  printf "%-10s %10s %10.0f   (%d scans per cycle)\n", "gearbox", x, (calls ? v * it / calls : 0), calls / it }'
