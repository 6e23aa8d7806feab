#!/usr/bin/env bash
# The default face's pictures in docs/facemesh.md: neutral + the six emotions at 0.9
# (tests/oracle/emotions.csv → emo2muscle → faceanim → facerender), one 7-tile sheet per view.
#   scripts/default_face_pictures.sh [BUILD_DIR]      (needs emo2muscle, faceanim, facerender built)
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${1:-build}/apps
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$bin"/emo2muscle/emo2muscle tests/oracle/emotions.csv --sides -o "$tmp"/muscles.csv
"$bin"/faceanim/faceanim --params "$tmp"/muscles.csv --out "$tmp"/frames
mkdir -p docs/img/facemesh
for v in front threequarter; do
  "$bin"/facerender/facerender "$tmp"/frames/*.obj --view "$v" --width 200 --height 233 --sheet 7 --occlusion 0.4 \
    --out "docs/img/facemesh/default_face_emotions_$v.png"
done
