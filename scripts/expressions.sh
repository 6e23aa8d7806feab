#!/usr/bin/env bash
# The expressions contact sheet (the previous main job; the main job is now scripts/demo.sh, Obie):
# install dependencies, build the apps, and run the pipeline
# on the built-in default face. Outputs go to out/ (override with OUT_DIR).
#   emotions (data/fuzzyexpr/example_emotions.csv) → emo2muscle → faceanim → facerender contact sheet
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
BUILD_DIR=${BUILD_DIR:-build}
OUT_DIR=${OUT_DIR:-out}
JOBS=${JOBS:-2}
cmake -S . -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$BUILD_DIR" -j"$JOBS" --target emo2muscle faceanim facerender
bin="$BUILD_DIR"/apps
mkdir -p "$OUT_DIR"
echo "== 1. emotions → muscle contractions (thesis ch. 6): data/fuzzyexpr/example_emotions.csv"
"$bin"/emo2muscle/emo2muscle data/fuzzyexpr/example_emotions.csv --sides -o "$OUT_DIR"/muscles.csv --summary
echo "== 2. muscle parameters → deformed default face, one mesh per row (thesis ch. 2)"
rm -rf "$OUT_DIR"/frames
"$bin"/faceanim/faceanim --params "$OUT_DIR"/muscles.csv --out "$OUT_DIR"/frames --gltf "$OUT_DIR"/expressions.gltf
echo "== 3. meshes → contact sheet"
"$bin"/facerender/facerender "$OUT_DIR"/frames/*.obj --sheet 5 --occlusion 0.4 --out "$OUT_DIR"/expressions.png
"$bin"/facerender/facerender "$OUT_DIR"/frames/*.obj --sheet 5 --view threequarter --occlusion 0.4 --out "$OUT_DIR"/expressions_threequarter.png
echo "wrote $OUT_DIR/muscles.csv, $OUT_DIR/frames/*.obj, $OUT_DIR/expressions.gltf,"
echo "      $OUT_DIR/expressions.png and $OUT_DIR/expressions_threequarter.png (rows of data/fuzzyexpr/example_emotions.csv)"
