#!/usr/bin/env bash
# docs/img/runtime/mindmotion_sheet.png: rex (data/mindmap/crowd/rex.json) as a runtime character of
# the mindmotion source (issue 19 item 5), driven through the Python module with a weight-space
# ARKit graph made by `mgraph` (default generated size). Each row is one seed: at rest, then 1 s
# after a joke, an insult and a bang (one stimulus each, the face of the last frame) — the rows
# differ by the seed (§5.1 variation, the mind map's choices). → faceanim → facerender.
# Usage: scripts/runtime_mindmotion_sheet.sh [BUILD_DIR [OUT.png]]  (build with -DEMOFACE_PYTHON=ON)
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR=${1:-build}
OUT=${2:-docs/img/runtime/mindmotion_sheet.png}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$BUILD_DIR"/apps/mgraph/mgraph generate --space arkit --out "$tmp/db.json" >/dev/null
"$BUILD_DIR"/apps/mgraph/mgraph build --db "$tmp/db.json" --out "$tmp/graph.json" >/dev/null
PYTHONPATH="$BUILD_DIR/libs/python" /usr/bin/python3 - "$tmp/graph.json" "$tmp/p.csv" <<'PY'
import sys
import emoface
graph, out = sys.argv[1], sys.argv[2]
rows = []
for seed in (1, 2):
    c = emoface.Character.mindmotion(graph, "data/mindmap/crowd/rex.json",
                                     {"format": "emoface.character", "version": "1.1", "seed": seed,
                                      "blinks": False, "gaze_noise": False, "head_noise": False})
    c.update(1.0)
    rows.append(list(c.parameters))
    for stimulus in ("joke", "insult", "bang"):
        applied, message = c.push_stimulus(stimulus)
        assert applied, message
        c.update(1.0)
        rows.append(list(c.parameters))
with open(out, "w") as f:
    f.write("time," + ",".join(emoface.parameter_names()) + "\n")
    for i, r in enumerate(rows):
        f.write(",".join([str(i)] + [repr(x) for x in r]) + "\n")
PY
"$BUILD_DIR"/apps/faceanim/faceanim --params "$tmp/p.csv" --out "$tmp/meshes" --fps 1 >/dev/null
mkdir -p "$(dirname "$OUT")"
"$BUILD_DIR"/apps/facerender/facerender "$tmp"/meshes/frame_000*.obj --sheet 4 --width 240 \
  --height 280 --out "$OUT"
echo "wrote $OUT"
