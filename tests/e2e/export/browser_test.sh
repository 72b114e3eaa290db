#!/usr/bin/env bash
# vt-export --html opened in headless Chromium: the screenshot of the page's home view equals
# vt-info --extract of the level it shows, within a PSNR; a deliberately wrong export (two tiles
# of that level swapped) fails the same comparison.
#
#   browser_test.sh BIN_DIR TESTS_BIN_DIR PYTHON CHROMIUM WORK_DIR
#
# The view: a 1024x768 image in a 512x384 page. OpenSeadragon's home view fits the whole image,
# so it shows it at scale 1/2, what the store's level 1 holds (OpenSeadragon 6.1 draws Deep Zoom
# level 10, the full image, at half size, and IIIF scale factor 2 at 1:1). The screenshot is compared with the extract of level 1 by PSNR over
# every pixel: Deep Zoom >= 40 dB (measured 50.2 dB on 2026-12-02, not bit-exact: the canvas
# smooths tiles drawn at sub-pixel positions); IIIF >= 30 dB (measured 33.5 dB: without tile
# overlap, OpenSeadragon's canvas drawer stretches every tile by one pixel to hide seams, 256 ->
# 257, which blurs). Two tiles swapped measure far below (printed). XYZ puts the image in a square world (padded tiles), so
# its home view is at scale 384/1024: compared with the extract of level 0 resized the same way
# (PIL, Lanczos) and placed as OpenSeadragon places it: >= 25 dB.
# Exit 77 (skipped, with the reason) when Chromium or OpenSeadragon is missing or cannot start.
set -euo pipefail
bin=$1 tbin=$2 py=$3 chromium=$4 work=$5
here=$(cd "$(dirname "$0")" && pwd)
osd=${VT_OPENSEADRAGON:-$HOME/.cache/vtpipe/npm/node_modules/openseadragon/build/openseadragon/openseadragon.min.js}
[ -n "$py" ] || { echo "skip: no Python 3 with numpy and PIL (scripts/setup)"; exit 77; }
[ -x "$chromium" ] || { echo "skip: no Chromium ('$chromium'; scripts/setup installs it)"; exit 77; }
[ -r "$osd" ] || { echo "skip: no openseadragon.min.js ('$osd'; scripts/setup installs it)"; exit 77; }
rm -rf "$work" && mkdir -p "$work" && cd "$work"

"$tbin/vt-synth-image" img.png --format png --size 1024x768 --photo
"$bin/vt-tiles" -q img.png -o s.vts --codec png --tile-size 256 --keep content
"$bin/vt-info" --extract 0 -o e0.png s.vts
"$bin/vt-info" --extract 1 -o e1.png s.vts

# compare SHOT REF MIN_DB [xyz]: PSNR of the screenshot against the reference view.
compare() {
  "$py" - "$@" <<'PY'
import math, sys
import numpy as np
from PIL import Image
shot, ref, min_db = sys.argv[1], sys.argv[2], float(sys.argv[3])
a = np.asarray(Image.open(shot).convert("RGB")).astype(np.float64)
if len(sys.argv) > 4:  # xyz: the 1024x1024 world fitted into 512x384 at 0.375, centred
    img = Image.open(ref).convert("RGB")
    s = 384 / 1024
    view = Image.new("RGB", (512, 384))
    view.paste(img.resize((round(1024 * s), round(768 * s)), Image.LANCZOS), (64, 0))
    b = np.asarray(view).astype(np.float64)
else:
    b = np.asarray(Image.open(ref).convert("RGB")).astype(np.float64)
if a.shape != b.shape:
    print(f"screenshot {a.shape[1]}x{a.shape[0]}, view {b.shape[1]}x{b.shape[0]}")
    sys.exit(1)
mse = np.mean((a - b) ** 2)
db = 99.0 if mse == 0 else 10 * math.log10(255 ** 2 / mse)
print(f"PSNR {db:.1f} dB (threshold {min_db} dB)")
sys.exit(0 if db >= min_db else 1)
PY
}

shot() {
  local rc=0
  "$py" "$here/browser_shot.py" "$chromium" "$1/index.html" 512x384 "$2" || rc=$?
  [ "$rc" = 77 ] && exit 77
  return "$rc"
}

for spec in dzi:40 iiif:30; do
  layout=${spec%:*}
  "$bin/vt-export" -q s.vts -o $layout --layout $layout --format png --html --openseadragon "$osd"
  shot $layout $layout.png
  echo -n "$layout home view: "
  compare $layout.png e1.png ${spec#*:}
done
"$bin/vt-export" -q s.vts -o xyz --layout xyz --format png --html --openseadragon "$osd"
shot xyz xyz.png
echo -n "xyz home view: "
compare xyz.png e0.png 25 xyz

# The wrong export: two tiles swapped in each level the view may draw (OpenSeadragon 6.1 draws
# level 10, the full image, at half size here: measured by swapping level 10's tiles alone).
cp -r dzi wrong
for level in 9 10; do
  mv wrong/s_files/$level/0_0.png t.png
  mv wrong/s_files/$level/1_1.png wrong/s_files/$level/0_0.png
  mv t.png wrong/s_files/$level/1_1.png
done
shot wrong wrong.png
echo -n "dzi with two tiles swapped: "
if compare wrong.png e1.png 40; then
  echo "FAIL: the swapped tiles were not seen"
  exit 1
fi
echo "ok: the comparison fails on the wrong export"
