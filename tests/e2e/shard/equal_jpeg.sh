# A photo-like 3000x1700 PNG (sequential input; not a multiple of the 1008-texel first-pass
# blocks: 3x2 blocks), JPEG tiles: 1, 2, 4 and 16 shards merged equal the single build byte for
# byte, shards built with -j1 and the single build with -j2. With 16 shards (a 4x4 grid of parts
# over 3x2 blocks) ten shards are empty stores, which the merge accepts.
set -euo pipefail
"$VT_SYNTH_IMAGE" in.png --format png --size 3000x1700 --photo
"$VT_TILES" in.png -o single.vts -j2 -q
for n in 1 2 4 16; do
  shards=()
  for i in $(seq 1 $n); do
    "$VT_TILES" in.png -o s$n-$i.vts --shard $i/$n -j1 -q
    shards+=(s$n-$i.vts)
  done
  "$VT_MERGE" "${shards[@]}" -o merged$n.vts -j2
  cmp single.vts merged$n.vts
  echo "ok $n shards merged equal the single build"
done
"$VT_INFO" s16-4.vts | grep -E '^tiles:|^layers:|^  shard(=|.build)'
"$VT_INFO" s16-1.vts | grep -E '^layers:|^layer 1|^  shard(=|.build)'
"$VT_INFO" merged4.vts | grep -E '^layers:|^metadata:'
