#!/usr/bin/env bash
# vt-view --terrain (tests/e2e/view/CMakeLists.txt, docs/viewer.md "Terrain"): a generated DEM
# (vtv_terrain_ref dem: 1001 x 707, hills, a sharp ridge, a valley, a plateau, a nodata hole) built
# as f32 and as u16 with --value-scale/--value-offset, draped with a photograph (autumn leaves) from
# Debian's plasma-workspace-wallpapers, rendered headless and compared with a CPU reference of the displaced
# grid (vtv_terrain_ref render).
# usage: run_terrain_test.sh CASE VT_VIEW VT_TILES VTV_TERRAIN_REF VTV_CHECK WORKDIR
set -euo pipefail
case_name=$1 view=$2 tiles=$3 ref=$4 check=$5 work=$6
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
*)
  fail "unknown case $case_name"
  ;;
esac
echo "PASS: $case_name"
