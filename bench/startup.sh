#!/bin/bash
# Whole-process CPU time of one gearbox cycle and of start-up (issue 17, "The cell and the
# bridges": 10,000x real time with the default backend). For each virtcom binary given (the
# build's, and e.g. a copy of the binary before a change, so that before/after come from the
# same run of this script), the median CPU time (user + sys of the process, bash's `time`,
# millisecond resolution) of RUNS runs of:
#   /bin/true                      the cost of any process on this machine (fork, exec, exit)
#   virtcom --version              loading the binary and its shared libraries, nothing else
#   gearbox seq 1 / seq 3          `virtcom run examples/gearbox-cell/cell.yaml --set MAIN.sequence=N
#                                  --quiet` (the default backend): start-up, PLC compile, run
# and, for the gearbox, the CPU time per simulated second and the real-time factor (simulated
# time / CPU time). Runs alternate between the binaries, so load changes hit them alike.
#   bench/startup.sh [BUILD_DIR (build/release)] [RUNS (21)] [OTHER_VIRTCOM...]
set -eu
build=${1:-build/release}
runs=${2:-21}
shift $(($# < 2 ? $# : 2))
root=$(dirname "$0")/..
binaries=("${VIRTCOM:-$build/src/cli/virtcom}" "$@")
cell=$root/examples/gearbox-cell/cell.yaml
TIMEFORMAT='%3U %3S'
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT

# Appends the CPU milliseconds of one run of "$@" (output discarded) to the file $out.
measure() {
  { time "$@" >/dev/null 2>&1; } 2>"$dir/t" || true
  awk '{ printf "%.0f\n", ($1 + $2) * 1000 }' "$dir/t" >>"$out"
}

median() { sort -n "$1" | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'; }

cases=(true version seq1 seq3)
for ((i = 0; i < runs; ++i)); do
  for b in "${!binaries[@]}"; do
    v=${binaries[$b]}
    out=$dir/$b.true measure /bin/true
    out=$dir/$b.version measure "$v" --version
    out=$dir/$b.seq1 measure "$v" run "$cell" --set MAIN.sequence=1 --quiet
    out=$dir/$b.seq3 measure "$v" run "$cell" --set MAIN.sequence=3 --quiet
  done
done

# Simulated seconds of each sequence, from the binary's own summary.
simulated() { "${binaries[0]}" run "$cell" --set MAIN.sequence="$1" | awk '/^Run time/ { print $3 }'; }
sim1=$(simulated 1)
sim3=$(simulated 3)

echo "median CPU ms of $runs runs; gearbox: simulated ${sim1} s (seq 1), ${sim3} s (seq 3)"
echo "binary | /bin/true | --version | seq 1 | seq 3 | seq 1 ms CPU per simulated s | seq 1 real-time factor | seq 3 real-time factor"
for b in "${!binaries[@]}"; do
  for c in "${cases[@]}"; do eval "m_$c=$(median "$dir/$b.$c")"; done
  awk -v n="${binaries[$b]}" -v t="$m_true" -v v="$m_version" -v s1="$m_seq1" -v s3="$m_seq3" -v d1="$sim1" -v d3="$sim3" \
    'BEGIN { printf "%s | %d | %d | %d | %d | %.3f | %.0fx | %.0fx\n", n, t, v, s1, s3, s1 / d1, d1 * 1000 / s1, d3 * 1000 / s3 }'
done
if [ "${#binaries[@]}" -gt 1 ]; then
  echo "speed-up of the first binary over each other one (its median CPU / the first one's, same run):"
  for ((b = 1; b < ${#binaries[@]}; ++b)); do
    row="${binaries[$b]}"
    for c in version seq1 seq3; do
      row="$row | $c $(awk -v a="$(median "$dir/0.$c")" -v o="$(median "$dir/$b.$c")" 'BEGIN { printf "%.2fx", o / a }')"
    done
    echo "$row"
  done
fi
