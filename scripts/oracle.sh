#!/usr/bin/env bash
# Expression oracle (issue 14): render neutral + the six emotions at 0.9 on the built-in face (front,
# 480×560, at three camera distances: emo2muscle → faceanim → facerender) and let an independent network name them
# (@vladmandic/human's emotion model, tests/oracle/classify.cjs). Prints the confusion table; exit 1
# when fewer than MIN (default 6) of the 7 are top-1 correct.
# Installs Node/npm from Debian if missing and the pinned npm packages with `npm ci`
# (tests/oracle/package-lock.json, ≈ 370 MB in tests/oracle/node_modules, once); nothing is
# downloaded when it runs.
# --arkit (issue 15, the ARKit check): the same emotions through `emo2muscle --weights arkit` (the 52
# ARKit weights per emotion) driving an ARKit character built from our own face — its 52 ARKit morph
# targets baked by muscles::bake_rig, posed as an engine poses them (neutral + Σ weight · target,
# `faceanim --weights arkit --blendshapes`) — rendered and named the same way (OUT_DIR out/oracle_arkit).
# --network faceapi: a second network, @vladmandic/face-api's FaceExpressionNet, names the same renders
# (OUT_DIR out/oracle_faceapi or out/oracle_arkit_faceapi; tests/oracle/classify.cjs explains both).
# Usage: scripts/oracle.sh [--no-build] [--arkit] [--network human|faceapi]   Env: BUILD_DIR (build), OUT_DIR (out/oracle), MIN (6),
#        JOBS (2), EMOTIONS (tests/oracle/emotions.csv), RIG (a rig file or "generic"; default face),
#        DISTANCES ("0.9 1.0 1.1": each face rendered at these camera distances, its scores averaged),
#        OCCLUSION (0.4: facerender --occlusion, the soft ambient occlusion the docs pictures use)
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR=${BUILD_DIR:-build}
OUT_DIR=${OUT_DIR:-}
MIN=${MIN:-6}
JOBS=${JOBS:-2}
EMOTIONS=${EMOTIONS:-tests/oracle/emotions.csv}
RIG=${RIG:-}  # a rig file or "generic"; empty: the built-in default face
DISTANCES=${DISTANCES:-0.9 1.0 1.1}  # camera distances, m (facerender --distance)
OCCLUSION=${OCCLUSION:-0.4}  # facerender --occlusion (0 = the plain render)
rig_args=()
if [ -n "$RIG" ]; then rig_args=(--rig "$RIG"); fi
build=1
arkit=0
network=human
while [ $# -gt 0 ]; do
  case "$1" in
    --no-build) build=0 ;;
    --arkit) arkit=1 ;;
    --network)
      network=${2:-}
      case "$network" in human | faceapi) ;; *) echo "oracle.sh: --network human or faceapi" >&2; exit 2 ;; esac
      shift ;;
    *) echo "oracle.sh: unknown argument $1" >&2; exit 2 ;;
  esac
  shift
done

if [ -z "$OUT_DIR" ]; then
  if [ "$arkit" = 1 ]; then OUT_DIR=out/oracle_arkit; else OUT_DIR=out/oracle; fi
  if [ "$network" = faceapi ]; then OUT_DIR=${OUT_DIR}_faceapi; fi
fi
scripts/oracle_install.sh  # Node/npm (Debian) and the pinned npm packages, once

if [ "$build" = 1 ]; then
  cmake -S . -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Release >/dev/null
  cmake --build "$BUILD_DIR" -j"$JOBS" --target emo2muscle faceanim facerender
fi
bin="$BUILD_DIR"/apps
rm -rf "$OUT_DIR"
mkdir -p "$OUT_DIR"
if [ "$arkit" = 1 ]; then
  "$bin"/emo2muscle/emo2muscle "$EMOTIONS" --weights arkit -o "$OUT_DIR"/arkit.csv
  "$bin"/faceanim/faceanim --weights arkit --blendshapes --ignore-unknown-columns --params "$OUT_DIR"/arkit.csv \
    --out "$OUT_DIR"/frames
else
  "$bin"/emo2muscle/emo2muscle "$EMOTIONS" --sides -o "$OUT_DIR"/muscles.csv
  "$bin"/faceanim/faceanim "${rig_args[@]}" --params "$OUT_DIR"/muscles.csv --out "$OUT_DIR"/frames
fi
# Each face at three camera distances, framed as a portrait (the face box the networks crop lies
# inside the image at all three; at the default framing, 0.75 m, the head fills the frame and
# human's box is clipped by it); a row's scores are the mean of the three (classify.cjs).
args=()
for d in $DISTANCES; do
  mkdir -p "$OUT_DIR/d$d"
  "$bin"/facerender/facerender "${rig_args[@]}" "$OUT_DIR"/frames/*.obj --view front --width 480 --height 560 \
    --distance "$d" --occlusion "$OCCLUSION" --out "$OUT_DIR/d$d/face.png"
  # one frame: facerender writes face.png itself, several: face_0000.png ...
  if [ -f "$OUT_DIR/d$d/face.png" ]; then mv "$OUT_DIR/d$d/face.png" "$OUT_DIR/d$d/face_0000.png"; fi
  i=0
  while IFS=, read -r id _; do
    args+=("$id=$OUT_DIR/d$d/$(printf 'face_%04d.png' "$i")")
    i=$((i + 1))
  done < <(tail -n +2 "$EMOTIONS")
done
node tests/oracle/classify.cjs --network "$network" --min "$MIN" --json "$OUT_DIR"/oracle.json "${args[@]}"
