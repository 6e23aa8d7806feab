#!/bin/sh
# ctest gltf.validator: every kind of glTF the apps write passes the Khronos glTF-Validator with
# 0 errors and 0 warnings (faceanim's with eye and jaw nodes, from ARKit weights, Obie's, and a user's
# own skinned glTF with our targets added), and Obie's face.glb for the §7.4 match stays under 4 MiB.
# Usage: tests/gltf/check_gltf.sh BUILD_DIR WORK_DIR   (needs scripts/setup_npm.sh; exit 77 = skip)
set -eu
BUILD=$1
WORK=$2
SRC=$(cd "$(dirname "$0")/../.." && pwd)
if [ ! -f "$SRC/tests/gltf/node_modules/gltf-validator/package.json" ] || ! command -v node >/dev/null; then
  echo "check_gltf: glTF-Validator not installed: run scripts/setup.sh (it calls scripts/setup_npm.sh)"
  exit 77
fi
rm -rf "$WORK"
mkdir -p "$WORK"
printf 'time,zygomatic_major_l,zygomatic_major_r,masseter,eye_gaze_yaw,eye_gaze_pitch,head_yaw,head_roll,eye_blink_l\n0,0,0,0,0,0,0,0,0\n0.5,1,1,0.4,0.3,-0.2,0.2,0.1,1\n1,0,0,0,-0.3,0.1,-0.1,0,0\n' > "$WORK/p.csv"
"$BUILD/apps/faceanim/faceanim" --params "$WORK/p.csv" --gltf "$WORK/faceanim.gltf"
"$BUILD/apps/faceanim/faceanim" --params "$WORK/p.csv" --gltf "$WORK/faceanim.glb"
"$BUILD/apps/emo2muscle/emo2muscle" "$SRC/data/fuzzyexpr/example_emotions.csv" --weights arkit -o "$WORK/arkit.csv"
"$BUILD/apps/faceanim/faceanim" --weights arkit --params "$WORK/arkit.csv" --gltf "$WORK/arkit.glb"
"$BUILD/apps/obie/obie" --match "$SRC/data/obie/match_7_4.json" --agent "$SRC/data/parlee/agents/neutral.json" \
  --out "$WORK/obie" --no-video --no-speech --quiet >/dev/null
size=$(stat -c %s "$WORK/obie/face.glb")
echo "obie face.glb: $size bytes"
if [ "$size" -ge 4194304 ]; then
  echo "check_gltf: Obie's face.glb is $size bytes, over the 4 MiB budget"
  exit 1
fi
# a user's own character (skin, UVs + texture, a target and an animation of theirs) rigged by the
# transfer and animated by faceanim: their file with our targets and animation added
"$BUILD/tests/make_user_gltf" "$WORK/user.gltf"
"$BUILD/apps/retarget/retarget" --target "$WORK/user.gltf" --out "$WORK/user_rig" --generations 2 --population 6 \
  --quiet --no-png
"$BUILD/apps/faceanim/faceanim" --rig "$WORK/user_rig/face.rig" --params "$WORK/p.csv" --gltf "$WORK/user_anim.glb"
# the same with their morph target as a sparse accessor (as engines export them): the transfer keeps
# it, faceanim adds ours after it
"$BUILD/tests/make_user_gltf" "$WORK/user_sparse.gltf" --sparse
"$BUILD/apps/retarget/retarget" --target "$WORK/user_sparse.gltf" --out "$WORK/user_sparse_rig" --generations 2 \
  --population 6 --quiet --no-png
"$BUILD/apps/faceanim/faceanim" --rig "$WORK/user_sparse_rig/face.rig" --params "$WORK/p.csv" \
  --gltf "$WORK/user_sparse_anim.glb"
node "$SRC/tests/gltf/validate.mjs" "$WORK/faceanim.gltf" "$WORK/faceanim.glb" "$WORK/arkit.glb" "$WORK/obie/face.glb" \
  "$WORK/user.gltf" "$WORK/user_anim.glb" "$WORK/user_sparse.gltf" "$WORK/user_sparse_rig/face.glb" \
  "$WORK/user_sparse_anim.glb"
