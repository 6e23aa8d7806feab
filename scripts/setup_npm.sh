#!/usr/bin/env bash
# Installs the test-only npm tools from their lock files (called by scripts/setup.sh):
#   tests/gltf: the Khronos glTF-Validator (gltf-validator, Apache-2.0) for the gltf.validator ctest.
# Needs node and npm (Debian packages nodejs, npm; scripts/setup.sh installs them).
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
for dir in tests/gltf; do
  if [ -f "$ROOT/$dir/node_modules/.package-lock.json" ] &&
     cmp -s "$ROOT/$dir/package-lock.json" "$ROOT/$dir/node_modules/.package-lock.json" 2>/dev/null; then
    echo "setup_npm: $dir up to date"
    continue
  fi
  echo "setup_npm: npm ci in $dir"
  (cd "$ROOT/$dir" && npm ci --no-audit --no-fund --loglevel=error)
done
