#!/usr/bin/env bash
# The README's main job, in one command: install dependencies, build what it needs, and let Obie
# (the neutral football supporter of thesis chapter 7) watch the §7.4 match on the built-in default
# face: events → emotions (parlee) → expressions (fuzzyexpr) and utterances (espeak-ng) → channels →
# muscle tracks → deformed faces → glTF, MP4 with speech, emotion charts, key-moment sheet, summary.
# Outputs go to out/obie (override with OUT_DIR); extra arguments go to obie (e.g. --fps 15, --rig DIR).
# The expressions contact sheet of the six basic emotions is scripts/expressions.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
BUILD_DIR=${BUILD_DIR:-build}
OUT_DIR=${OUT_DIR:-out/obie}
JOBS=${JOBS:-2}
cmake -S . -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$BUILD_DIR" -j"$JOBS" --target obie
echo "== Obie watches the match of thesis §7.4 (data/obie/match_7_4.json) with the neutral personality"
"$BUILD_DIR"/apps/obie/obie --match data/obie/match_7_4.json --agent data/parlee/agents/neutral.json \
  --out "$OUT_DIR" --seed 1 "$@"
echo "watch $OUT_DIR/obie.mp4; look at $OUT_DIR/key_moments.png and $OUT_DIR/charts.png"
