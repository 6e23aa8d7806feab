#!/bin/sh
# Regenerates the transfer pictures of docs/retarget.md: the six emotions on the MakeHuman head and on a
# remeshed, rotated, decimetre copy of the built-in face, front and three-quarter (retarget --mode
# transfer), and close-ups of the MakeHuman eyes and mouth. Needs a build with the retarget app and tests (build/ by default); the MakeHuman head is data/face/makehuman_head.obj (as ../shared/meshes).
#   scripts/transfer_pictures.sh [BUILD_DIR]
set -eu
here=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$here/build}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
EMOFACE_TRANSFER_DEMO_DIR=$tmp "$build/tests/retarget/retarget_transfer_slow_test" \
  --gtest_filter='Transfer.RotatedDecimetreCopyKeepsItsFrameAndMoves:Transfer.MakeHumanCloseUps' >/dev/null
mkdir -p "$here/docs/img/retarget"
"$build/apps/retarget/retarget" --target "$here/data/face/makehuman_head.obj" --out "$tmp/mh" --tile-width 200 --quiet
"$build/apps/retarget/retarget" --target "$tmp/remeshed_head.obj" --out "$tmp/remeshed" --tile-width 200 --quiet
cp "$tmp/mh/emotions.png" "$here/docs/img/retarget/transfer_makehuman_emotions.png"
cp "$tmp/remeshed/emotions.png" "$here/docs/img/retarget/transfer_remeshed_emotions.png"
cp "$tmp/mh/report.json" "$here/docs/img/retarget/transfer_makehuman_report.json"
cp "$tmp/makehuman_eyes.png" "$here/docs/img/retarget/transfer_makehuman_eyes.png"
cp "$tmp/makehuman_mouth.png" "$here/docs/img/retarget/transfer_makehuman_mouth.png"
