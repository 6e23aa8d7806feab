#!/usr/bin/env bash
# Installs every Debian package emoface needs to build, test and benchmark. Idempotent: packages
# already installed are skipped, and apt-get runs only when something is missing.
# Usage: scripts/setup.sh            (as root, or as a user with sudo)
set -euo pipefail
# --browser: also Debian's chromium and three.js (npm) for the browser test (ctest -L browser,
# scripts/browser_test.sh). Never a browser from npm.
BROWSER=0
if [ "${1:-}" = "--browser" ]; then BROWSER=1; fi

PACKAGES=(
  build-essential cmake pkg-config git ca-certificates
  clang libclang-rt-14-dev          # EMOFACE_FUZZ (libFuzzer)
  libeigen3-dev libopenmesh-dev libflann-dev
  libceres-dev                      # headers only (TinySolver, Jet): libceres is never linked
  nlohmann-json3-dev libcli11-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libfuzzylite-dev                  # test-only oracle (GPL): never linked into a library or app
  libpng-dev zlib1g-dev             # PNG output (facemesh renders, parlee/channels charts, motiongraph sheets)
  libtinygltf-dev                   # facemesh: animated glTF export
  espeak-ng espeak-ng-data libpugixml-dev   # channels: the espeak-ng *program* (run, never linked), markup
  ffmpeg                            # core::VideoWriter: facerender, obie, mgraph, mindmap crowd videos
  graphviz                          # core::render_dot: mindmap dot / mgraph dot SVG and PNG pictures
  liblz4-dev                        # retarget: FLANN's k-d tree headers reference LZ4 (linked directly)
  nodejs                            # test-only: the Khronos glTF-Validator (scripts/setup_npm.sh)
  python3-dev python3-pybind11 pybind11-dev python3-numpy python3-pytest   # EMOFACE_PYTHON: import emoface
  clang-format                      # scripts/check_format.sh (changed lines, docs/architecture.md)
  python3-dask python3-distributed  # the Dask recipe of docs/scale-out.md and its test (ctest -L slow)
)
if [ "$BROWSER" = 1 ]; then PACKAGES+=(chromium); fi
# Debian's npm package; a nodejs from elsewhere (e.g. NodeSource) bundles npm and conflicts with it.
if ! command -v npm >/dev/null 2>&1; then PACKAGES+=(npm); fi

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#PACKAGES[@]} packages present"
  "$(dirname "$0")/setup_npm.sh" $([ "$BROWSER" = 1 ] && echo --browser)
  exit 0
fi
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
echo "setup: installing ${missing[*]}"
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
"$(dirname "$0")/setup_npm.sh" $([ "$BROWSER" = 1 ] && echo --browser)
