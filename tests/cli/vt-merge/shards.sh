# Two shards of one build (tiles with tx < tiles_x / 2 of each level in a.vts, the others in
# b.vts; metadata shard=1/2 and shard=2/2, the rest as the build's) merge into the single build
# byte for byte, in either order; empty tiles (--empty) and shared payloads (--flat) included.
set -euo pipefail
"$VT_SYNTH" build.vts --codec png --layers 2 --empty --flat
"$VT_STORE_CHECK" split build.vts a.vts b.vts
"$VT_INFO" a.vts | grep -E '^tiles:|^  shard'
"$VT_INFO" b.vts | grep -E '^tiles:|^  shard'
"$VT_MERGE" a.vts b.vts -o ab.vts
cmp build.vts ab.vts
"$VT_MERGE" b.vts a.vts -o ba.vts
cmp build.vts ba.vts
"$VT_INFO" --verify ab.vts
echo "ok merged shards equal the single build byte for byte"
"$VT_SYNTH" raw.vts --channels 3 --sample u16 --size 1000x700 --tile 120 --border 4
"$VT_STORE_CHECK" split raw.vts a.vts b.vts
"$VT_MERGE" -v b.vts a.vts -o m.vts
cmp raw.vts m.vts
echo "ok raw u16 shards equal the single build byte for byte"
