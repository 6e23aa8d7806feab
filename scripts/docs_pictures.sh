#!/usr/bin/env bash
# Regenerates every docs picture of the face that a command in the repository makes (issue 14 item 5),
# so that a change to the face, the muscles, the rules or the renderer is followed by one command:
#   muscles_gallery        docs/img/facemesh/{neutral,regions}.png, docs/img/muscles/*.png
#   default_face_pictures  docs/img/facemesh/default_face_emotions_{front,threequarter}.png
#   facerender             docs/img/facemesh/makehuman_auto_{front,threequarter}.png  (../shared/meshes)
#   transfer_pictures      docs/img/retarget/transfer_*                              (../shared/meshes)
#   retarget deform-source docs/img/retarget/makehuman_{overlay,emotions,error_curve}.png (../shared)
#   engines_gallery        docs/img/engines/{arkit_shapes,emotions_round_trip}.png
#   runtime_sheet          docs/img/runtime/sheet.png                    (needs -DEMOFACE_PYTHON=ON)
#   obie                   docs/img/obie/{key_moments,charts}.png        (the README's main job)
#   mindmap crowd          docs/img/mindmotion/crowd_sheet.png
#   mgraph                 docs/img/motiongraph/{face_labels_sheet,surprise_sheet,surprise_plot,
#                          chain_sheet,chain_plot,mouth_graph}.png, chain.gif
# Pictures of the face with no command (made by hand or by a run not repeated; listed in the docs
# pages beside them): docs/img/engines/{threejs,facerender}_*.png (the browser page),
# docs/img/obie/{frame_40_5,key_moments_makehuman}.png, docs/img/retarget/{align_rotated_*,
# decimated_overlay,synthetic_overlay}.png (test runs on transformed copies).
# Charts without a face (parlee, mindmap, channels) are not touched.
# Usage: scripts/docs_pictures.sh [--no-build] [--only NAME[,NAME...]]   Env: BUILD_DIR (build), JOBS (2)
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR=${BUILD_DIR:-build}
JOBS=${JOBS:-2}
build=1
only=""
while [ $# -gt 0 ]; do
  case "$1" in
    --no-build) build=0 ;;
    --only) only=",$2,"; shift ;;
    *) echo "docs_pictures.sh: unknown argument $1" >&2; exit 2 ;;
  esac
  shift
done
want() { [ -z "$only" ] || [[ "$only" == *",$1,"* ]]; }
shared=../shared/meshes/makehuman_head.obj
B=$BUILD_DIR
if [ "$build" = 1 ]; then
  targets=(emo2muscle faceanim facerender retarget obie mindmap mgraph muscles_gallery)
  if [ -f "$shared" ]; then targets+=(retarget_transfer_slow_test); fi
  cmake -S . -B "$B" -DCMAKE_BUILD_TYPE=Release >/dev/null
  cmake --build "$B" -j"$JOBS" --target "${targets[@]}"
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
step() { echo "== $*"; }

if want gallery; then
  step "muscles_gallery → docs/img/facemesh, docs/img/muscles"
  "$B"/tests/muscles/muscles_gallery docs/img
fi
if want default_face; then
  step "default_face_pictures → docs/img/facemesh/default_face_emotions_*.png"
  scripts/default_face_pictures.sh "$B"
fi
if want makehuman; then
  if [ -f "$shared" ]; then
    step "facerender MakeHuman → docs/img/facemesh/makehuman_auto_*.png"
    for v in front threequarter; do
      "$B"/apps/facerender/facerender "$shared" --view "$v" --width 240 --height 280 \
        --out "docs/img/facemesh/makehuman_auto_$v.png"
    done
    step "retarget --mode deform-source --refine MakeHuman → docs/img/retarget/makehuman_*.png"
    "$B"/apps/retarget/retarget --target "$shared" --mode deform-source --out "$tmp/fit" --refine \
      --tile-width 200 --quiet
    cp "$tmp/fit/overlay.png" docs/img/retarget/makehuman_overlay.png
    cp "$tmp/fit/emotions.png" docs/img/retarget/makehuman_emotions.png
    cp "$tmp/fit/error_curve.png" docs/img/retarget/makehuman_error_curve.png
  else
    echo "skipped (no $shared): makehuman_auto_*, retarget/makehuman_*" >&2
  fi
fi
if want transfer; then
  if [ -f "$shared" ] && [ -x "$B/tests/retarget/retarget_transfer_slow_test" ]; then
    step "transfer_pictures → docs/img/retarget/transfer_*"
    scripts/transfer_pictures.sh "$B"
  else
    echo "skipped (no $shared or retarget_transfer_slow_test): retarget/transfer_*" >&2
  fi
fi
if want engines; then
  step "engines_gallery → docs/img/engines/{arkit_shapes,emotions_round_trip}.png"
  scripts/engines_gallery.sh "$B"
fi
if want runtime; then
  if ls "$B"/libs/python/emoface*.so >/dev/null 2>&1; then
    step "runtime_sheet → docs/img/runtime/sheet.png"
    scripts/runtime_sheet.sh "$B"
  else
    echo "skipped (no Python module in $B; configure with -DEMOFACE_PYTHON=ON): runtime/sheet.png" >&2
  fi
fi
if want obie; then
  step "obie (neutral agent, §7.4 match) → docs/img/obie/{key_moments,charts}.png"
  "$B"/apps/obie/obie --match data/obie/match_7_4.json --agent data/parlee/agents/neutral.json \
    --out "$tmp/obie" --no-video --no-speech >/dev/null
  cp "$tmp/obie/key_moments.png" "$tmp/obie/charts.png" docs/img/obie/
fi
if want crowd || want mgraph; then
  "$B"/apps/mgraph/mgraph generate --out "$tmp/db.json" >/dev/null
  "$B"/apps/mgraph/mgraph build --db "$tmp/db.json" --out "$tmp/graph.json" >/dev/null
fi
if want crowd; then
  step "mindmap crowd → docs/img/mindmotion/crowd_sheet.png"
  "$B"/apps/mindmap/mindmap crowd --maps data/mindmap/crowd --events data/mindmap/crowd_events.ndjson \
    --graph "$tmp/graph.json" --out "$tmp/crowd" --seed 1 --width 160 >/dev/null
  cp "$tmp/crowd/key_moments.png" docs/img/mindmotion/crowd_sheet.png
fi
if want mgraph; then
  step "mgraph → docs/img/motiongraph/*"
  m="$B"/apps/mgraph/mgraph
  "$m" generate --out "$tmp/db2.json" --sheet docs/img/motiongraph/face_labels_sheet.png --columns 4 \
    --cell-width 240 >/dev/null
  "$m" generate --per-label 1 --subjects 7 --out "$tmp/small.json" >/dev/null
  "$m" build --db "$tmp/small.json" --compression 0.9 --out "$tmp/small_graph.json" >/dev/null
  "$m" dot --graph "$tmp/small_graph.json" --region mouth --out docs/img/motiongraph/mouth_graph.png
  "$m" synth --graph "$tmp/graph.json" --labels surprise --out "$tmp/s.json" \
    --sheet docs/img/motiongraph/surprise_sheet.png --plot docs/img/motiongraph/surprise_plot.png \
    --columns 7 --every 3 --cell-width 180 >/dev/null
  "$m" synth --graph "$tmp/graph.json" --labels fear,surprise,happiness --idle 2 --seed 3 --vary \
    --replace 0.3 --out "$tmp/chain.csv" --plot docs/img/motiongraph/chain_plot.png \
    --sheet docs/img/motiongraph/chain_sheet.png --columns 10 --every 8 --cell-width 140 \
    --video docs/img/motiongraph/chain.gif --video-width 320 --video-height 245 >/dev/null
fi
echo "done; look at the pictures (git status docs/img shows which changed)"
