# The make recipe of docs/sharding.md (tests/e2e/shard/Makefile.shards) with make -j4: 16 shards,
# then the merge, equal to the single build; a second make has nothing to do.
set -euo pipefail
"$VT_SYNTH_IMAGE" in.tif --format tiff --size 2500x1900 --channels 3 --tile 128
"$VT_TILES" in.tif -o single.vts --tile-size 128 -j2 -q
cp "$(dirname "$BASH_SOURCE")/Makefile.shards" Makefile
make -s -j4 IN=in.tif OUT=out.vts N=16 OPTS='--tile-size 128' VT_TILES="$VT_TILES" VT_MERGE="$VT_MERGE"
ls out.vts.shard-* | wc -l
cmp single.vts out.vts && echo "ok make -j4: 16 shards merged equal the single build"
make -j4 IN=in.tif OUT=out.vts N=16 VT_TILES="$VT_TILES" VT_MERGE="$VT_MERGE" | sed 's/^make: //'
