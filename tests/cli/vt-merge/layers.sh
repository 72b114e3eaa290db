# Stores with different layers merge into one store with every layer in argument order: a raw RGBA8
# layer and a png u16 RGB layer named 'detail' give a 2-layer store whose tiles are each input's
# (same payload bytes, same texels); metadata: the first input's plus merge.sources.
set -euo pipefail
"$VT_SYNTH" raw.vts --empty
"$VT_SYNTH" p.vts --codec png --channels 3 --sample u16 --flat --seed 3
"$VT_STORE_CHECK" rename p.vts png.vts 0 detail
"$VT_MERGE" -v raw.vts png.vts -o m.vts
"$VT_STORE_CHECK" same-bytes raw.vts 0 m.vts 0
"$VT_STORE_CHECK" same-bytes png.vts 0 m.vts 1
"$VT_STORE_CHECK" same-tiles raw.vts 0 m.vts 0
"$VT_STORE_CHECK" same-tiles png.vts 0 m.vts 1
"$VT_INFO" --verify m.vts
"$VT_INFO" m.vts | grep -E '^(layers|tiles|metadata):|^layer |^  [a-z][a-z0-9.]*='
"$VT_MERGE" png.vts raw.vts -o m2.vts
"$VT_INFO" m2.vts | grep -E '^layer |^  merge'
