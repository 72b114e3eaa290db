#!/usr/bin/env bash
# Installs the build into a temporary prefix and builds a libvts consumer with pkg-config only,
# as C and as C++ (the public headers must compile in both), then runs it on a generated store.
# usage: check_install.sh BUILD_DIR SOURCE_DIR VT_SYNTH
set -euo pipefail
build=$1 src=$2 synth=$3
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cmake --install "$build" --prefix "$tmp/prefix" >/dev/null
libdir=$(ls -d "$tmp"/prefix/lib*/pkgconfig | head -1)
export PKG_CONFIG_PATH=$libdir
[ "$(pkg-config --modversion vts)" != "" ]
for f in vts.h vts_writer.h vt_error.h; do
  [ -f "$tmp/prefix/include/vts/$f" ] || { echo "missing installed header $f"; exit 1; }
done
test -x "$tmp/prefix/bin/vt-info" || { echo "vt-info not installed"; exit 1; }
cc -std=c11 -Wall -Wextra -Werror $(pkg-config --cflags vts) "$src/tests/e2e/install/consumer.c" \
  -o "$tmp/consumer" $(pkg-config --libs vts)
printf '#include <vts.h>\n#include <vts_writer.h>\nint main(void){return 0;}\n' > "$tmp/cxx.cpp"
c++ -Wall -Wextra -Werror $(pkg-config --cflags vts) "$tmp/cxx.cpp" -o "$tmp/cxx"
"$synth" "$tmp/s.vts" --size 300x200 --tile 64 --border 2 --empty
out=$(LD_LIBRARY_PATH=$(dirname "$libdir") "$tmp/consumer" "$tmp/s.vts")
echo "$out"
# 300x200 with 64 px tiles: 5x4 + 3x2 + 2x1 + 1 = 29 tiles, 3 of level 0 empty ((tx + 2ty) % 7 == 3)
[ "$out" = "300x200 levels=4 stored=26" ] || { echo "unexpected consumer output: $out"; exit 1; }
