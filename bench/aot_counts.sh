#!/bin/sh
# Deterministic cost of the AOT tier per PLC scan (issue 17, "The native tier"), for the
# bench/st cases: x86 instructions per call of the compiled MAIN (valgrind callgrind, inclusive
# cost of p_MAIN, callees included, exactly SCANS calls after the cold start) of
# bench/interp_scan.cpp run with `aot`, and a hash of the memory image after the run on the AOT
# code and on the interpreter (equal hashes: the same results); if virtcom_bench is built, also
# the x86 instructions per call of each C++ twin (`<case>/native`, -O2) and the ratio.
# Counts do not depend on the machine's load. The generated C is compiled into a private cache
# each run, so the numbers are those of the generator of this build.
#   bench/aot_counts.sh [BUILD_DIR (build/release)] [SCANS (200)]
# The tables of docs/performance.md ("Native tier") come from it.
set -eu
build=${1:-build/release}
scans=${2:-200}
root=$(dirname "$0")/..
scan=$build/bench/virtcom_interp_scan
bench=$build/bench/virtcom_bench
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
VIRTCOM_AOT_CACHE=$dir/cache
export VIRTCOM_AOT_CACHE

. "$root/bench/callgrind_counts.sh"

printf '%-10s %10s %12s %9s  %-16s %s\n' case aot-x86 native-x86 x86-ratio aot-hash interp-hash
for c in arith:arithNative fb_calls:fbCallsScan bits:bitsScan strings:stringsScan cell:cellScan; do
  name=${c%%:*}
  program=$root/bench/st/$name.st
  "$scan" "$program" 1 aot >/dev/null  # compiles into the cache outside the measurement
  set -- $(callgrind p_MAIN "$scan" "$program" "$scans" aot)
  x86=$1
  hash=$(awk '/memory_hash/ { print $2 }' "$dir/out")
  interp=$("$scan" "$program" "$scans" | awk '/memory_hash/ { print $2 }')
  native=0
  if [ -x "$bench" ]; then
    set -- $(callgrind "$(twin "${c#*:}")" "$bench" --benchmark_filter="^$name/native\$")
    native=$1
  fi
  awk -v n="$name" -v x="$x86" -v t="$native" -v h="$hash" -v i="$interp" 'BEGIN {
    printf "%-10s %10s %12s %8.2fx  %-16s %s\n", n, x, t, (t > 0 ? x / t : 0), h, i }'
done
