# --stats: per layer, level and channel min/max/mean/stddev of the texels. Level 0 of a PNG store
# equals numpy's figures for the source image (population stddev, as gdalinfo); the same check
# against another image fails. A float store with empty tiles (zeros, counted), --json, --layer,
# and a layer the store does not have (exit 2).
set -euo pipefail
py=/usr/bin/python3
"$VT_SYNTH_IMAGE" a.png --format png --size 300x200 --channels 3 --seed 4
"$VT_SYNTH_IMAGE" b.png --format png --size 300x200 --channels 3 --seed 5
"$VT_TILES" -q a.png -o a.vts --codec png --tile-size 64
"$VT_INFO" --stats a.vts | tee stats.txt | head -4
numpy_stats() {
  "$py" -c "
import sys; from PIL import Image; import numpy as np
a = np.asarray(Image.open(sys.argv[1])).astype(np.float64)
for c in range(a.shape[2]):
    print('  channel %d: min %.9g max %.9g mean %.6f stddev %.6f'
          % (c, a[..., c].min(), a[..., c].max(), a[..., c].mean(), a[..., c].std()))" "$1"
}
sed -n 2,4p stats.txt >ours.txt
numpy_stats a.png >ref.txt
cmp ours.txt ref.txt && echo "level 0 = numpy's statistics of a.png"
numpy_stats b.png >wrong.txt
if cmp -s ours.txt wrong.txt; then echo "FAIL: the comparison cannot tell b.png"; exit 1; fi
echo "and differs from b.png's"
"$VT_SYNTH" f.vts --size 200x130 --tile 64 --border 2 --channels 1 --sample f32 --empty --seed 3
"$VT_INFO" --stats --json f.vts
"$VT_INFO" --stats --layer 0 f.vts | head -2
rc=0; "$VT_INFO" --stats --layer 3 f.vts 2>&1 || rc=$?; echo "exit $rc"
rc=0; "$VT_INFO" --stats --verify f.vts 2>&1 || rc=$?; echo "exit $rc"
