#!/usr/bin/env bash
# clang-format check on the C++ files changed against a base (issue 18, docs/architecture.md#formatting):
#   scripts/check_format.sh [BASE]     BASE defaults to main, else origin/main
# Runs `clang-format --dry-run -Werror` with the repository's .clang-format on the *changed lines*
# (--lines, from `git diff -U0` against the merge base with BASE) of every added, copied, modified or
# renamed *.cpp/*.hpp/*.h/*.cc, and on the whole of untracked new ones. Older lines nobody touched are
# not reported. Fix a file the same way: scripts/check_format.sh --fix [BASE].
# Exit 0: all formatted (or nothing changed); 1: some file needs formatting (listed); 2: usage/setup.
#
#   scripts/check_format.sh --tree           every tracked C++ file, whole, except the older ones listed
#                                            in scripts/format_legacy.txt (the ctest `format`: needs no
#                                            base, so it runs on CI's fresh clone). A listed file that is
#                                            now clean, or gone, is an error too: the list only shrinks.
#   scripts/check_format.sh --write-legacy   rewrites that list (the files not clean today).
# Exit 77 in these two modes when clang-format or git is missing (ctest SKIP_RETURN_CODE).
set -euo pipefail
cd "$(dirname "$0")/.."
CLANG_FORMAT=${CLANG_FORMAT:-clang-format}
LEGACY=scripts/format_legacy.txt
if [ "${1:-}" = "--tree" ] || [ "${1:-}" = "--write-legacy" ]; then
  mode=$1
  if ! command -v "$CLANG_FORMAT" >/dev/null 2>&1 || ! command -v git >/dev/null 2>&1 ||
     ! git rev-parse --is-inside-work-tree >/dev/null 2>&1; then
    echo "check_format: clang-format, git or a git checkout missing: skipped" >&2
    exit 77
  fi
  mapfile -t all < <(git ls-files -- '*.cpp' '*.hpp' '*.h' '*.cc')
  # One clang-format run over every file; the files it would change are those it names in a
  # "-Wclang-format-violations" diagnostic.
  declare -A unclean=()
  while read -r f; do unclean[$f]=1; done < <(
    "$CLANG_FORMAT" --dry-run --style=file "${all[@]}" 2>&1 |
      sed -n 's/^\(.*\):[0-9]*:[0-9]*: \(warning\|error\): code should be clang-formatted.*/\1/p' |
      sort -u)
  clean() { [ -z "${unclean[$1]:-}" ]; }
  if [ "$mode" = --write-legacy ]; then
    {
      echo "# C++ files older than the formatting rule (issue 18) that clang-format would still change."
      echo "# Checked by scripts/check_format.sh --tree (ctest: format); regenerate with --write-legacy."
      for f in "${all[@]}"; do clean "$f" || echo "$f"; done
    } > "$LEGACY"
    echo "check_format: $(grep -vc '^#' "$LEGACY") legacy file(s) listed in $LEGACY"
    exit 0
  fi
  declare -A listed=()
  if [ -f "$LEGACY" ]; then
    while read -r f; do
      case "$f" in ''|'#'*) continue ;; esac
      listed[$f]=1
    done < "$LEGACY"
  fi
  declare -A tracked=()
  bad=0
  for f in "${all[@]}"; do
    tracked[$f]=1
    if [ -n "${listed[$f]:-}" ]; then
      if clean "$f"; then
        echo "now formatted, remove it from $LEGACY: $f"
        bad=$((bad + 1))
      fi
    elif ! clean "$f"; then
      echo "needs clang-format (clang-format -i $f): $f"
      bad=$((bad + 1))
    fi
  done
  for f in "${!listed[@]}"; do
    if [ -z "${tracked[$f]:-}" ]; then
      echo "listed in $LEGACY but not a tracked file: $f"
      bad=$((bad + 1))
    fi
  done
  if [ "$bad" -gt 0 ]; then
    echo "check_format: $bad problem(s): clang-format -i the files named; delete the now-formatted" \
         "ones from $LEGACY (--write-legacy would also list new unformatted files: do not)" >&2
    exit 1
  fi
  echo "check_format: ${#all[@]} files, $(( ${#all[@]} - ${#listed[@]} )) formatted, ${#listed[@]} legacy"
  exit 0
fi
if ! command -v "$CLANG_FORMAT" >/dev/null 2>&1; then
  echo "check_format: $CLANG_FORMAT not found (Debian package clang-format, scripts/setup.sh)" >&2
  exit 2
fi
fix=0
if [ "${1:-}" = "--fix" ]; then fix=1; shift; fi
base=${1:-}
if [ -z "$base" ]; then
  for candidate in main origin/main; do
    if git rev-parse --verify -q "$candidate" >/dev/null; then base=$candidate; break; fi
  done
fi
if [ -z "$base" ] || ! git rev-parse --verify -q "$base" >/dev/null; then
  echo "check_format: no base to compare with (give one: scripts/check_format.sh origin/main)" >&2
  exit 2
fi
merge_base=$(git merge-base "$base" HEAD)
mapfile -t files < <({ git diff --name-only --diff-filter=ACMR "$merge_base" -- \
                         '*.cpp' '*.hpp' '*.h' '*.cc';
                       git ls-files --others --exclude-standard -- '*.cpp' '*.hpp' '*.h' '*.cc'; } |
                     sort -u)
if [ ${#files[@]} -eq 0 ]; then
  echo "check_format: no C++ files changed against $base"
  exit 0
fi
# The changed line ranges of a tracked file as --lines=A:B arguments (none for a new untracked file).
line_args() {
  git diff -U0 "$merge_base" -- "$1" |
    sed -n 's/^@@ -[0-9,]* +\([0-9]*\)\(,\([0-9]*\)\)\? @@.*/\1 \3/p' |
    while read -r start count; do
      count=${count:-1}
      [ "$count" -eq 0 ] && continue
      echo "--lines=$start:$((start + count - 1))"
    done
}
bad=0
checked=0
for f in "${files[@]}"; do
  [ -f "$f" ] || continue
  args=()
  if git ls-files --error-unmatch "$f" >/dev/null 2>&1; then
    mapfile -t args < <(line_args "$f")
    [ ${#args[@]} -eq 0 ] && continue  # only deletions
  fi
  checked=$((checked + 1))
  if [ "$fix" = 1 ]; then
    "$CLANG_FORMAT" -i --style=file "${args[@]}" "$f"
  elif ! "$CLANG_FORMAT" --dry-run -Werror --style=file "${args[@]}" "$f" >/dev/null 2>&1; then
    echo "needs clang-format: $f"
    bad=$((bad + 1))
  fi
done
if [ "$bad" -gt 0 ]; then
  echo "check_format: $bad of $checked changed file(s) need formatting" \
       "(scripts/check_format.sh --fix $base)" >&2
  exit 1
fi
echo "check_format: changed lines of $checked file(s) formatted"
