#!/usr/bin/env bash
# Installs the build into a temporary prefix and builds a libvts consumer with pkg-config only,
# as C and as C++ (the public headers must compile and link in both), then runs both on a
# generated store. Also: only the public headers are installed, and libvts.so exports nothing
# but vts_* (the check is shown to fail on a symbol list with an internal name). The same for
# libvts-decode (vts_decode_* only; consumers through vts-decode.pc and vts::decode) and the
# installed vtpipe Python package, which must load the prefix's libvts-decode. The moved prefix's
# tools run with the build tree hidden (a private mount namespace): vt-tiles reads a TGA through
# its own OpenImageIO module and vt-export exports the store.
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
[ "$headers" = "vts.h vts_clipmap.h vts_decode.h vts_wang.h vts_writer.h " ] || fail "installed headers: $headers"
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
# libvts-decode.so: vts_decode_* only; the store's functions are libvts.so's (undefined here).
not_decode() { awk '$2 ~ /^[TDBRVW]$/ && $3 !~ /^vts_decode_/ {print $3}'; }
printf '0000 T vts_decode_tile\n0000 T vts_open\n' | not_decode | grep -x vts_open >/dev/null \
  || fail "the export check does not catch a non-vts_decode_ symbol"
dso=$(ls "$tmp"/prefix/lib*/libvts-decode.so | head -1)
bad=$(nm -D --defined-only "$dso" | not_decode)
[ -z "$bad" ] || fail "libvts-decode.so exports non-vts_decode_ symbols: $(echo $bad)"
count=$(nm -D --defined-only "$dso" | awk '$3 ~ /^vts_decode_/' | wc -l)
[ "$count" -ge 5 ] || fail "libvts-decode.so exports only $count vts_decode_ symbols"
nm -D --undefined-only "$dso" | grep -qw vts_store_read || fail "libvts-decode.so does not use libvts.so"
echo "libvts-decode.so: $count symbols, all vts_decode_*"
[ "$(pkg-config --modversion vts-decode)" = "$(pkg-config --modversion vts)" ] ||
  fail "pkg-config --modversion vts-decode"

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

# libvts-decode through vts-decode.pc, as C and C++: level 0 decoded whole agrees with its tiles.
cc -std=c11 -Wall -Wextra -Werror $(pkg-config --cflags vts-decode) \
  "$src/tests/e2e/install/consumer_decode.c" -o "$tmp/consumer_decode" $(pkg-config --libs vts-decode)
cp "$src/tests/e2e/install/consumer_decode.c" "$tmp/consumer_decode_cxx.cpp"
c++ -std=c++11 -Wall -Wextra -Werror $(pkg-config --cflags vts-decode) "$tmp/consumer_decode_cxx.cpp" \
  -o "$tmp/consumer_decode_cxx" $(pkg-config --libs vts-decode)
decoded=$(LD_LIBRARY_PATH=$(dirname "$libdir") "$tmp/consumer_decode" "$tmp/s.vts") ||
  fail "consumer_decode failed"
echo "consumer_decode: $decoded"
case $decoded in 300x200x4\ fnv1a=*) ;; *) fail "unexpected consumer_decode output: $decoded" ;; esac
out=$(LD_LIBRARY_PATH=$(dirname "$libdir") "$tmp/consumer_decode_cxx" "$tmp/s.vts")
[ "$out" = "$decoded" ] || fail "consumer_decode_cxx: $out"

# The installed Python package: imported from the prefix's site directory, it loads the prefix's
# libvts-decode (found relative to itself) and decodes what the C consumer decoded.
pydir=$(ls -d "$tmp"/prefix/lib/python3*/*-packages | head -1)
test -f "$pydir/vtpipe/__init__.py" || fail "vtpipe not installed in $pydir"
for py in python3 /usr/bin/python3; do "$py" -c 'import numpy' 2>/dev/null && break; done
got=$(cd "$tmp" && PYTHONPATH=$pydir PYTHONDONTWRITEBYTECODE=1 "$py" -c "
import sys, vtpipe
assert vtpipe.__file__.startswith('$pydir/'), vtpipe.__file__
maps = open('/proc/self/maps').read()
assert '$tmp/prefix/lib' in maps and 'libvts-decode.so' in maps and '$build' not in maps, 'libs'
a = vtpipe.open('$tmp/s.vts').level(0, 0)
h = 14695981039346656037
for b in a.tobytes():
    h = ((h ^ b) * 1099511628211) % (1 << 64)
print('%dx%dx%d fnv1a=%016x' % (a.shape[1], a.shape[0], a.shape[2] * a.itemsize, h))") ||
  fail "the installed vtpipe package failed"
[ "$got" = "$decoded" ] || fail "the installed vtpipe package decoded $got, the C consumer $decoded"
echo "python vtpipe (installed): $got"

# find_package(vts): a CMake consumer of the imported target vts::vts; a version the package does
# not have is refused.
mkdir "$tmp/cm"
cp "$src/tests/e2e/install/consumer.c" "$tmp/cm/"
cp "$src/tests/e2e/install/consumer_decode.c" "$tmp/cm/"
cat > "$tmp/cm/CMakeLists.txt" <<'CM'
cmake_minimum_required(VERSION 3.20)
project(consumer C)
find_package(vts ${WANT} REQUIRED)
add_executable(consumer consumer.c)
target_link_libraries(consumer PRIVATE vts::vts)
add_executable(consumer_decode consumer_decode.c)
target_link_libraries(consumer_decode PRIVATE vts::decode)
CM
cmake -S "$tmp/cm" -B "$tmp/cm/build" -DCMAKE_PREFIX_PATH="$tmp/prefix" -DWANT=0.1 >/dev/null ||
  fail "find_package(vts 0.1) failed"
cmake --build "$tmp/cm/build" >/dev/null || fail "the CMake consumer did not build"
out=$("$tmp/cm/build/consumer" "$tmp/s.vts") # the imported target carries libvts's rpath
[ "$out" = "300x200 levels=4 stored=26" ] || fail "unexpected CMake consumer output: $out"
echo "find_package(vts 0.1): $out"
out=$("$tmp/cm/build/consumer_decode" "$tmp/s.vts")
[ "$out" = "$decoded" ] || fail "unexpected CMake consumer_decode output: $out"
echo "find_package(vts 0.1) vts::decode: $out"
if cmake -S "$tmp/cm" -B "$tmp/cm/b99" -DCMAKE_PREFIX_PATH="$tmp/prefix" -DWANT=99 \
   >/dev/null 2>&1; then
  fail "find_package(vts 99) was accepted"
fi

# Man pages, bash completion, the make rules and vt-obj2ply.
tools="vt-atlas vt-convert vt-export vt-info vt-merge vt-obj2ply vt-offset vt-tiles vt-view"
for t in $tools; do
  test -x "$tmp/prefix/bin/$t" || fail "$t not installed"
  page=$tmp/prefix/share/man/man1/$t.1
  grep -q "^\.TH $(echo "$t" | tr a-z A-Z) 1 " "$page" || fail "no man page $page"
  grep -q -- '--help' "$page" || fail "$page does not list the options"
  test -f "$tmp/prefix/share/bash-completion/completions/$t" || fail "no bash completion for $t"
done
cmp "$src/scripts/vt.mk" "$tmp/prefix/share/vtpipe/vt.mk" || fail "share/vtpipe/vt.mk"
echo "man pages, completions and vt.mk: $(echo $tools | wc -w) tools"
bc=/usr/share/bash-completion/bash_completion
if [ -f "$bc" ]; then # complete 'vt-tiles --layo' as bash would
  got=$(PATH=$tmp/prefix/bin:$PATH bash -c "source $bc; source \
    '$tmp/prefix/share/bash-completion/completions/vt-tiles'; COMP_WORDS=(vt-tiles --layo); \
    COMP_CWORD=1; COMP_LINE='vt-tiles --layo'; COMP_POINT=\${#COMP_LINE}; \
    _longopt vt-tiles --layo vt-tiles; echo \"\${COMPREPLY[*]}\"")
  [ "$got" = "--layout" ] || fail "completing 'vt-tiles --layo' gave '$got'"
  echo "bash completion: vt-tiles --layo -> $got"
else
  echo "bash completion: not tried (no $bc)"
fi

# The installed tools, moved with their prefix, load their own OpenImageIO module, never the
# build tree's (LD_DEBUG shows which file dlopen() maps).
if ls "$tmp"/prefix/lib*/vtpipe/libvt_oiio.so >/dev/null 2>&1; then
  mv "$tmp/prefix" "$tmp/moved"
  /usr/bin/python3 -c "from PIL import Image; Image.new('RGB', (70, 50), (10, 200, 30)).save('$tmp/x.tga')"
  (unset VT_OIIO_MODULE; LD_DEBUG=files "$tmp/moved/bin/vt-tiles" -q "$tmp/x.tga" -o "$tmp/x.vts" \
    2>"$tmp/ld.txt") || { cat "$tmp/ld.txt" | grep -v '^ *[0-9]*:' ; fail "installed vt-tiles could not read a TGA"; }
  grep -q "file=$tmp/moved/bin/../lib[^ ]*/vtpipe/libvt_oiio.so" "$tmp/ld.txt" ||
    fail "the moved vt-tiles did not load its own module: $(grep -o 'file=[^ ]*oiio[^ ]*' "$tmp/ld.txt" | head -1)"
  ! grep -q "file=$build" "$tmp/ld.txt" || fail "the installed vt-tiles opened a file of the build tree"
  echo "OpenImageIO module: the moved prefix's own"

  # The same with the build tree gone: a private mount namespace binds an empty folder over it
  # (other tests running meanwhile still see it), then the moved tools read the TGA and export it.
  mkdir "$tmp/empty"
  hidden_run() {
    unshare --map-root-user --mount bash -c '
      set -e; mount --bind "$1" "$2"; [ -z "$(ls -A "$2")" ]
      unset VT_OIIO_MODULE
      "$3/bin/vt-tiles" -q "$4/x.tga" -o "$4/h.vts"
      "$3/bin/vt-export" -q "$4/h.vts" -o "$4/h" --format png --html \
        --openseadragon "$4/osd.js"
      "$3/bin/vt-info" --extract 0 -o "$4/h0.png" "$4/h.vts"' hidden "$tmp/empty" "$build" \
      "$tmp/moved" "$tmp"
  }
  echo 'var OpenSeadragon = null;' >"$tmp/osd.js"
  if unshare --map-root-user --mount true 2>/dev/null; then
    hidden_run || fail "the moved tools failed with the build tree hidden"
    /usr/bin/python3 -c "
from PIL import Image
a, b = Image.open('$tmp/h/h_files/7/0_0.png'), Image.open('$tmp/h0.png')
assert a.size == b.size == (70, 50) and a.tobytes() == b.tobytes(), 'tile != extract'
assert Image.open('$tmp/h/h_files/0/0_0.png').size == (1, 1)" ||
      fail "vt-export with the build tree hidden: the tile is not the extract"
    test -f "$tmp/h/index.html" || fail "no index.html"
    echo "build tree hidden: the moved vt-tiles read a TGA, vt-export exported it (tile = extract)"
  else
    echo "build tree hidden: not tried (unshare --map-root-user --mount is not permitted here)"
  fi
  mv "$tmp/moved" "$tmp/prefix"
fi
echo "ok: install"
