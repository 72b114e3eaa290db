# png -> jpeg -> png keeps the geometry and the index structure (which tiles are empty, which share
# a payload: --flat makes the left quarter of every level one colour), keeps the metadata and adds
# convert.1 and convert.2; the layer table follows the codec (jpeg quality in codec_param); the
# last png holds exactly the jpeg's texels; every output passes vt-info --verify.
set -euo pipefail
opts="--codec png --channels 3 --empty --flat --size 300x200 --tile 60 --border 2"
"$VT_SYNTH" s.vts $opts
"$VT_CONVERT" s.vts -o j.vts --codec jpeg --quality 90
"$VT_STORE_CHECK" structure s.vts j.vts
"$VT_CONVERT" j.vts -o p.vts --codec png --mode best
"$VT_STORE_CHECK" structure s.vts p.vts
"$VT_STORE_CHECK" same-tiles j.vts 0 p.vts 0
"$VT_INFO" --verify j.vts
"$VT_INFO" --verify p.vts
"$VT_INFO" --json j.vts >j.json
"$VT_CLI_CHECK" json j.json layers.0.codec='"jpeg"' layers.0.codec_param=90 layers.0.sample='"u8"' \
  totals.stored=26 totals.empty=3 totals.shared=3 level_count=4
for f in s j p; do
  echo "== $f.vts"
  "$VT_INFO" $f.vts | grep -E '^(size|tile|levels|layers|flags|tiles|metadata):|^layer |^  [a-z][a-z0-9.]*='
done
