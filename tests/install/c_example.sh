#!/usr/bin/env bash
# ctest install.c_example: installs the build tree into a scratch prefix, compiles examples/c/character.c
# as C99 against the installed header, libemoface.so and emoface.pc (pkg-config), and runs it.
# Usage: c_example.sh BUILD_DIR SOURCE_DIR WORK_DIR
set -euo pipefail
build=$1 src=$2 work=$3
rm -rf "$work"
cmake --install "$build" --prefix "$work/prefix" >/dev/null
libdir=$(dirname "$(find "$work/prefix" -name emoface.pc -path '*pkgconfig*' | head -1)")/..
export PKG_CONFIG_PATH="$libdir/pkgconfig"
flags=$(pkg-config --cflags --libs emoface)
cc -std=c99 -Wall -Wextra -Werror -pedantic -o "$work/character" "$src/examples/c/character.c" $flags \
  -Wl,-rpath,"$(cd "$libdir" && pwd)"
# the example must not depend on the build tree
if ldd "$work/character" | grep -q "$build/libs"; then echo "links the build tree"; exit 1; fi
"$work/character"
rm -rf "$work"
