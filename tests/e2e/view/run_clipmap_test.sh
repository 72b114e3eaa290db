#!/usr/bin/env bash
# One vt-view --clipmap test case (tests/e2e/view/CMakeLists.txt, docs/viewer.md "Clipmap mode"):
# a store built by vt-tiles from a generated photo-like image with the hard properties of real
# data (1000 x 700: not a power of two, partial last tiles in both directions, 6 levels, sRGB),
# rendered headless (EGL surfaceless, Mesa llvmpipe).
# usage: run_clipmap_test.sh CASE VT_VIEW VT_TILES VT_INFO VT_SYNTH_IMAGE VTV_CHECK WORKDIR
#        [VTV_MAKE_SPARSE]
# VT_PYTHON (default python3) runs clipmap_check.py, the brute-force model of the uploads.
set -euo pipefail
case_name=$1 view=$2 vt_tiles=$3 vt_info=$4 synth_image=$5 check=$6 work=$7 make_sparse=${8:-}
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
python=${VT_PYTHON:-python3}
rm -rf "$work"
mkdir -p "$work"
cd "$work"
export MESA_SHADER_CACHE_DISABLE=true EGL_LOG_LEVEL=fatal
fail() { echo "FAIL: $*" >&2; exit 1; }
vt() { "$view" "$@" --headless --size 256x256 -q; }

# 64 px payload tiles, border 4: C = 56 content texels; levels 1000, 500, 250, 125, 63, 32 wide.
store() {
  "$synth_image" img.png --format png --size 1000x700 --channels 3 --photo
  "$vt_tiles" img.png -o s.vts --tile-size 64 --keep payload --border 4 --codec png --filter box -q
  "$vt_info" s.vts --json >info.json
}

case $case_name in
strips)
  # A camera path whose centre moves by sub-tile amounts, by whole tiles, diagonally, and jumps
  # (and comes back): per frame, the uploaded tiles equal exactly the model's (clipmap_check.py),
  # and the bytes stay within the budget. Even and odd windows; a budget of 10 tiles per frame
  # (the plan cut mid-strip) and one of 3.
  store
  {
    echo "300 250 1"; echo "300 250 1"; echo "300 250 1"
    for i in 1 2 3 4 5 6; do echo "$((300 + i * 13)).3 250.6 1"; done         # sub-tile
    for i in 1 2 3 4; do echo "$((378 + i * 56)).3 250.6 1"; done             # whole tiles
    for i in 1 2 3 4; do echo "$((602 - i * 56)).3 $((250 + i * 56)).6 1"; done # diagonal
    echo "900.5 650.2 1"; echo "40.2 30.7 1"; echo "40.2 30.7 1"; echo "41 31 1" # jumps
    for i in 1 2 3 4; do echo "378.3 $((474 - i * 112)).1 1"; done           # two tiles a frame
    echo "520 360 1"
  } >path.cam
  for run in "4 125440" "3 125440" "5 37632"; do
    set -- $run
    tag=n$1_b$2
    vt s.vts --clipmap "$1" --budget "$2" --sync --frames 40 --camera path.cam --stats "$tag.json"
    "$python" "$here/clipmap_check.py" strips "$tag.json" info.json || fail "$tag: uploads"
    # negative control: the same check on a list with one tile dropped, or one added, fails
    for t in drop add; do
      if "$python" "$here/clipmap_check.py" strips "$tag.json" info.json --tamper $t >/dev/null; then
        fail "$tag: the check passed a list with one tile $t"
      fi
    done
  done
  # the run did move the windows: several frames uploaded tiles after the first fill
  moved=$("$python" -c 'import json,sys; print(sum(1 for f in json.load(open(sys.argv[1]))["frames"][8:] if f["uploads"]))' n4_b125440.json)
  [ "$moved" -ge 10 ] || fail "only $moved frames after the start uploaded tiles"
  ;;
psnr)
  # Once converged (--sync, every level complete), clipmap renders match the page-table renders of
  # the same view: magnified, 1:1, minified (levels 1-2) and far out (coarse levels), bilinear
  # and trilinear.
  store
  echo "480.3 330.7 2.37" >mag.cam
  echo "300.5 200.5 1" >one.cam
  echo "520.2 310.9 0.41" >min.cam
  echo "480.3 330.7 0.12" >far.cam
  for f in bilinear trilinear; do
    for cam in mag one min far; do
      vt s.vts --clipmap 8 --sync --frames 3 --camera $cam.cam --filtering $f \
        --screenshot clip_${f}_$cam.png --stats clip_${f}_$cam.json
      vt s.vts --sync --frames 16 --camera $cam.cam --filtering $f --screenshot pt_${f}_$cam.png
      "$check" psnr clip_${f}_$cam.png pt_${f}_$cam.png --min 40 || fail "$f $cam: PSNR"
      "$check" stat clip_${f}_$cam.json fallback_pixels == 0 || fail "$f $cam: fallback"
      "$check" stat clip_${f}_$cam.json levels_complete == 6 || fail "$f $cam: levels"
    done
  done
  # negative controls: level 0 addressed one texel off (magnified view), level 1 so (minified),
  # and the view shifted by a texel, each fall below 40 dB
  VTV_CLIPMAP_DEBUG_OFFSET=0 vt s.vts --clipmap 8 --sync --frames 3 --camera mag.cam \
    --screenshot off0.png
  "$check" psnr off0.png pt_bilinear_mag.png --max 40 || fail "a level 0 off by a texel passed"
  VTV_CLIPMAP_DEBUG_OFFSET=1 vt s.vts --clipmap 8 --sync --frames 3 --camera min.cam \
    --screenshot off1.png
  "$check" psnr off1.png pt_bilinear_min.png --max 40 || fail "a level 1 off by a texel passed"
  echo "481.3 330.7 2.37" >shifted.cam
  vt s.vts --clipmap 8 --sync --frames 3 --camera shifted.cam --screenshot shifted.png
  "$check" psnr shifted.png pt_bilinear_mag.png --max 40 || fail "a shifted view passed"
  ;;
wide)
  # Layers that are not RGBA8 u8, in clipmap mode as in the page-table path: an f32 one-channel
  # layer through --range and the dusk ramp (GL_R32F), a u16 sRGB RGB layer (decoded to linear f32
  # RGB), and a one-channel u8 land-class map through index colours, nearest (vtv_check classes):
  # converged frames against the page table's >= 40 dB (74-99 dB measured), at 1:1, minified and
  # magnified; the budget counts the bytes of the upload (C x C x 4, x 12, x 4).
  "$synth_image" f.tif --format tiff --size 700x500 --channels 1 --sample f32
  "$vt_tiles" f.tif -o f.vts --tile-size 64 --border 4 -q
  "$synth_image" u.png --format png --size 700x500 --channels 3 --sample u16
  "$vt_tiles" u.png -o u.vts --tile-size 64 --border 4 -q
  "$check" classes k.png 600 >/dev/null
  "$vt_tiles" k.png -o k.vts --tile-size 64 --border 4 -q
  for z in 1 0.41 2.37; do
    echo "300.3 200.7 $z" >z$z.cam
    for s in "f.vts --range 0.25:2.5 --ramp dusk" "u.vts" "k.vts --ramp index --filtering nearest"; do
      set -- $s
      tag=${1%.vts}_$z
      # Under ASan, LeakSanitizer's tracer crashes at exit of the f32 clipmap runs ("Tracer caught
      # signal 11" on a dynamic-TLS block of Mesa's threads; clang 14 and gcc 12 alike, not with
      # the page table's run): their leak check is off (ASan's checks stay on; valgrind's
      # memcheck of the same run finds no invalid access; the other layers' runs keep it).
      nolsan=
      [ "$1" = f.vts ] && nolsan=${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0
      ASAN_OPTIONS=${nolsan:-${ASAN_OPTIONS:-}} \
        vt "$@" --camera z$z.cam --clipmap 8 --sync --frames 3 --screenshot c_$tag.png \
        --stats c_$tag.json
      vt "$@" --camera z$z.cam --sync --frames 16 --screenshot p_$tag.png
      "$check" psnr c_$tag.png p_$tag.png --min 40 || fail "$tag: PSNR"
      "$check" stat c_$tag.json fallback_pixels == 0 || fail "$tag: fallback"
    done
  done
  grep -q '"tile_bytes": 16384' c_f_1.json || fail "f32 one channel: 64 x 64 x 4 bytes a tile"
  grep -q '"tile_bytes": 49152' c_u_1.json || fail "u16 sRGB RGB: 64 x 64 x 12 bytes a tile"
  "$check" psnr c_f_1.png p_u_1.png --max 30 >/dev/null || fail "different layers compare equal"
  ;;
async)
  # Loader threads (no --sync; also run under ThreadSanitizer): the page table's frame once every
  # level is complete (how many frames that takes depends on the CPU the loaders get: 30, then 4x
  # more frames, at most 4 runs).
  store
  echo "520.2 310.9 0.41" >min.cam
  vt s.vts --sync --frames 16 --camera min.cam --screenshot pt.png
  frames=30
  for try in 1 2 3 4; do
    vt s.vts --clipmap 8 --frames $frames --camera min.cam --screenshot async.png --stats async.json
    "$check" stat async.json levels_complete == 6 >/dev/null && break
    frames=$((frames * 4))
  done
  "$check" stat async.json fallback_pixels == 0 || fail "async: fallback"
  "$check" psnr async.png pt.png --min 40 || fail "async: PSNR"
  ;;
snap)
  # The camera fixed far enough out that every pixel wants level 2 (lambda 2.18) and the frame
  # shows more than level 2's 2 x 2 window (the rest falls back to levels 3 and 4); the paging
  # centre moved by less than a level-2 tile (224 level-0 texels) without crossing its snapping
  # step: level 2's window stays, so every pixel (all of which show level 2 or the coarser
  # levels, whose windows stay too) is byte-identical, while level 0's window did move. A move by
  # a whole level-2 tile changes pixels.
  store
  echo "500 350 0.22" >snap.cam
  for f in bilinear trilinear; do
    for c in 500,350 540,400 724,350; do
      vt s.vts --clipmap 2 --sync --frames 4 --camera snap.cam --filtering $f --clipmap-centre $c \
        --screenshot snap_${f}_$c.png --stats snap_${f}_$c.json
      "$check" stat snap_${f}_$c.json fallback_pixels '>' 1000 || fail "$f $c: no fallback shown"
    done
    "$check" maxdiff snap_${f}_500,350.png snap_${f}_540,400.png 0 0 256 256 --max 0 ||
      fail "$f: a sub-tile move of the centre changed pixels"
    if "$check" maxdiff snap_${f}_500,350.png snap_${f}_724,350.png 0 0 256 256 --max 0; then
      fail "$f: a whole-tile move of the centre changed no pixel"
    fi
    "$python" - snap_${f}_500,350.json snap_${f}_540,400.json <<'EOF' || fail "$f: fronts"
import json, sys
a, b = (json.load(open(p))["last"]["fronts"] for p in sys.argv[1:3])
assert a[0] != b[0], "level 0's window should have moved"
assert a[2:] == b[2:], "levels 2.. should not have moved"
EOF
  done
  ;;
full_size)
  # Precision at full size (as view_full_size for the page table): a 2^20 x 2^20 store with only
  # its far corner's 2 x 2 level-0 tiles stored (vtv_make_sparse), the view there magnified x2.37
  # across the corner tiles' edges, through --clipmap 2 (12 levels, the level-0 window at tiles
  # 1031..1032): >= 40 dB against the CPU reference of the same texels in double precision
  # (54.9 dB measured, as the page table's); a reference moved by 1/8 texel scores < 35 dB.
  "$make_sparse" big.vts
  echo "1048500.3 1048490.7 2.37" >far.cam
  vt big.vts --clipmap 2 --budget 256M --camera far.cam --frames 3 --sync --screenshot far.png \
    --stats far.json
  "$check" stat far.json fallback_pixels == 0 || fail "fallback at the far corner"
  "$check" stat far.json levels_complete == 12 || fail "levels"
  "$make_sparse" --reference ref.png 1048500.3 1048490.7 2.37 256 256
  "$make_sparse" --reference shifted.png 1048500.3 1048490.7 2.37 256 256 --shift 0.125
  "$check" psnr far.png ref.png --min 40 || fail "the far corner against the CPU reference"
  "$check" psnr far.png shifted.png --max 35 || fail "the far corner matches a shifted reference"
  ;;
cli)
  store
  bad() { # EXPECTED-MESSAGE ARGS...: exit 2 and one line naming the problem (plus the "try" line)
    local msg=$1
    shift
    set +e
    "$view" "$@" --headless 2>err.txt
    local rc=$?
    set -e
    [ $rc -eq 2 ] || fail "$*: exit $rc, not 2"
    grep -q -- "$msg" err.txt || fail "$*: message: $(cat err.txt)"
    [ "$(grep -vc "^try 'vt-view --help'" err.txt)" -eq 1 ] || fail "$*: not one line: $(cat err.txt)"
  }
  bad "--clipmap '0': expected a window of 1..256 tiles" s.vts --clipmap 0
  bad "--clipmap '257'" s.vts --clipmap 257
  bad "--clipmap 'x'" s.vts --clipmap x
  bad "--budget '0'" s.vts --clipmap 4 --budget 0
  bad "--budget '12x'" s.vts --clipmap 4 --budget 12x
  bad "--budget '-5'" s.vts --clipmap 4 --budget -5
  bad "--budget 12543: below one tile's upload (12544 bytes" s.vts --clipmap 4 --budget 12543
  bad "--budget and --clipmap-centre need --clipmap N" s.vts --budget 4M
  bad "--budget and --clipmap-centre need --clipmap N" s.vts --clipmap-centre 1,2
  bad "--clipmap-centre '1'" s.vts --clipmap 4 --clipmap-centre 1
  bad "--clipmap and --reference exclude each other" s.vts --clipmap 4 --reference
  bad "--cache is a page-table option" s.vts --clipmap 4 --cache 16
  bad "--ram-cache is a page-table option" s.vts --clipmap 4 --ram-cache 16
  bad "not yet supported" s.vts scene.vt.obj --clipmap 4
  bad "--clipmap and --wang exclude each other" --wang s.vts --clipmap 4
  bad "not anisoN" s.vts --clipmap 4 --filtering aniso4
  # the smallest budget, one tile a frame, and K/M suffixes are accepted
  vt s.vts --clipmap 2 --budget 12544 --sync --frames 2 --stats one.json
  "$check" stat one.json uploads == 1 || fail "one tile a frame"
  vt s.vts --clipmap 2 --budget 13K --sync --frames 1 --stats k.json
  "$check" stat k.json bytes_uploaded == 12544 || fail "13K: one tile"
  # the page-table mode reports bytes_uploaded too: uploads x 64 x 64 x 4 (sRGB RGBA8 payloads)
  vt s.vts --sync --frames 2 --stats pt.json
  "$python" -c 'import json,sys; f=json.load(open(sys.argv[1]))["last"]; assert f["uploads"] > 0 and f["bytes_uploaded"] == f["uploads"] * 64 * 64 * 4, f' pt.json ||
    fail "page-table bytes_uploaded"
  ;;
bc)
  # BC1..BC5 blocks uploaded as stored (docs/viewer.md "Clipmap mode", Texture): an sRGB photo in
  # bc1, a photo with alpha in bc3, a normal map in bc5 (z rebuilt in the shader), 64 px payloads
  # with border 4 (C = 56): converged clipmap frames (compressed texture array) against the page
  # table's (compressed physical texture) >= 40 dB, magnified and minified; one tile's upload is
  # C * C / 2 bytes (bc1) or C * C (bc3, bc5), every frame's bytes are its tiles times that, and
  # a budget of 3 compressed tiles uploads 3 tiles a frame. A border of 6 (content 52, aligned;
  # border not), one of 5 (content 54) and --bc-upload off decode on the CPU (C * C * 4 bytes)
  # and still match.
  "$synth_image" img.png --format png --size 1000x700 --channels 3 --photo
  "$vt_tiles" img.png -o bc1.vts --tile-size 64 --keep payload --border 4 --codec bc1 -q
  "$synth_image" a.png --format png --size 1000x700 --channels 4 --alpha smooth
  "$vt_tiles" a.png -o bc3.vts --tile-size 64 --keep payload --border 4 --codec bc3 -q
  "$vt_tiles" img.png -o bc5.vts --tile-size 64 --keep payload --border 4 --codec bc5 \
    --colour normal -q
  "$vt_tiles" img.png -o b6.vts --tile-size 64 --keep payload --border 6 --codec bc1 -q
  "$vt_tiles" img.png -o b5.vts --tile-size 64 --keep payload --border 5 --codec bc1 -q
  echo "480.3 330.7 2.37" >mag.cam
  echo "520.2 310.9 0.41" >min.cam
  # every frame's bytes_uploaded = tiles_uploaded * B, and B in the header
  bytes_per_tile() {
    "$python" - "$1" "$2" <<'PY' || fail "$1: bytes per tile"
import json, sys
d = json.load(open(sys.argv[1])); b = int(sys.argv[2])
assert d["clipmap"]["tile_bytes"] == b, (d["clipmap"]["tile_bytes"], b)
assert all(f["bytes_uploaded"] == f["tiles_uploaded"] * b for f in d["frames"])
assert sum(f["tiles_uploaded"] for f in d["frames"]) > 0
PY
  }
  for run in "bc1 1568 blocks" "bc3 3136 blocks" "bc5 3136 blocks" "b6 10816 CPU" "b5 11664 CPU" \
    "bc1 12544 CPU --bc-upload off"; do
    set -- $run
    s=$1 bytes=$2 path=$3
    shift 3
    for cam in mag min; do
      tag=${s}_${bytes}_$cam
      "$view" $s.vts "$@" --headless --size 256x256 -v --clipmap 8 --sync --frames 3 \
        --camera $cam.cam --screenshot c_$tag.png --stats c_$tag.json 2>log_$tag.txt
      vt $s.vts --sync --frames 16 --camera $cam.cam --screenshot p_$tag.png
      "$check" psnr c_$tag.png p_$tag.png --min 40 || fail "$tag: PSNR"
      "$check" stat c_$tag.json fallback_pixels == 0 || fail "$tag: fallback"
      bytes_per_tile c_$tag.json $bytes
      if [ $path = blocks ]; then
        grep -q "clipmap: layer 'diffuse': blocks uploaded compressed" log_$tag.txt ||
          fail "$tag: not uploaded as blocks"
      else
        grep -q "clipmap: layer 'diffuse': decoded on the CPU" log_$tag.txt ||
          fail "$tag: not decoded on the CPU"
      fi
    done
  done
  grep -q "z rebuilt in the shader" log_bc5_3136_mag.txt || fail "bc5 normal: z not rebuilt"
  # a budget of 3 compressed tiles (4704 bytes; less than one RGBA8 tile's 12544) uploads 3 tiles
  # a frame until the levels are complete
  vt bc1.vts --clipmap 4 --budget 4704 --sync --frames 12 --camera min.cam --stats budget.json
  "$python" - budget.json <<'PY' || fail "budget of 3 compressed tiles"
import json, sys
d = json.load(open(sys.argv[1]))
assert d["clipmap"]["tiles_per_frame"] == 3, d["clipmap"]
up = [f["tiles_uploaded"] for f in d["frames"]]
last = max(i for i, u in enumerate(up) if u)
assert all(u == 3 for u in up[:last]) and 1 <= up[last] <= 3, up
assert all(f["bytes_uploaded"] <= 4704 for f in d["frames"]), up
PY
  # negative controls: level 0 (magnified) or level 1 (minified) addressed one texel off in the
  # compressed array falls below 40 dB
  VTV_CLIPMAP_DEBUG_OFFSET=0 vt bc1.vts --clipmap 8 --sync --frames 3 --camera mag.cam \
    --screenshot off0.png
  "$check" psnr off0.png p_bc1_1568_mag.png --max 40 || fail "bc1: a level 0 off by a texel passed"
  VTV_CLIPMAP_DEBUG_OFFSET=1 vt bc5.vts --clipmap 8 --sync --frames 3 --camera min.cam \
    --screenshot off1.png
  "$check" psnr off1.png p_bc5_3136_min.png --max 40 || fail "bc5: a level 1 off by a texel passed"
  ;;
bc_strips)
  # The strips test's moving centre over a bc1 store uploaded as blocks: the uploads equal the
  # model's (clipmap_check.py) with one tile's upload C * C / 2 = 1568 bytes, under a budget of
  # 10 and of 3 compressed tiles; one tile dropped or added fails.
  "$synth_image" img.png --format png --size 1000x700 --channels 3 --photo
  "$vt_tiles" img.png -o s.vts --tile-size 64 --keep payload --border 4 --codec bc1 -q
  "$vt_info" s.vts --json >info.json
  {
    echo "300 250 1"; echo "300 250 1"
    for i in 1 2 3 4 5 6; do echo "$((300 + i * 13)).3 250.6 1"; done
    for i in 1 2 3 4; do echo "$((378 + i * 56)).3 250.6 1"; done
    for i in 1 2 3 4; do echo "$((602 - i * 56)).3 $((250 + i * 56)).6 1"; done
    echo "900.5 650.2 1"; echo "40.2 30.7 1"; echo "41 31 1"
  } >path.cam
  for run in "4 15680" "5 4704"; do
    set -- $run
    tag=n$1_b$2
    vt s.vts --clipmap "$1" --budget "$2" --sync --frames 30 --camera path.cam --stats "$tag.json"
    "$python" "$here/clipmap_check.py" strips "$tag.json" info.json --tile-bytes 1568 ||
      fail "$tag: uploads"
    for t in drop add; do
      if "$python" "$here/clipmap_check.py" strips "$tag.json" info.json --tamper $t \
        --tile-bytes 1568 >/dev/null; then
        fail "$tag: the check passed a list with one tile $t"
      fi
    done
    # and the RGBA8 size is not what was uploaded
    if "$python" "$here/clipmap_check.py" strips "$tag.json" info.json >/dev/null; then
      fail "$tag: the check passed 4 bytes a texel"
    fi
  done
  ;;
*)
  fail "unknown case $case_name"
  ;;
esac
echo "ok: $case_name"
