# Storage is constant: a 2x2-colour pack of 16 tiles of 256 texels with a 4096-entry hash stands
# for a 1048576 x 1048576 (1M^2) virtual output in less than 2 MB on disk (a photo-like sample,
# jpeg tiles). The summary names the pack and the output's period; a region of the output far
# away is the same texels.
set -euo pipefail
"$VT_SYNTH_IMAGE" sample.png --format png --size 640x480 --channels 3 --photo --seed 5
"$VT_WANG" sample.png -o pack.vts --tile 256 --colours 2x2 --hash 4096 -j 2
size=$(stat -c %s pack.vts)
if [ "$size" -ge 2000000 ]; then echo "pack is $size bytes, not < 2 MB"; exit 1; fi
echo "pack < 2 MB"
# the check can fail: the same pack with raw tiles is larger
"$VT_WANG" sample.png -o raw.vts --tile 256 --colours 2x2 --hash 4096 --codec raw -j 2
if [ "$(stat -c %s raw.vts)" -ge 2000000 ]; then echo "raw pack >= 2 MB"; fi
"$VT_INFO" pack.vts | grep '^wang'
"$VT_INFO" --json pack.vts | grep -A3 '"wang"' | head -4
# the output repeats every 4096 tiles: a region one period away is the same PNG, a region one
# tile away is not
"$VT_INFO" --extract 0 --wang-region 1048676,1048600,300,200 -o far.png pack.vts
"$VT_INFO" --extract 0 --wang-region 100,24,300,200 -o near.png pack.vts
"$VT_INFO" --extract 0 --wang-region 356,24,300,200 -o other.png pack.vts
cmp far.png near.png && echo "one period away: the same texels"
if cmp -s near.png other.png; then echo "a tile away: the same (wrong)"; fi
