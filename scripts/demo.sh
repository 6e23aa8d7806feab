#!/usr/bin/env bash
# The README's main job, in one command: install dependencies, build the apps, and run the pipeline
# on the built-in default data. Outputs go to out/ (override with OUT_DIR).
#   emotions (data/fuzzyexpr/example_emotions.csv) → emo2muscle → out/muscles.csv (+ a readable summary)
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
BUILD_DIR=${BUILD_DIR:-build}
OUT_DIR=${OUT_DIR:-out}
JOBS=${JOBS:-2}
cmake -S . -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$BUILD_DIR" -j"$JOBS" --target emo2muscle
mkdir -p "$OUT_DIR"
echo "== emotions → muscle contractions (thesis ch. 6) =="
"$BUILD_DIR"/apps/emo2muscle/emo2muscle data/fuzzyexpr/example_emotions.csv \
  -o "$OUT_DIR"/muscles.csv --summary
"$BUILD_DIR"/apps/emo2muscle/emo2muscle data/fuzzyexpr/example_emotions.csv \
  -o "$OUT_DIR"/face_parameters.csv --sides
echo "wrote $OUT_DIR/muscles.csv (19 muscles) and $OUT_DIR/face_parameters.csv (35 left/right parameters)"
