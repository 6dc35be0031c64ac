# Shared by bench/interp_counts.sh and bench/aot_counts.sh (sourced, not run): callgrind counts
# of one function. The includer sets $dir (a scratch directory) and $bench (virtcom_bench).

# Instructions per call of function $1 and its number of calls in the callgrind output $2.
per_call() {
  awk -v fn="$1" '
    /^summary:/ { total = $2 }
    /^cfn=/ { sub(/^cfn=/, ""); hit = ($0 == fn) }
    /^calls=/ { if (hit) { split($0, c, /[= ]/); calls += c[2] }; hit = 0 }
    END { printf "%.0f %d\n", (calls ? total / calls : 0), calls }' "$2"
}

# Instructions per call and calls of function $1 in the run of the command $2...; the
# command's output is left in $dir/out.
callgrind() {
  fn=$1
  shift
  valgrind --tool=callgrind --compress-strings=no --compress-pos=no --toggle-collect="$fn" \
    --callgrind-out-file="$dir/cg" "$@" >"$dir/out" 2>/dev/null
  per_call "$fn" "$dir/cg"
}

# The demangled name of the twin function $1 of virtcom_bench, as callgrind names it (the whole
# line is matched: the twins live in an anonymous namespace, whose name has a space).
twin() { nm -C "$bench" | awk -v t="$1" '$0 ~ "::"t"\\(" { $1 = ""; $2 = ""; sub(/^  /, ""); print; exit }'; }
