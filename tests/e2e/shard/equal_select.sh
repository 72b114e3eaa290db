# Selections (docs/filters.md, "Selections"): a categorical map (--colour index: mode) and float
# elevation min/max pyramids, odd sizes, small tiles: shards merged (the merge resumes with the
# selection named in the "filter" metadata) equal the single build byte for byte, with the seams
# path (no wrap) and the carried level (--wrap); -j1 equals -j2.
set -euo pipefail
"$VT_SYNTH_IMAGE" c.png --format png --size 1001x777 --channels 1
"$VT_SYNTH_IMAGE" e.tif --format tiff --size 901x613 --channels 1 --sample f32
"$VT_TILES" c.png -o c.vts --tile-size 32 --colour index -j2 -q
"$VT_TILES" c.png -o c1j.vts --tile-size 32 --colour index -j1 -q
cmp c.vts c1j.vts
"$VT_TILES" e.tif -o lo.vts --tile-size 32 --filter min -j2 -q
"$VT_TILES" e.tif -o hi.vts --tile-size 32 --filter max --wrap -j1 -q
for i in 1 2 3 4; do
  "$VT_TILES" c.png -o c$i.vts --tile-size 32 --colour index --shard $i/4 -q
  "$VT_TILES" e.tif -o lo$i.vts --tile-size 32 --filter min --shard $i/4 -j2 -q
  "$VT_TILES" e.tif -o hi$i.vts --tile-size 32 --filter max --wrap --shard $i/4 -q
done
"$VT_MERGE" c4.vts c3.vts c2.vts c1.vts -o cm.vts
cmp c.vts cm.vts
echo "ok index (mode) shards merged equal the single build"
"$VT_MERGE" lo{1..4}.vts -o lom.vts -j2
cmp lo.vts lom.vts
"$VT_MERGE" hi{1..4}.vts -o him.vts
cmp hi.vts him.vts
echo "ok min and max (wrap) shards merged equal the single build"
"$VT_INFO" cm.vts | grep -E '^layer 0|filter|colour'
"$VT_INFO" lom.vts | grep -E '^layer 0|filter'
