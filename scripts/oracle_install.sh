#!/usr/bin/env bash
# Installs what the expression oracles need (scripts/oracle.sh, scripts/oracle_sweep.sh): Node/npm from
# Debian if missing, and the pinned npm packages with `npm ci` into tests/oracle/node_modules
# (tests/oracle/package-lock.json, ≈ 370 MB, once; again only when the lock file is newer).
set -euo pipefail
cd "$(dirname "$0")/.."
if ! command -v node >/dev/null || ! command -v npm >/dev/null; then
  SUDO=""
  if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
  echo "oracle: installing nodejs npm (Debian)"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends nodejs npm
fi
stamp=tests/oracle/node_modules/.package-lock.json
if [ ! -f "$stamp" ] || [ tests/oracle/package-lock.json -nt "$stamp" ]; then
  echo "oracle: npm ci (tests/oracle)"
  npm ci --prefix tests/oracle --no-audit --no-fund --loglevel=error
fi
