#!/bin/sh
# ctest browser.threejs (label browser, not in the default run): three.js in headless Debian Chromium
# loads a glTF written by faceanim (named morph targets, weights over time), poses it at the time of
# each key and compares the screenshot with facerender's picture of the same frame (the muscle model):
# the mean absolute difference (MAD, 0–255 per channel) of the matching pose must be under THRESHOLD,
# and under half the MAD against a different pose (so the comparison can fail).
# THRESHOLD 4 (of 255): measured 1.9–2.5 for the same pose — three's Lambert shading has no specular
# highlight, MSAA differs from facerender's 2×2 supersampling, and the glTF's blend of targets differs
# from the muscle model by ≤ a few mm where muscles overlap — and ≥ 4.6 for a different pose (neutral
# against a smile with the jaw open), ≥ 18 with the head turned; 4 lies between the two.
# Usage: tests/browser/check_browser.sh BUILD_DIR WORK_DIR   (needs scripts/setup.sh --browser; 77 = skip)
set -eu
BUILD=$1
WORK=$2
SRC=$(cd "$(dirname "$0")/../.." && pwd)
THRESHOLD=${THRESHOLD:-4}
if ! command -v chromium >/dev/null || [ ! -f "$SRC/tests/browser/node_modules/three/package.json" ]; then
  echo "check_browser: chromium or three.js missing: run scripts/setup.sh --browser"
  exit 77
fi
rm -rf "$WORK"
mkdir -p "$WORK"
cp "$SRC/tests/browser/page.html" "$SRC/tests/browser/page.mjs" "$WORK/"
ln -s "$SRC/tests/browser/node_modules" "$WORK/node_modules"
# three keys: neutral, smile + open jaw + look left, sad brows + head turned
printf 'time,zygomatic_major_l,zygomatic_major_r,masseter,eye_gaze_yaw,frontalis_medialis_l,frontalis_medialis_r,triangularis_l,triangularis_r,head_yaw\n0,0,0,0,0,0,0,0,0,0\n1,1,1,0.5,0.3,0,0,0,0,0\n2,0,0,0,0,1,1,0.8,0.8,0.2\n' >"$WORK/p.csv"
"$BUILD/apps/faceanim/faceanim" --params "$WORK/p.csv" --out "$WORK/frames" --gltf "$WORK/face.glb"
for k in 0 1 2; do
  "$BUILD/apps/facerender/facerender" "$WORK/frames/frame_000$k.obj" --width 240 --height 280 --no-paint \
    --out "$WORK/ref$k.png"
done
PORT=$(python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
python3 -m http.server "$PORT" --bind 127.0.0.1 --directory "$WORK" >"$WORK/server.log" 2>&1 &
SERVER=$!
PROFILE=$(mktemp -d)
trap 'kill $SERVER 2>/dev/null; rm -rf "$PROFILE"' EXIT
i=0
until python3 -c "import urllib.request; urllib.request.urlopen('http://127.0.0.1:$PORT/page.html')" 2>/dev/null; do
  i=$((i + 1)); [ $i -lt 50 ] || { echo "check_browser: server did not start"; exit 1; }; sleep 0.1
done
mad() {  # t ref → MAD
  out=$(timeout 120 chromium --headless --no-sandbox --disable-gpu --disable-quic --no-first-run \
    --disable-background-networking --disable-component-update --disable-sync \
    --enable-unsafe-swiftshader --use-angle=swiftshader --user-data-dir="$PROFILE" \
    --window-size=240,400 --virtual-time-budget=30000 --dump-dom \
    "http://127.0.0.1:$PORT/page.html?glb=face.glb&t=$1&ref=$2&w=240&h=280" 2>/dev/null)
  r=$(printf '%s' "$out" | sed -n 's/.*<pre id="result">\([^<]*\)<.*/\1/p')
  echo "t=$1 vs $2: $r" >&2
  case "$r" in MAD*) printf '%s' "$r" | awk '{print $2}' ;; *) echo "check_browser: page failed: $r" >&2; echo 999 ;; esac
}
fail=0
for k in 0 1 2; do
  same=$(mad "$k" "ref$k.png")
  other=$(mad "$(( (k + 1) % 3 ))" "ref$k.png")
  awk -v s="$same" -v o="$other" -v th="$THRESHOLD" -v k="$k" 'BEGIN {
    ok = (s < th) && (o > 2 * s);
    printf "key %d: MAD same pose %.2f (limit %s), other pose %.2f -> %s\n", k, s, th, o, ok ? "ok" : "FAIL";
    exit !ok }' || fail=1
done
exit $fail
