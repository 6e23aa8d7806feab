#!/usr/bin/env bash
# Fails if any built emoface library or app links libespeak-ng (GPL-3.0) — directly (a NEEDED entry
# of an executable or shared library) or through a static archive that references its symbols.
# Speech goes through the espeak-ng program in a separate process instead (docs/channels.md).
# Usage: check_no_gpl_link.sh BUILD_DIR
set -euo pipefail
build=${1:?usage: check_no_gpl_link.sh BUILD_DIR}
checked=0
bad=0
while IFS= read -r -d '' f; do
  case "$f" in */CMakeFiles/*|*/_deps/*|*/install_test/*) continue ;; esac
  if readelf -h "$f" >/dev/null 2>&1 && [[ "$f" != *.a ]]; then
    checked=$((checked + 1))
    if readelf -d "$f" 2>/dev/null | grep -E 'NEEDED' | grep -qi 'espeak'; then
      echo "links libespeak-ng (GPL-3.0): $f"; bad=1
    fi
  elif [[ "$f" == *.a ]]; then
    checked=$((checked + 1))
    if nm -u "$f" 2>/dev/null | grep -qE '\bespeak_'; then
      echo "references libespeak-ng symbols (GPL-3.0): $f"; bad=1
    fi
  fi
done < <(find "$build/libs" "$build/apps" -type f \( -name '*.a' -o -name '*.so*' -o -perm -u+x \) -print0 2>/dev/null)
if [ "$checked" -eq 0 ]; then echo "no libraries or apps found under $build"; exit 1; fi
if [ "$bad" -ne 0 ]; then exit 1; fi
echo "checked $checked libraries and apps: none links libespeak-ng"
