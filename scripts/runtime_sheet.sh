#!/usr/bin/env bash
# docs/img/runtime/sheet.png: a runtime::Character (Python module) at rest, happy, surprised, angry —
# parameters sampled 2 s after each emotion event → faceanim (meshes) → facerender (contact sheet).
# Usage: scripts/runtime_sheet.sh [BUILD_DIR [OUT.png]]   (build with -DEMOFACE_PYTHON=ON)
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR=${1:-build}
OUT=${2:-docs/img/runtime/sheet.png}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
PYTHONPATH="$BUILD_DIR/libs/python" /usr/bin/python3 - "$tmp/p.csv" <<'PY'
import sys
import emoface
c = emoface.Character({"format": "emoface.character", "version": "1.0", "seed": 3})
rows = []
c.update(0.5)
rows.append(list(c.parameters))
for event in ({"emotions": {"happiness": 0.9}}, {"emotions": {"surprise": 1.0}, "replace": True},
              {"emotions": {"anger": 0.8, "disgust": 0.4}, "replace": True}):
    c.push_event(event)
    c.update(2.0)
    rows.append(list(c.parameters))
with open(sys.argv[1], "w") as f:
    f.write("time," + ",".join(emoface.parameter_names()) + "\n")
    for i, r in enumerate(rows):
        f.write(",".join([str(i)] + [repr(x) for x in r]) + "\n")
PY
"$BUILD_DIR"/apps/faceanim/faceanim --params "$tmp/p.csv" --out "$tmp/meshes" --fps 1 >/dev/null
mkdir -p "$(dirname "$OUT")"
"$BUILD_DIR"/apps/facerender/facerender "$tmp"/meshes/frame_000*.obj --sheet 4 --width 240 --height 280 --out "$OUT"
echo "wrote $OUT"
