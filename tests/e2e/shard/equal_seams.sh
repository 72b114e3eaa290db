# Without --wrap the shards build the levels above their first pass but along the seams between
# parts, and carry only the texels the merge needs there (docs/sharding.md, "Seams"): RGBA with
# transparent areas (premultiplied filtering, empty tiles), an odd size, Lanczos-3 and a 3-texel
# border (wide filter windows across the seams), 2, 8 and 64 shards (grids 2x1, 4x2, 8x8, most of
# the 64 parts smaller than a tile of level 3), merged equal the single build byte for byte.
set -euo pipefail
"$VT_SYNTH_IMAGE" in.tif --format tiff --size 2901x1333 --channels 4 --tile 128
opts=(--tile-size 64 --keep payload --border 3 --filter lanczos3 --codec png)
"$VT_TILES" in.tif -o single.vts "${opts[@]}" -j2 -q
for n in 2 8 64; do
  for i in $(seq 1 $n); do
    "$VT_TILES" in.tif -o s$n-$i.vts "${opts[@]}" --shard $i/$n -j1 -q
  done
  "$VT_MERGE" $(seq -f "s$n-%g.vts" 1 $n) -o merged$n.vts -j2
  cmp single.vts merged$n.vts
  echo "ok $n shards merged equal the single build"
done
"$VT_INFO" s8-3.vts | grep -E '^layers:|^  shard(=|.build)'
# --verify reads every tile of a shard: its image layer decoded, its carried texels checksummed
"$VT_INFO" --verify -v s8-3.vts 2>&1
