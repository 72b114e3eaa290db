# Float input (32-bit float TIFF, linear, raw F32 tiles) and a 16-bit normal map (PNG codec,
# renormalised), odd sizes, small tiles: 4 shards merged in reverse order equal the single build.
# Then images of one and two levels.
set -euo pipefail
"$VT_SYNTH_IMAGE" f.tif --format tiff --size 1001x777 --channels 3 --sample f32
"$VT_SYNTH_IMAGE" n.png --format png --size 1300x515 --channels 3 --sample u16
"$VT_TILES" f.tif -o f.vts --tile-size 32 -j2 -q
"$VT_TILES" n.png -o n.vts --tile-size 40 --colour normal --filter kaiser -j2 -q
for i in 1 2 3 4; do
  "$VT_TILES" f.tif -o f$i.vts --tile-size 32 --shard $i/4 -j2 -q
  "$VT_TILES" n.png -o n$i.vts --tile-size 40 --colour normal --filter kaiser --shard $i/4 -q
done
"$VT_MERGE" f4.vts f3.vts f2.vts f1.vts -o fm.vts
cmp f.vts fm.vts
echo "ok float shards merged equal the single build"
"$VT_MERGE" n4.vts n3.vts n2.vts n1.vts -o nm.vts
cmp n.vts nm.vts
echo "ok normal-map shards merged equal the single build"
"$VT_INFO" f.vts | grep -E '^layer 0'
"$VT_INFO" n.vts | grep -E '^layer 0'
# images of one and two levels: no second pass, the shards carry nothing and the merge only joins
"$VT_SYNTH_IMAGE" small.png --format png --size 300x200
"$VT_SYNTH_IMAGE" one.png --format png --size 100x60
"$VT_TILES" small.png -o small.vts -q
"$VT_TILES" one.png -o one.vts -q
for i in 1 2 3 4; do "$VT_TILES" small.png -o small$i.vts --shard $i/4 -q; done
"$VT_TILES" one.png -o one1.vts --shard 1/2 -q
"$VT_TILES" one.png -o one2.vts --shard 2/2 -q
"$VT_MERGE" small{1..4}.vts -o small-m.vts
cmp small.vts small-m.vts
"$VT_MERGE" one2.vts one1.vts -o one-m.vts
cmp one.vts one-m.vts
echo "ok shards of images without a second pass merged equal the single build"
