#!/usr/bin/env bash
# vt-view --terrain (tests/e2e/view/CMakeLists.txt, docs/viewer.md "Terrain"): a generated DEM
# (vtv_terrain_ref dem: 1001 x 707, hills, a sharp ridge, a valley, a plateau, a nodata hole) built
# as f32 and as u16 with --value-scale/--value-offset, draped with a photograph (autumn leaves) from
# Debian's plasma-workspace-wallpapers, rendered headless and compared with a CPU reference of the displaced
# grid (vtv_terrain_ref render).
# Terrain in clipmap mode (--clipmap N): against the page-table render and the CPU reference, and
# a fly-over path whose uploads clipmap_check.py checks against its model.
# usage: run_terrain_test.sh CASE VT_VIEW VT_TILES VTV_TERRAIN_REF VTV_CHECK WORKDIR [VT_INFO]
# VT_PYTHON (default python3) runs clipmap_check.py.
set -euo pipefail
case_name=$1 view=$2 tiles=$3 ref=$4 check=$5 work=$6 vt_info=${7:-}
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
python=${VT_PYTHON:-python3}
rm -rf "$work"
mkdir -p "$work"
cd "$work"
export MESA_SHADER_CACHE_DISABLE=true EGL_LOG_LEVEL=fatal
fail() { echo "FAIL: $*" >&2; exit 1; }
photo=/usr/share/wallpapers/Autumn/contents/images/2560x1600.jpg
if [ ! -r "$photo" ]; then
  echo "SKIP: $photo missing (install plasma-workspace-wallpapers: scripts/setup)"
  exit 77
fi
command -v gdal_translate >/dev/null || { echo "SKIP: gdal_translate missing (gdal-bin)"; exit 77; }
command -v oiiotool >/dev/null || { echo "SKIP: oiiotool missing (openimageio-tools)"; exit 77; }
W=640 H=480
SCALE=0.01 OFFSET=-100
# the colour: the photo scaled down to 768 x 543 (not a power of two), PNG tiles (lossless)
oiiotool "$photo" --resize 768x543 -o colour.png
"$tiles" colour.png -o colour.vts --codec png --tile-size 128 -q
# the DEM: f32 (nodata -9999) and u16 (nodata 0), nodata and a 1-unit pixel as GDAL tags
"$ref" dem 1001 707 dem_raw.tif dem16_raw.tif $SCALE $OFFSET
gdal_translate -q -a_nodata -9999 -a_ullr 0 707 1001 0 dem_raw.tif dem.tif
gdal_translate -q -a_nodata 0 -a_ullr 0 707 1001 0 dem16_raw.tif dem16.tif
"$tiles" dem.tif -o dem.vts --colour data --tile-size 128 -q
"$tiles" dem16.tif -o dem16.vts --colour data --tile-size 128 --value-scale $SCALE \
  --value-offset $OFFSET -q
vt() { "$view" --headless --sync --size ${W}x$H "$@"; }
# json FILE EXPR: a Python expression over the statistics j, true or the test fails
json() { python3 -c "import json,sys; j=json.load(open(sys.argv[1])); sys.exit(0 if ($2) else 1)" "$1" ||
  fail "$1: not ($2)"; }

case "$case_name" in
terrain_reference)
  CAM="0 520 560 0 60 40 55"
  echo "$CAM" >view.cam
  G=400
  # reference ELEV NODATA SCALE OFFSET EXAG SHIFT OUT [SX SZ X0 Y0 X1 Y1]
  reference() {
    local sx=${8:-1001} sz=${9:-707} win="${10:-0} ${11:-0} ${12:-1001} ${13:-707}"
    "$ref" render "$1" colour.png "$7" $W $H $G "$3" "$4" "$2" $sx $sz "$5" $CAM "$6" $win
  }
  db() { "$check" psnr "$1" "$2" --max 1000 | awk '{print $2}'; }
  for kind in f32 u16; do
    if [ $kind = f32 ]; then store=dem.vts file=dem.tif nd=-9999 s=1 o=0
    else store=dem16.vts file=dem16.tif nd=0 s=$SCALE o=$OFFSET; fi
    vt colour.vts --terrain $store --terrain-grid $G --camera view.cam --frames 12 \
      --screenshot $kind.png --stats $kind.json
    reference $file $nd $s $o 1 0 ref_$kind.png
    reference $file $nd $s $o 0 0 flat_$kind.png
    reference $file $nd $s $o 2 0 x2_$kind.png
    reference $file $nd $s $o 1 6 shift_$kind.png
    good=$(db $kind.png ref_$kind.png)
    flat=$(db $kind.png flat_$kind.png)
    x2=$(db $kind.png x2_$kind.png)
    shift=$(db $kind.png shift_$kind.png)
    echo "$kind: reference $good dB; negative controls: flat $flat dB, x2 $x2 dB, colour shifted $shift dB"
    awk -v g="$good" 'BEGIN { exit !(g >= 35) }' || fail "$kind: $good dB against the reference (want >= 35)"
    # the comparison catches a terrain drawn without its elevation, with twice its heights or
    # with the colour 6 texels off
    for v in "$flat" "$x2" "$shift"; do
      awk -v v="$v" 'BEGIN { exit !(v <= 30) }' || fail "$kind: a negative control scores $v dB (want <= 30)"
    done
    "$check" stat $kind.json fallback_pixels == 0 || fail "$kind: fallback pixels in a converged frame"
  done
  # far away (colour levels 2 and 3 where the view above takes 0 to 3): the level rule matches
  echo "0 1500 1700 0 0 0 40" >far.cam
  vt colour.vts --terrain dem.vts --terrain-grid $G --camera far.cam --frames 12 --screenshot far.png
  CAM="0 1500 1700 0 0 0 40"
  reference dem.tif -9999 1 0 1 0 ref_far.png
  reference dem.tif -9999 1 0 0 0 flat_far.png
  CAM="0 520 560 0 60 40 55"
  good=$(db far.png ref_far.png)
  flat=$(db far.png flat_far.png)
  echo "far view: reference $good dB; flat $flat dB"
  awk -v g="$good" -v f="$flat" 'BEGIN { exit !(g >= 35 && f <= 30) }' ||
    fail "far view: $good dB (want >= 35), flat $flat dB (want <= 30)"
  # both stores georeferenced: the photo placed on x 200..800, y 100..600 of the DEM's CRS (the
  # DEM spans 0..1001 x 0..707, row 0 at y = 707), 600 x 500 units; the grid covers the photo
  # and samples the DEM where the transforms put it (DEM texels x 200..800, rows 107..607)
  gdal_translate -q -a_ullr 200 600 800 100 colour.png colour_geo.tif
  "$tiles" colour_geo.tif -o colour_geo.vts --codec png --tile-size 128 -q
  vt colour_geo.vts --terrain dem.vts --terrain-grid $G --camera view.cam --frames 12 \
    --screenshot geo.png --stats geo.json
  reference dem.tif -9999 1 0 1 0 ref_geo.png 600 500 200 107 800 607
  reference dem.tif -9999 1 0 1 0 ref_geo_whole.png 600 500
  json geo.json "j['terrain']['mapped_by_geo'] and j['terrain']['window'] == [200, 107, 800, 607]"
  json geo.json "abs(j['terrain']['unit_per_texel'] - 600 / 768) < 1e-12"
  json f32.json "not j['terrain']['mapped_by_geo'] and j['terrain']['window'] == [0, 0, 1001, 707]"
  good=$(db geo.png ref_geo.png)
  whole=$(db geo.png ref_geo_whole.png)
  echo "mapped by geo.transform: reference $good dB; the whole DEM under the photo instead $whole dB"
  awk -v g="$good" -v w="$whole" 'BEGIN { exit !(g >= 35 && w <= 30) }' ||
    fail "mapped by geo.transform: $good dB (want >= 35), unmapped $whole dB (want <= 30)"
  ;;
terrain_plain)
  W=320 H=240
  # without --terrain nothing of it runs: no terrain object, no lit variant
  vt colour.vts --frames 2 --stats plain.json
  json plain.json "'terrain' not in j and j['mode'] == '2d' and [v['features'] for v in j['variants']] == [['diffuse_map']]"
  printf 'v -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nvt 0 1\nvt 1 1\nvt 1 0\nvt 0 0\nf 1/1 2/2 3/3 4/4\n' >plane.vt.obj
  vt colour.vts plane.vt.obj --frames 2 --stats scene.json
  json scene.json "'terrain' not in j"
  # a terrain run carries it: the DEM's range (vtv_terrain_ref dem printed it), the level read
  read -r lo hi < <("$ref" dem 1001 707 x.tif y.tif $SCALE $OFFSET)
  vt colour.vts --terrain dem.vts --terrain-grid 400 --frames 1 --stats t.json
  json t.json "j['terrain']['grid'] == 400 and j['terrain']['level'] == 0 and j['terrain']['level_size'] == [1001, 707]"
  json t.json "abs(j['terrain']['min_height'] - $lo) < 1e-3 and abs(j['terrain']['max_height'] - $hi) < 1e-3"
  json t.json "j['terrain']['nodata_texels'] == 40 * 30 and j['terrain']['georeferenced']"
  json t.json "abs(j['terrain']['unit_per_texel'] - 1001 / 768) < 1e-9"
  json t.json "j['mode'] == '3d' and [v['features'] for v in j['variants']] == [['diffuse_map', 'lit']]"
  # the coarsest level with at least G texels across and down: 251 x 177 for G = 128
  vt colour.vts --terrain dem.vts:diffuse --terrain-grid 128 --terrain-exaggeration 2 --frames 1 \
    --stats t128.json
  json t128.json "j['terrain']['level'] == 2 and j['terrain']['level_size'] == [251, 177]"
  json t128.json "j['terrain']['exaggeration'] == 2"
  # u16 through the scale and offset vt-tiles wrote: the same heights to the quantum
  "$view" --version >/dev/null
  vt colour.vts --terrain dem16.vts --terrain-grid 400 --frames 1 --stats t16.json
  json t16.json "j['terrain']['scale'] == $SCALE and j['terrain']['offset'] == $OFFSET"
  json t16.json "abs(j['terrain']['min_height'] - $lo) <= 0.005 + 1e-9 and abs(j['terrain']['max_height'] - $hi) <= 0.005 + 1e-9"
  # GDAL's band scale and offset of a GeoTIFF become layer.0.scale/offset; --value-scale wins
  gdal_translate -q -a_nodata 0 -a_scale $SCALE -a_offset $OFFSET -a_ullr 0 707 1001 0 \
    dem16_raw.tif gscaled.tif
  "$tiles" gscaled.tif -o gscaled.vts --colour data --tile-size 128 -q
  vt colour.vts --terrain gscaled.vts --terrain-grid 400 --frames 1 --stats tg.json
  json tg.json "j['terrain']['scale'] == $SCALE and j['terrain']['offset'] == $OFFSET"
  json tg.json "abs(j['terrain']['min_height'] - $lo) <= 0.005 + 1e-9 and j['terrain']['nodata_texels'] == 1200"
  "$tiles" gscaled.tif -o gscaled2.vts --colour data --tile-size 128 --value-scale 0.02 -q
  vt colour.vts --terrain gscaled2.vts --terrain-grid 64 --frames 1 --stats tg2.json
  json tg2.json "j['terrain']['scale'] == 0.02 and j['terrain']['offset'] == 0"
  # horizontal units: the CRS's (2 units per DEM texel), or the colour store's texels without a
  # geo.transform
  gdal_translate -q -a_nodata -9999 -a_ullr 0 1414 2002 0 dem_raw.tif dem2.tif
  "$tiles" dem2.tif -o dem2.vts --colour data --tile-size 128 -q
  vt colour.vts --terrain dem2.vts --terrain-grid 64 --frames 1 --stats t2.json
  json t2.json "abs(j['terrain']['unit_per_texel'] - 2002 / 768) < 1e-9"
  "$tiles" dem16_raw.tif -o plain16.vts --colour data --tile-size 128 --value-scale $SCALE \
    --value-offset $OFFSET -q
  vt colour.vts --terrain plain16.vts --terrain-grid 64 --frames 1 --stats t3.json
  json t3.json "j['terrain']['unit_per_texel'] == 1 and not j['terrain']['georeferenced'] and j['terrain']['nodata_texels'] == 0"
  # a layer of the same store (:LAYER), an orbit, the plain-texture reference
  vt dem.vts --terrain :0 --terrain-grid 64 --frames 1 --stats same.json
  json same.json "j['terrain']['store'] == 'dem.vts' and j['terrain']['layer'] == 'diffuse'"
  vt colour.vts --terrain dem.vts --terrain-grid 64 --orbit 3 --stats orbit.json
  json orbit.json "len(j['frames']) == 3"
  vt colour.vts --terrain dem.vts --terrain-grid 128 --frames 8 --screenshot vt.png
  vt colour.vts --terrain dem.vts --terrain-grid 128 --frames 1 --reference --screenshot ref.png
  "$check" psnr vt.png ref.png --min 35 || fail "--terrain with --reference"
  # vt-tiles wrote the metadata; refuses a scale of 0
  "$tiles" dem16_raw.tif -o bad.vts --value-scale 0 -q 2>err.txt && fail "--value-scale 0 accepted"
  [ $? -eq 2 ] || true
  grep -q "value-scale" err.txt || fail "--value-scale 0: $(cat err.txt)"
  # errors: one line, exit 1 (bad input) or 2 (usage)
  expect() { # STATUS PATTERN ARGS...
    local want=$1 pat=$2
    shift 2
    set +e
    vt "$@" --frames 1 2>err.txt
    local got=$?
    set -e
    [ $got -eq "$want" ] || fail "$*: exit $got, want $want ($(cat err.txt))"
    grep -q -- "$pat" err.txt || fail "$*: message '$(cat err.txt)' lacks '$pat'"
    [ "$want" -eq 2 ] || [ "$(wc -l <err.txt)" -eq 1 ] || fail "$*: more than one line: $(cat err.txt)"
  }
  expect 1 "missing.vts" colour.vts --terrain missing.vts
  expect 1 "has 3 channels" colour.vts --terrain colour.vts:diffuse
  expect 1 "no one-channel layer" colour.vts --terrain colour.vts
  expect 1 "no layer 'height'" colour.vts --terrain dem.vts:height
  "$tiles" dem16_raw.tif -o noscale.vts --colour data --tile-size 128 -q
  expect 1 "no layer.0.scale" colour.vts --terrain noscale.vts
  expect 2 "no SCENE" colour.vts plane.vt.obj --terrain dem.vts
  expect 2 "--wang" colour.vts --terrain dem.vts --wang colour.vts
  expect 2 "--terrain-grid" colour.vts --terrain dem.vts --terrain-grid 1
  expect 2 "--terrain-grid" colour.vts --terrain dem.vts --terrain-grid 4097
  expect 2 "need --terrain" colour.vts --terrain-grid 64
  expect 2 "--terrain-exaggeration" colour.vts --terrain dem.vts --terrain-exaggeration -1
  # an unreadable tile (four bytes of a level-0 payload overwritten: its CRC fails)
  cp dem.vts corrupt.vts
  size=$(stat -c %s corrupt.vts)
  printf '\377\377\377\377' | dd of=corrupt.vts bs=1 seek=$((size - 100)) conv=notrunc status=none
  expect 1 "checksum" colour.vts --terrain corrupt.vts --terrain-grid 400
  # the elevation store is an input: no output replaces it (STORE:LAYER named too)
  cp dem.vts keep.vts
  expect 1 "is the input" colour.vts --terrain keep.vts:0 --screenshot keep.vts
  cmp keep.vts dem.vts || fail "the elevation store was replaced"
  ;;
terrain_clipmap)
  # The terrain drawn through the clipmap (--clipmap 8: every level's window holds the whole level
  # once loaded), converged (--sync, 3 frames): against the page-table render of the same camera
  # (>= 40 dB) and the CPU reference of the displaced grid (>= 35 dB); negative controls: level 0
  # addressed one texel off (VTV_CLIPMAP_DEBUG_OFFSET=0) against the page table, the colour 6
  # texels off against the clipmap render. The paging centre is the colour texel under the eye.
  G=400
  CAM="0 520 560 0 60 40 55"
  echo "$CAM" >view.cam
  vt colour.vts --terrain dem.vts --terrain-grid $G --camera view.cam --frames 12 --screenshot pt.png
  vt colour.vts --terrain dem.vts --terrain-grid $G --camera view.cam --frames 3 --clipmap 8 \
    --screenshot clip.png --stats clip.json
  "$ref" render dem.tif colour.png ref.png $W $H $G 1 0 -9999 1001 707 1 $CAM 0 0 0 1001 707
  "$ref" render dem.tif colour.png shift.png $W $H $G 1 0 -9999 1001 707 1 $CAM 6 0 0 1001 707
  VTV_CLIPMAP_DEBUG_OFFSET=0 vt colour.vts --terrain dem.vts --terrain-grid $G --camera view.cam \
    --frames 3 --clipmap 8 --screenshot off0.png
  db() { "$check" psnr "$1" "$2" --max 1000 | awk '{print $2}'; }
  pt=$(db clip.png pt.png)
  good=$(db clip.png ref.png)
  off=$(db off0.png pt.png)
  shift=$(db clip.png shift.png)
  echo "clipmap terrain: page table $pt dB, reference $good dB; controls: level 0 off by a texel $off dB, colour shifted $shift dB"
  awk -v v="$pt" 'BEGIN { exit !(v >= 40) }' || fail "$pt dB against the page table (want >= 40)"
  awk -v v="$good" 'BEGIN { exit !(v >= 35) }' || fail "$good dB against the reference (want >= 35)"
  awk -v v="$off" 'BEGIN { exit !(v < 40) }' || fail "level 0 off by a texel: $off dB (want < 40)"
  awk -v v="$shift" 'BEGIN { exit !(v <= 30) }' || fail "colour shifted: $shift dB (want <= 30)"
  "$check" stat clip.json fallback_pixels == 0 || fail "fallback pixels in a converged frame"
  json clip.json "j['renderer'] == 'clipmap' and j['mode'] == '3d' and [v['features'] for v in j['variants']] == [['diffuse_map', 'lit']]"
  # the eye (0, 560) over the DEM's 1001 x 707 units, on the colour's 768 x 543 texels
  json clip.json "all(abs(a - b) < 1e-9 for a, b in zip(j['frames'][0]['centre'], [384, (560 / 707 + 0.5) * 543]))"
  # --clipmap-centre still fixes it
  vt colour.vts --terrain dem.vts --terrain-grid 64 --camera view.cam --frames 1 --clipmap 2 \
    --clipmap-centre 100,50 --stats fixed.json
  json fixed.json "j['frames'][0]['centre'] == [100, 50]"
  ;;
terrain_flyover)
  # A fly-over in clipmap mode: 32 frames flying low (eye at height 150; the DEM's heights are
  # -66..233) across the DEM, looking ahead and down; a colour store of 64 px tiles (14 x 10
  # at level 0), --clipmap 3, a budget of 5 tiles a frame. Per frame the paging centre is the
  # colour texel under the eye (computed here from the path), the uploaded tiles equal exactly
  # clipmap_check.py's model (same tiles, same order) and the bytes stay within the budget; the
  # check fails on a list with one tile dropped or added.
  [ -n "$vt_info" ] || fail "terrain_flyover needs VT_INFO"
  "$tiles" colour.png -o c64.vts --codec png --tile-size 64 -q
  "$vt_info" c64.vts --json >info.json
  C=$("$python" -c 'import json,sys; print(json.load(open(sys.argv[1]))["tile_content_px"])' info.json)
  budget=$((5 * C * C * 4))
  awk 'BEGIN { for (i = 0; i < 32; i++) { x = -420 + i * 26; z = -260 + i * 17;
    printf "%.3f 150 %.3f %.3f 0 %.3f 50\n", x, z, x + 120, z + 80 } }' >fly.cam
  vt c64.vts --terrain dem.vts --terrain-grid 200 --camera fly.cam --frames 32 --clipmap 3 \
    --budget $budget --stats fly.json --screenshot fly.png
  "$python" "$here/clipmap_check.py" strips fly.json info.json || fail "fly-over: uploads"
  for t in drop add; do
    if "$python" "$here/clipmap_check.py" strips fly.json info.json --tamper $t >/dev/null; then
      fail "fly-over: the check passed a list with one tile $t"
    fi
  done
  "$python" - fly.json fly.cam <<'PY' || fail "fly-over: paging centres"
import json, sys
j = json.load(open(sys.argv[1]))
cams = [list(map(float, l.split())) for l in open(sys.argv[2])]
for f, c in zip(j["frames"], cams):
    want = [(c[0] / 1001 + 0.5) * 768, (c[2] / 707 + 0.5) * 543]
    assert all(abs(a - b) < 1e-9 for a, b in zip(f["centre"], want)), (f["centre"], want)
    assert f["bytes_uploaded"] <= j["clipmap"]["budget"], f
moved = sum(1 for f in j["frames"][4:] if f["uploads"])
assert moved >= 8, f"only {moved} frames after the start uploaded tiles"
print(f"fly-over: {len(j['frames'])} frames, {sum(f['uploads'] for f in j['frames'])} tiles uploaded, {moved} frames after the 4th uploaded")
PY
  ;;
*)
  fail "unknown case $case_name"
  ;;
esac
echo "PASS: $case_name"
