# -o - writes the merged store to standard output (spooled in $TMPDIR, then copied): the same
# bytes as -o FILE, for shards and for layers, into a file or a pipe; the shards of
# `vt-tiles --shard` (their coarse levels built with pass images in $TMPDIR) give the single
# build; no file named '-' appears, no spool is left and nothing else is on stdout.
set -euo pipefail
mkdir tmp
export TMPDIR=$PWD/tmp
"$VT_SYNTH" build.vts --codec png --layers 2 --empty --flat
"$VT_STORE_CHECK" split build.vts a.vts b.vts
"$VT_MERGE" a.vts b.vts -o - >dash.vts
cmp build.vts dash.vts && echo "ok shards through -o - equal the single build"
"$VT_SYNTH" one.vts --codec png
"$VT_STORE_CHECK" rename one.vts other.vts 0 other
"$VT_MERGE" one.vts other.vts -o layers.vts
"$VT_MERGE" -v one.vts other.vts --output - | cat >piped.vts
cmp layers.vts piped.vts && echo "ok layers through a pipe equal -o FILE"
"$VT_STORE_CHECK" smooth-png photo.png 700 500
"$VT_TILES" photo.png -o single.vts --tile-size 64 --codec png
"$VT_TILES" photo.png -o s1.vts --tile-size 64 --codec png --shard 1/2
"$VT_TILES" photo.png -o s2.vts --tile-size 64 --codec png --shard 2/2
"$VT_MERGE" s2.vts s1.vts -o - >merged.vts
cmp single.vts merged.vts && echo "ok vt-tiles --shard through -o - equals the single build"
ls -A . tmp
