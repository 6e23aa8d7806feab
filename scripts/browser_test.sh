#!/usr/bin/env bash
# The browser test: installs Debian's chromium and three.js (scripts/setup.sh --browser), builds what
# it needs and runs ctest -L browser (three.js in headless Chromium against facerender's frames).
# Usage: scripts/browser_test.sh [BUILD_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
B=${1:-build}
scripts/setup.sh --browser
cmake -S . -B "$B" >/dev/null
cmake --build "$B" -j2 --target faceanim facerender
ctest --test-dir "$B" -L browser --output-on-failure
