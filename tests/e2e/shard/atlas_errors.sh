# Wrong sets of atlas shards are refused with one line and exit 1, nothing written: a missing
# shard, an image shard among atlas shards, shards of another split, a layout changed since the
# shards read it; the merge reads the layout by the path the shards recorded.
set -euo pipefail
"$VT_SAMPLE_SCENE" --shrink 8 -q scene
"$VT_ATLAS" scene/scene.obj -o atlas.json --tile-size 64 --border 2 -q
"$VT_SYNTH_IMAGE" in.png --format png --size 300x200 --photo
for i in 1 2 3 4; do "$VT_TILES" --layout atlas.json -o s$i.vts --shard $i/4 -q; done
"$VT_TILES" --layout atlas.json -o h1.vts --shard 1/2 -q
"$VT_TILES" in.png -o i2.vts --tile-size 64 --shard 2/4 -q
"$VT_MERGE" s1.vts s2.vts s4.vts -o out.vts || echo "exit $?"
"$VT_MERGE" s1.vts i2.vts s3.vts s4.vts -o out.vts || echo "exit $?"
"$VT_MERGE" h1.vts s2.vts s3.vts s4.vts -o out.vts || echo "exit $?"
mkdir elsewhere
(cd elsewhere && "$VT_MERGE" ../s1.vts ../s2.vts ../s3.vts ../s4.vts -o out.vts) || echo "exit $?"
touch -d '2001-01-01' atlas.json
{ "$VT_MERGE" s1.vts s2.vts s3.vts s4.vts -o out.vts 2>&1 || echo "exit $?"; } | sed -E 's/[0-9]{3,}/N/g'
test ! -e out.vts && test ! -e elsewhere/out.vts && echo "ok nothing written"
"$VT_TILES" --layout atlas.json -o x.vts --shard 1/4 --export-atlas x.png || echo "exit $?"
