#!/usr/bin/env bash
# Installs the build into a temporary prefix and builds a libvts consumer with pkg-config only,
# as C and as C++ (the public headers must compile and link in both), then runs both on a
# generated store. Also: only the public headers are installed, and libvts.so exports nothing
# but vts_* (the check is shown to fail on a symbol list with an internal name).
# usage: check_install.sh BUILD_DIR SOURCE_DIR VT_SYNTH
set -euo pipefail
build=$1 src=$2 synth=$3
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
cmake --install "$build" --prefix "$tmp/prefix" >/dev/null
libdir=$(ls -d "$tmp"/prefix/lib*/pkgconfig | head -1)
export PKG_CONFIG_PATH=$libdir
[ "$(pkg-config --modversion vts)" != "" ] || fail "pkg-config --modversion vts"
headers=$(cd "$tmp/prefix/include/vts" && ls | tr '\n' ' ')
[ "$headers" = "vts.h vts_writer.h " ] || fail "installed headers: $headers"
test -x "$tmp/prefix/bin/vt-info" || fail "vt-info not installed"

# Exported symbols: every defined dynamic symbol of libvts.so is vts_*.
not_vts() { awk '$2 ~ /^[TDBRVW]$/ && $3 !~ /^vts_/ {print $3}'; }
printf '0000 T vts_open\n0000 T vt_error_set\n0000 U malloc\n' | not_vts | grep -x vt_error_set >/dev/null \
  || fail "the export check does not catch an internal symbol"
so=$(ls "$tmp"/prefix/lib*/libvts.so | head -1)
bad=$(nm -D --defined-only "$so" | not_vts)
[ -z "$bad" ] || fail "libvts.so exports non-vts_ symbols: $(echo $bad)"
count=$(nm -D --defined-only "$so" | awk '$3 ~ /^vts_/' | wc -l)
[ "$count" -ge 30 ] || fail "libvts.so exports only $count vts_ symbols"
echo "libvts.so: $count symbols, all vts_*"

cc -std=c11 -Wall -Wextra -Werror $(pkg-config --cflags vts) "$src/tests/e2e/install/consumer.c" \
  -o "$tmp/consumer" $(pkg-config --libs vts)
cp "$src/tests/e2e/install/consumer.c" "$tmp/consumer_cxx.cpp"
c++ -std=c++11 -Wall -Wextra -Werror $(pkg-config --cflags vts) "$tmp/consumer_cxx.cpp" \
  -o "$tmp/consumer_cxx" $(pkg-config --libs vts)
printf '#include <vts_writer.h>\nint main(void){return vts_writer_destroy(0), 0;}\n' > "$tmp/writer.cpp"
c++ -Wall -Wextra -Werror $(pkg-config --cflags vts) "$tmp/writer.cpp" -o "$tmp/writer" \
  $(pkg-config --libs vts)
"$synth" "$tmp/s.vts" --size 300x200 --tile 64 --border 2 --empty
# 300x200 with 64 px tiles: 5x4 + 3x2 + 2x1 + 1 = 29 tiles, 3 of level 0 empty ((tx + 2ty) % 7 == 3)
for c in consumer consumer_cxx; do
  out=$(LD_LIBRARY_PATH=$(dirname "$libdir") "$tmp/$c" "$tmp/s.vts")
  echo "$c: $out"
  [ "$out" = "300x200 levels=4 stored=26" ] || fail "unexpected $c output: $out"
done
