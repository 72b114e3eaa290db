# A tile stored by several inputs with the same bytes is allowed (the build and one of its shards;
# three inputs); the shard set is not complete, so the metadata is the first input's plus
# merge.sources.
set -euo pipefail
"$VT_SYNTH" build.vts --empty --flat
"$VT_STORE_CHECK" split build.vts a.vts b.vts
"$VT_MERGE" build.vts b.vts -o m.vts
"$VT_STORE_CHECK" structure build.vts m.vts
"$VT_STORE_CHECK" same-bytes build.vts 0 m.vts 0
"$VT_MERGE" a.vts build.vts b.vts -o m3.vts
"$VT_STORE_CHECK" same-bytes build.vts 0 m3.vts 0
"$VT_INFO" --verify m3.vts
"$VT_INFO" m3.vts | grep -E '^  [a-z][a-z0-9.]*='
