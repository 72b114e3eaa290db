#!/usr/bin/env bash
# vt-view --terrain (tests/e2e/view/CMakeLists.txt, docs/viewer.md "Terrain"): a generated DEM
# (vtv_terrain_ref dem: 1001 x 707, hills, a sharp ridge, a valley, a plateau, a nodata hole) built
# as f32 and as u16 with --value-scale/--value-offset, draped with a photograph of Debian's
# gnome-backgrounds package, rendered headless and compared with a CPU reference of the displaced
# grid (vtv_terrain_ref render).
# usage: run_terrain_test.sh CASE VT_VIEW VT_TILES VTV_TERRAIN_REF VTV_CHECK WORKDIR
set -euo pipefail
case_name=$1 view=$2 tiles=$3 ref=$4 check=$5 work=$6
rm -rf "$work"
mkdir -p "$work"
cd "$work"
export MESA_SHADER_CACHE_DISABLE=true EGL_LOG_LEVEL=fatal
fail() { echo "FAIL: $*" >&2; exit 1; }
photo=/usr/share/backgrounds/gnome/licorice-l.webp
if [ ! -r "$photo" ]; then
  echo "SKIP: $photo missing (install gnome-backgrounds: scripts/setup)"
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

case "$case_name" in
terrain_reference)
  CAM="0 520 560 0 60 40 55"
  echo "$CAM" >view.cam
  G=400
  # render ELEV NODATA SCALE OFFSET EXAG SHIFT OUT
  reference() {
    "$ref" render "$1" colour.png "$7" $W $H $G "$3" "$4" "$2" 1001 707 "$5" $CAM "$6"
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
  ;;
*)
  fail "unknown case $case_name"
  ;;
esac
echo "PASS: $case_name"
