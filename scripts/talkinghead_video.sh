#!/usr/bin/env bash
# Thesis Fig. 4.8 as a video: marked-up text → talkinghead (tracks + speech) → faceanim (meshes) →
# facerender (frames + MP4) → ffmpeg muxes the speech in. Builds the apps first.
# Usage: scripts/talkinghead_video.sh [SCRIPT.xml] [OUT_DIR]   (defaults: the thesis example, out/talkinghead)
set -euo pipefail
cd "$(dirname "$0")/.."
SCRIPT=${1:-data/channels/examples/oh_really.xml}
OUT=${2:-out/talkinghead}
BUILD_DIR=${BUILD_DIR:-build}
FPS=${FPS:-25}
cmake -S . -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$BUILD_DIR" -j"${JOBS:-2}" --target talkinghead faceanim facerender
bin="$BUILD_DIR"/apps
rm -rf "$OUT" && mkdir -p "$OUT"/frames
"$bin"/talkinghead/talkinghead --script "$SCRIPT" --fps "$FPS" --seed 1 --out "$OUT"/tracks.csv \
  --wav "$OUT"/speech.wav --plot "$OUT"/tracks.png \
  --plot-params zygomatic_major_l,orbicularis_oris_funneler,frontalis_medialis_l,masseter
"$bin"/faceanim/faceanim --params "$OUT"/tracks.csv --out "$OUT"/meshes --fps "$FPS"
"$bin"/facerender/facerender "$OUT"/meshes/*.obj --view threequarter --width 480 --height 480 \
  --out "$OUT"/frames/frame.png --video "$OUT"/talkinghead.mp4 --audio "$OUT"/speech.wav --fps "$FPS"
echo "wrote $OUT/talkinghead.mp4 (video + speech), $OUT/tracks.csv, $OUT/tracks.png"
