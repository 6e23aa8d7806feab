#!/usr/bin/env bash
# Which labels do the expression oracles give the built-in face at all? (issue 14, docs/muscles.md
# "Session 10"). Renders N random symmetric muscle settings — each of the 19 muscles of thesis Table 2.1
# active with probability 0.35 at a level uniform in [0.3, 1], the jaw (masseter) at 0.6 of its draw;
# both sides alike — front, 480×560 at one camera distance with soft ambient occlusion, lets both
# networks of tests/oracle/classify.cjs name every image, and prints per network how often each label
# is top-1 and its largest score over the N faces, then the settings that scored highest for LABELS.
# Same N and SEED: the same settings (Python's random.Random(SEED), stable across Python 3 versions).
# Needs what scripts/oracle.sh needs (it installs Node and the npm packages the same way).
# Usage: scripts/oracle_sweep.sh [--no-build]   Env: N (160), SEED (1), BUILD_DIR (build),
#        OUT_DIR (out/oracle_sweep), DISTANCE (1.0), OCCLUSION (0.4), RIG (as oracle.sh),
#        LABELS ("fear disgust": list the best settings for these), TOP (3)
set -euo pipefail
cd "$(dirname "$0")/.."
N=${N:-160}
SEED=${SEED:-1}
BUILD_DIR=${BUILD_DIR:-build}
OUT_DIR=${OUT_DIR:-out/oracle_sweep}
DISTANCE=${DISTANCE:-1.0}
OCCLUSION=${OCCLUSION:-0.4}
RIG=${RIG:-}
LABELS=${LABELS:-fear disgust}
TOP=${TOP:-3}
rig_args=()
if [ -n "$RIG" ]; then rig_args=(--rig "$RIG"); fi
build=1
while [ $# -gt 0 ]; do
  case "$1" in
    --no-build) build=0 ;;
    *) echo "oracle_sweep.sh: unknown argument $1" >&2; exit 2 ;;
  esac
  shift
done
case "$N" in '' | *[!0-9]*) echo "oracle_sweep.sh: N must be a positive integer" >&2; exit 2 ;; esac
if [ "$N" -lt 1 ] || [ "$N" -gt 5000 ]; then echo "oracle_sweep.sh: N must be in [1, 5000]" >&2; exit 2; fi
case "$SEED" in '' | *[!0-9]*) echo "oracle_sweep.sh: SEED must be a non-negative integer" >&2; exit 2 ;; esac

scripts/oracle_install.sh  # Node/npm (Debian) and the pinned npm packages, once
if [ "$build" = 1 ]; then
  cmake -S . -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Release >/dev/null
  cmake --build "$BUILD_DIR" -j2 --target emo2muscle faceanim facerender
fi
bin="$BUILD_DIR"/apps
rm -rf "$OUT_DIR"
mkdir -p "$OUT_DIR"/render

# The settings: a CSV of the 35 face parameters (the columns of `emo2muscle --sides`, which
# faceanim --params reads), one row per face.
printf 'id,sadness,happiness,anger,fear,disgust,surprise\nx,0,0,0,0,0,0\n' |
  "$bin"/emo2muscle/emo2muscle --sides | grep -v '^#' | head -n 1 > "$OUT_DIR"/columns.csv
python3 - "$N" "$SEED" "$OUT_DIR/settings.csv" "$OUT_DIR/columns.csv" <<'EOF'
import random, sys
n, seed, out = int(sys.argv[1]), int(sys.argv[2]), sys.argv[3]
cols = open(sys.argv[4]).read().strip().split(",")[1:]
base = lambda c: c[:-2] if c[-2:] in ("_l", "_r") else c
muscles = sorted({base(c) for c in cols})  # the draw order, fixed
if len(muscles) != 19:
    sys.exit("oracle_sweep: emo2muscle --sides gave %d muscles, not 19" % len(muscles))
rng = random.Random(seed)
with open(out, "w") as f:
    f.write("id," + ",".join(cols) + "\n")
    for i in range(n):
        v = {}
        for m in muscles:
            if rng.random() < 0.35:
                v[m] = round(rng.uniform(0.3, 1.0), 2)
        if "masseter" in v:
            v["masseter"] = round(0.6 * v["masseter"], 2)
        row = [v.get(base(c), 0.0) for c in cols]
        f.write("s%04d," % i + ",".join("%g" % x for x in row) + "\n")
EOF
"$bin"/faceanim/faceanim "${rig_args[@]}" --params "$OUT_DIR"/settings.csv --out "$OUT_DIR"/frames >/dev/null
"$bin"/facerender/facerender "${rig_args[@]}" "$OUT_DIR"/frames/*.obj --view front --width 480 --height 560 \
  --distance "$DISTANCE" --occlusion "$OCCLUSION" --out "$OUT_DIR"/render/face.png
# one frame: facerender writes face.png itself, several: face_0000.png ... (as oracle.sh)
if [ -f "$OUT_DIR"/render/face.png ]; then mv "$OUT_DIR"/render/face.png "$OUT_DIR"/render/face_0000.png; fi
args=()
for ((i = 0; i < N; ++i)); do args+=("neutral=$OUT_DIR/render/$(printf 'face_%04d.png' "$i")"); done
for network in human faceapi; do
  echo "oracle_sweep: $network names $N faces"
  node tests/oracle/classify.cjs --network "$network" --min 0 --json "$OUT_DIR/$network.json" "${args[@]}" >/dev/null
done

python3 - "$OUT_DIR" "$LABELS" "$TOP" <<'EOF'
import csv, json, sys
out, labels, top = sys.argv[1], sys.argv[2].split(), int(sys.argv[3])
names = ["neutral", "happiness", "sadness", "anger", "fear", "disgust", "surprise"]
rows = list(csv.DictReader(open(out + "/settings.csv")))
print("| network | " + " | ".join(names) + " |")
print("|---" * (len(names) + 1) + "|")
results = {}
for network in ("human", "faceapi"):
    images = json.load(open("%s/%s.json" % (out, network)))["images"]
    if len(images) != len(rows):
        sys.exit("oracle_sweep: %s named %d of %d faces" % (network, len(images), len(rows)))
    results[network] = images
    counts = {k: 0 for k in names}
    for im in images:
        counts[max(names, key=lambda k: im["scores"][k])] += 1
    print("| `%s` top-1 | " % network + " | ".join(str(counts[k]) for k in names) + " |")
    print("| `%s` largest score | " % network +
          " | ".join("%.2f" % max(im["scores"][k] for im in images) for k in names) + " |")
for label in labels:
    for network, images in results.items():
        best = sorted(range(len(images)), key=lambda i: -images[i]["scores"][label])[:top]
        for i in best:
            r = rows[i]
            active = ", ".join("%s %s" % (c[:-2] if c.endswith("_r") else c, v) for c, v in r.items()
                               if c != "id" and not c.endswith("_l") and float(v) > 0)
            print("%s, %s %.2f: %s (%s)" % (label, network, images[i]["scores"][label], r["id"], active))
EOF
