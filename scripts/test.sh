#!/usr/bin/env bash
# One command: install dependencies, build everything, run the default test suite.
# Usage: scripts/test.sh [extra cmake -D options]   e.g. scripts/test.sh -DEMOFACE_SANITIZE=ON
# Env: BUILD_DIR (default build), JOBS (default 2).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
BUILD_DIR=${BUILD_DIR:-build}
JOBS=${JOBS:-2}
# -DEMOFACE_PYTHON=ON: the Python module and its pytest suite are part of the default run.
cmake -S . -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Release -DEMOFACE_PYTHON=ON "$@"
cmake --build "$BUILD_DIR" -j"$JOBS"
# Slow suites carry the label "slow" and stay out of the default run (ctest -L slow runs them).
ctest --test-dir "$BUILD_DIR" -j"$JOBS" --output-on-failure -LE slow
