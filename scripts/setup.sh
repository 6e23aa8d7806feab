#!/usr/bin/env bash
# Installs every Debian package emoface needs to build, test and benchmark. Idempotent: packages
# already installed are skipped, and apt-get runs only when something is missing.
# Usage: scripts/setup.sh            (as root, or as a user with sudo)
set -euo pipefail

PACKAGES=(
  build-essential cmake pkg-config git ca-certificates
  clang libclang-rt-14-dev          # EMOFACE_FUZZ (libFuzzer)
  libeigen3-dev libopenmesh-dev libceres-dev libflann-dev
  nlohmann-json3-dev libcli11-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libfuzzylite-dev                  # test-only oracle (GPL): never linked into a library or app
  libpng-dev zlib1g-dev             # PNG output (facemesh renders, parlee/channels charts, motiongraph sheets)
  libtinygltf-dev                   # facemesh: animated glTF export
  libespeak-ng-dev espeak-ng-data libpugixml-dev   # channels / talkinghead: speech, markup
  ffmpeg                            # core::VideoWriter: facerender, obie, mgraph, mindmap crowd videos
  graphviz                          # core::render_dot: mindmap dot / mgraph dot SVG and PNG pictures
  liblz4-dev                        # retarget: FLANN's k-d tree headers reference LZ4 (linked directly)
)

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#PACKAGES[@]} packages present"
  exit 0
fi
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
echo "setup: installing ${missing[*]}"
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
