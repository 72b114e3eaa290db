# Wrong shard sets are refused with one line and exit 1, and nothing is written: a missing shard,
# a shard of another build (other options; another input file under the same name), a shard given twice, shards of two
# splits, a plain store among shards.
set -euo pipefail
"$VT_SYNTH_IMAGE" in.png --format png --size 1500x1000 --photo
"$VT_SYNTH_IMAGE" other.png --format png --size 1500x1000 --photo --seed 7
"$VT_TILES" in.png -o single.vts --tile-size 128 -q
for i in 1 2 3 4; do
  "$VT_TILES" in.png -o s$i.vts --tile-size 128 --shard $i/4 -q
done
"$VT_TILES" in.png -o q2.vts --tile-size 128 --quality 90 --shard 2/4 -q
cp in.png keep.png
cp other.png in.png
"$VT_TILES" in.png -o o2.vts --tile-size 128 --shard 2/4 -q
"$VT_TILES" keep.png -o a1.vts --tile-size 128 --shard 1/2 -q
"$VT_MERGE" s1.vts s2.vts s4.vts -o out.vts || echo "exit $?"
"$VT_MERGE" s1.vts s2.vts -o out.vts || echo "exit $?"
"$VT_MERGE" s1.vts q2.vts s3.vts s4.vts -o out.vts || echo "exit $?"
# the same command on another input file: told apart by its size and time (digits masked here)
{ "$VT_MERGE" s1.vts o2.vts s3.vts s4.vts -o out.vts 2>&1 || echo "exit $?"; } | sed -E 's/[0-9]{3,}/N/g'

"$VT_MERGE" s1.vts s2.vts s2.vts s4.vts -o out.vts || echo "exit $?"
"$VT_MERGE" s1.vts a1.vts s3.vts s4.vts -o out.vts || echo "exit $?"
"$VT_MERGE" s1.vts s2.vts single.vts s4.vts -o out.vts || echo "exit $?"
"$VT_MERGE" single.vts s2.vts s3.vts s4.vts -o out.vts || echo "exit $?"
test ! -e out.vts && echo "ok nothing written"
"$VT_MERGE" s1.vts s2.vts s3.vts s4.vts -o out.vts
cmp single.vts out.vts && echo "ok the right set still merges"
"$VT_MERGE" s3.vts s2.vts s1.vts -o out2.vts
