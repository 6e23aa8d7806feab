#!/bin/sh
# Regenerates data/obie/match_7_4.json (Obie's match, thesis §7.4) from the parlee events
# data/parlee/match.ndjson (themselves made by data/parlee/make_match.py).
# Usage, from the repository root after building:  data/obie/make_match_7_4.sh [path/to/obie]
set -eu
OBIE=${1:-build/apps/obie/obie}
"$OBIE" convert --events data/parlee/match.ndjson --domain ../parlee/football.domain \
  --title "Obie's match (thesis 7.4)" \
  --for team --for-name For --against oteam --against-name Against --duration 90 \
  --key-moment "12:against scores 0-1" --key-moment "30:for equalises 1-1" \
  --key-moment "40.5:free-kick, 2-1" --key-moment "80:against 2-2" \
  --out data/obie/match_7_4.json
