#!/bin/sh
# Threads, processes and MPI ranks for `virtcom optimise` and `virtcom sweep` (docs/scaling.md):
# wall time and evaluations per hour of
#   - annealing on the line model (bench/optimise/line_model.yaml, BUDGET evaluations, seed 1,
#     batch 16) on 1 thread, 2 threads and 2 MPI ranks of 1 thread, checking the results agree;
#   - the 70-point gearbox sweep (bench/optimise/gearbox_sweep.yaml) on 1 thread, 2 threads,
#     2 processes (--shard 1/2 and 2/2 side by side, then --merge) and 2 MPI ranks, checking the
#     tables agree.
#   bench/optimise/scaling.sh [BUILD_DIR (build/release)] [BUDGET (480)]
# Start-up (reading the cell, compiling its program) is included, as a user sees it.
set -eu
build=${1:-build/release}
budget=${2:-480}
virtcom=$build/src/cli/virtcom
here=$(dirname "$0")
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
mpirun="mpirun --oversubscribe --allow-run-as-root -n 2"

now() { date +%s.%N; }
since() { awk -v a="$1" -v b="$(now)" 'BEGIN { print b - a }'; }
# "label seconds evaluations": one table row with evaluations per hour.
row() { awk -v l="$1" -v s="$2" -v n="$3" 'BEGIN { printf "| %s | %.2f s | %d | %.0f |\n", l, s, n, n / s * 3600 }'; }

echo "| line model, anneal, $budget evaluations | wall | evaluations | per hour |"
echo "| --- | ---: | ---: | ---: |"
opt="$virtcom optimise $here/line_model.yaml --method anneal --budget-evals $budget --seed 1 --quiet"
for case in "1 thread:--jobs 1" "2 threads:--jobs 2" "2 MPI ranks:mpi"; do
  label=${case%%:*}; how=${case#*:}
  t0=$(now)
  if [ "$how" = mpi ]; then $mpirun $opt --jobs 1 >"$dir/opt-$label.txt"; else $opt $how >"$dir/opt-$label.txt"; fi
  wall=$(since "$t0")
  n=$(sed -n 's/^evaluations: \([0-9]*\).*/\1/p' "$dir/opt-$label.txt")
  row "$label" "$wall" "$n"
  sed -n '/^| sequence/,$p' "$dir/opt-$label.txt" >"$dir/result-$label.txt"
done
cmp -s "$dir/result-1 thread.txt" "$dir/result-2 threads.txt" && cmp -s "$dir/result-1 thread.txt" "$dir/result-2 MPI ranks.txt" ||
  { echo "results differ"; exit 1; }
sed -n '/found: best-1/p' "$dir/result-1 thread.txt"

echo
echo "| gearbox sweep, 70 points | wall | points | per hour |"
echo "| --- | ---: | ---: | ---: |"
sweep="$virtcom sweep $here/gearbox_sweep.yaml"
t0=$(now); $sweep --jobs 1 --csv "$dir/one.csv" 2>/dev/null; row "1 thread" "$(since "$t0")" 70
t0=$(now); $sweep --jobs 2 --csv "$dir/two.csv" 2>/dev/null; row "2 threads" "$(since "$t0")" 70
t0=$(now)
$sweep --jobs 1 --shard 1/2 --csv "$dir/s1.csv" 2>/dev/null & $sweep --jobs 1 --shard 2/2 --csv "$dir/s2.csv" 2>/dev/null; wait
$virtcom sweep --merge "$dir/merged.csv" "$dir/s1.csv" "$dir/s2.csv"
row "2 processes (shards)" "$(since "$t0")" 70
t0=$(now); $mpirun $sweep --jobs 1 --csv "$dir/mpi.csv" 2>/dev/null; row "2 MPI ranks" "$(since "$t0")" 70
for f in two merged mpi; do cmp -s "$dir/one.csv" "$dir/$f.csv" || { echo "$f.csv differs"; exit 1; }; done
echo "all tables agree"
