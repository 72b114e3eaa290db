# An RGBA tiled TIFF (random-access input, alpha kept: PNG tiles), 3000x1700, with 64-texel tiles
# (7 levels: the merge runs two passes after the shards' one), the Lanczos-3 filter and --wrap:
# 4 and 16 shards merged equal the single build; shards -j2, single build -j1.
set -euo pipefail
"$VT_SYNTH_IMAGE" in.tif --format tiff --size 3000x1700 --channels 4 --tile 256
opts=(--tile-size 64 --filter lanczos3 --wrap)
"$VT_TILES" in.tif -o single.vts "${opts[@]}" -j1 -q
for n in 4 16; do
  for i in $(seq 1 $n); do
    "$VT_TILES" in.tif -o s$n-$i.vts "${opts[@]}" --shard $i/$n -j2 -q
  done
  "$VT_MERGE" $(seq -f "s$n-%g.vts" 1 $n) -o merged$n.vts -j1
  cmp single.vts merged$n.vts
  echo "ok $n shards merged equal the single build"
done
"$VT_INFO" single.vts | grep -E '^layer 0|^levels:'
