#!/usr/bin/env bash
# Regenerates the pictures of docs/engines.md: ARKit shapes on the default face (each ARKit weight
# alone, fitted to face parameters by faceanim --weights arkit) and the six emotions through ARKit
# and back. Usage: scripts/engines_gallery.sh [BUILD_DIR]   (needs emo2muscle, faceanim, facerender)
set -euo pipefail
cd "$(dirname "$0")/.."
B=${1:-build}
T=$(mktemp -d)
[ -z "${KEEP:-}" ] || echo "work dir $T"
trap '[ -n "${KEEP:-}" ] || rm -rf "$T"' EXIT
shapes=(neutral eyeBlink_L browInnerUp browDown_L,browDown_R eyeWide_L,eyeWide_R cheekSquint_L,cheekSquint_R
        noseSneer_L,noseSneer_R mouthSmile_L,mouthSmile_R mouthFrown_L,mouthFrown_R mouthFunnel
        mouthPress_L,mouthPress_R jawOpen)
names=$("$B/apps/emo2muscle/emo2muscle" data/fuzzyexpr/example_emotions.csv --weights arkit | sed -n 2p | cut -d, -f2-)
{
  echo "$names"
  for s in "${shapes[@]}"; do
    row=""
    IFS=, read -ra cols <<<"$names"
    for c in "${cols[@]}"; do
      v=0
      for w in ${s//,/ }; do [ "$w" = "$c" ] && v=1; done
      row+="${row:+,}$v"
    done
    echo "$row"
  done
} >"$T/shapes.csv"
"$B/apps/faceanim/faceanim" --weights arkit --params "$T/shapes.csv" --out "$T/shapes"
mkdir -p docs/img/engines
"$B/apps/facerender/facerender" $(ls "$T"/shapes/frame_*.obj | sort) --sheet 6 --width 200 --height 240 \
  --out docs/img/engines/arkit_shapes.png
# the six emotions (fuzzyexpr at 0.9): parameters, and parameters → ARKit → parameters
printf 'id,sadness,happiness,anger,fear,disgust,surprise\nsad,0.9,0,0,0,0,0\nhappy,0,0.9,0,0,0,0\nangry,0,0,0.9,0,0,0\nafraid,0,0,0,0.9,0,0\ndisgusted,0,0,0,0,0.9,0\nsurprised,0,0,0,0,0,0.9\n' >"$T/emotions.csv"
"$B/apps/emo2muscle/emo2muscle" "$T/emotions.csv" --sides -o "$T/sides.csv"
"$B/apps/emo2muscle/emo2muscle" "$T/emotions.csv" --weights arkit -o "$T/arkit.csv"
"$B/apps/faceanim/faceanim" --params "$T/sides.csv" --out "$T/direct" --ignore-unknown-columns
"$B/apps/faceanim/faceanim" --weights arkit --params "$T/arkit.csv" --out "$T/via_arkit"
"$B/apps/facerender/facerender" $(ls "$T"/direct/frame_*.obj | sort) $(ls "$T"/via_arkit/frame_*.obj | sort) \
  --sheet 6 --width 200 --height 240 --out docs/img/engines/emotions_round_trip.png
echo "wrote docs/img/engines/arkit_shapes.png, docs/img/engines/emotions_round_trip.png"
