#!/bin/sh
# Runs a libFuzzer target from the separate clang fuzz build for a short while on a scratch copy
# of its seed corpus, so the checked-in corpus is never modified.
# Usage: run_fuzz_smoke.sh <target> <seed corpus dir> <seconds>
# Needs FUZZ_BUILD_DIR: the clang build made with -DVIRTCOM_FUZZ_ONLY=ON (`make test` sets it).
set -eu
target=$1
corpus=$2
seconds=$3

if [ -z "${FUZZ_BUILD_DIR:-}" ]; then
  echo "FAIL: FUZZ_BUILD_DIR is not set. Build the fuzz targets with clang" >&2
  echo "  (cmake -S . -B build/fuzz -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_C_COMPILER=clang -DVIRTCOM_FUZZ_ONLY=ON" >&2
  echo "   && cmake --build build/fuzz) and run ctest with FUZZ_BUILD_DIR=<that build dir>, or use 'make test'." >&2
  exit 1
fi
binary="$FUZZ_BUILD_DIR/tests/fuzz/$target"
if [ ! -x "$binary" ]; then
  echo "FAIL: fuzz binary '$binary' is missing: build the fuzz build in FUZZ_BUILD_DIR first." >&2
  exit 1
fi

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT INT TERM
mkdir "$work/corpus" "$work/artifacts"
cp "$corpus"/* "$work/corpus/"
if ! "$binary" -max_total_time="$seconds" -rss_limit_mb=2048 -artifact_prefix="$work/artifacts/" "$work/corpus"; then
  mkdir -p fuzz-artifacts
  cp "$work"/artifacts/* fuzz-artifacts/ 2>/dev/null || true
  echo "FAIL: $target found a crash; the input is saved in $(pwd)/fuzz-artifacts/" >&2
  exit 1
fi
