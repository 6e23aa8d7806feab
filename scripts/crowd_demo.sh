#!/usr/bin/env bash
# Crowd demo (issue #9 §2; paper Fig. 1 and Fig. 4): four characters of different personalities
# (data/mindmap/crowd: cheerful ana, grumpy ben, hot-tempered rex, timid tess) hear a bang, get a gift,
# are insulted and hear a joke (data/mindmap/crowd_events.ndjson). Their mind maps pick actions, the
# motion graph animates them, the bridge turns the landmark motion into muscle tracks, and the default
# face renders them side by side with a mood strip under each face.
# Builds the two apps it needs, makes the motion graph if it is missing (mgraph generate + build), and
# writes to OUT_DIR (default out/crowd). No setup step: run scripts/setup.sh once if packages are missing.
# Usage: scripts/crowd_demo.sh [OUT_DIR]     env: BUILD_DIR, JOBS, GRAPH (default out/graph.json),
#        SEED (1), WIDTH (pixels per face, 240), FPS (0 = the graph's 30), VIDEO (1; 0 = no MP4)
set -euo pipefail
cd "$(dirname "$0")/.."
OUT=${1:-out/crowd}
BUILD_DIR=${BUILD_DIR:-build}
GRAPH=${GRAPH:-out/graph.json}
cmake -S . -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$BUILD_DIR" -j"${JOBS:-2}" --target mindmap mgraph
bin="$BUILD_DIR"/apps
if [ ! -f "$GRAPH" ]; then
  echo "== motion graph: synthetic CK+-like database → $GRAPH"
  mkdir -p "$(dirname "$GRAPH")"
  "$bin"/mgraph/mgraph generate --out "${GRAPH%.json}_db.json"
  "$bin"/mgraph/mgraph build --db "${GRAPH%.json}_db.json" --out "$GRAPH"
fi
video=()
if [ "${VIDEO:-1}" != 0 ]; then
  if command -v ffmpeg >/dev/null; then video=(--video); else echo "ffmpeg not found: no crowd.mp4"; fi
fi
rm -rf "$OUT"
echo "== crowd: data/mindmap/crowd + data/mindmap/crowd_events.ndjson → $OUT"
"$bin"/mindmap/mindmap crowd --maps data/mindmap/crowd --events data/mindmap/crowd_events.ndjson \
  --graph "$GRAPH" --out "$OUT" --seed "${SEED:-1}" --width "${WIDTH:-240}" --fps "${FPS:-0}" "${video[@]}"
echo "outputs:"
ls -l "$OUT"
echo "key moments (one row per stimulus: bang, gift, insult, joke): $OUT/key_moments.png"
[ -f "$OUT"/crowd.mp4 ] && echo "video: $OUT/crowd.mp4"
exit 0
