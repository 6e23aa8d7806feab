#!/usr/bin/env bash
# Reproduces the performance figures in docs/: builds the Google Benchmark programs in a Release tree and
# runs them, then times emo2muscle end to end on a generated 1-million-row ESV CSV.
# Usage: scripts/bench.sh [benchmark-name-regex]     Env: BUILD_DIR (default build-bench), ROWS (1000000)
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR=${BUILD_DIR:-build-bench}
ROWS=${ROWS:-1000000}
cmake -S . -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Release -DEMOFACE_BUILD_BENCH=ON -DEMOFACE_BUILD_TESTS=OFF >/dev/null
cmake --build "$BUILD_DIR" -j2
filter=${1:-.}
for b in "$BUILD_DIR"/tests/bench/*_bench; do
  [ -x "$b" ] || continue
  echo "== $(basename "$b")"
  "$b" --benchmark_filter="$filter" --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
done
if [ -x "$BUILD_DIR/tests/bench/fuzzyexpr_bench" ]; then
  tmp=$(mktemp -d)
  trap 'rm -rf "$tmp"' EXIT
  "$BUILD_DIR"/tests/bench/fuzzyexpr_bench --write-csv "$tmp/esv.csv" "$ROWS"
  echo "== emo2muscle end to end, $ROWS rows"
  for i in 1 2 3; do
    start=$(date +%s.%N)
    "$BUILD_DIR"/apps/emo2muscle/emo2muscle "$tmp/esv.csv" -o "$tmp/fmcv.csv"
    end=$(date +%s.%N)
    awk -v s="$start" -v e="$end" -v n="$ROWS" 'BEGIN { printf "run: %.2f s, %.0f rows/s\n", e - s, n / (e - s) }'
  done
fi
