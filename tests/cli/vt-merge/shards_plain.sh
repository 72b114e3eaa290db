# Disjoint stores of one layer table without shard metadata merge as shards: every tile equals the
# original's (same bytes, same empty and shared tiles); the metadata is the first input's plus
# merge.sources.
set -euo pipefail
"$VT_SYNTH" build.vts --codec png --layers 2 --empty --flat --channels 3
"$VT_STORE_CHECK" split build.vts a.vts b.vts --no-shard-key
"$VT_MERGE" a.vts b.vts -o m.vts
"$VT_STORE_CHECK" structure build.vts m.vts
"$VT_STORE_CHECK" same-bytes build.vts 0 m.vts 0
"$VT_STORE_CHECK" same-bytes build.vts 1 m.vts 1
"$VT_INFO" --verify m.vts
"$VT_INFO" m.vts | grep -E '^metadata|^  [a-z][a-z0-9.]*='
