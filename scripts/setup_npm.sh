#!/usr/bin/env bash
# Installs the test-only npm tools from their lock files (called by scripts/setup.sh):
#   tests/gltf: the Khronos glTF-Validator (gltf-validator, Apache-2.0) for the gltf.validator ctest;
#   tests/browser (with --browser): three.js (three, MIT) for the browser.threejs ctest.
# Needs node and npm (Debian packages nodejs, npm; scripts/setup.sh installs them).
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
DIRS=(tests/gltf)
if [ "${1:-}" = "--browser" ]; then DIRS+=(tests/browser); fi
for dir in "${DIRS[@]}"; do
  if [ -d "$ROOT/$dir/node_modules" ] && (cd "$ROOT/$dir" && npm ls --all >/dev/null 2>&1); then
    echo "setup_npm: $dir up to date"
    continue
  fi
  echo "setup_npm: npm ci in $dir"
  (cd "$ROOT/$dir" && npm ci --no-audit --no-fund --loglevel=error)
done
