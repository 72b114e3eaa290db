# The GNU parallel recipe of docs/sharding.md: 4 shards, two at a time, then the merge.
set -euo pipefail
export HOME=$PWD # parallel keeps state in ~/.parallel
"$VT_SYNTH_IMAGE" in.png --format png --size 2000x1500 --photo
"$VT_TILES" in.png -o single.vts -j2 -q
parallel --will-cite --halt now,fail=1 -j2 "$VT_TILES" in.png -o shard-{}.vts --shard {}/4 -j1 -q ::: 1 2 3 4
"$VT_MERGE" shard-{1..4}.vts -o out.vts
cmp single.vts out.vts && echo "ok parallel -j2: 4 shards merged equal the single build"
