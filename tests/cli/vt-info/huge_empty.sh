# A 100000 x 70000 store whose tiles are all empty: the summary has no rates (n/a, null), and
# --extract refuses a level above 2^32 texels (bad usage) naming the finest level that fits.
set -euo pipefail
"$VT_CLI_CHECK" empty-store e.vts 100000 70000 1024 4
"$VT_INFO" e.vts
"$VT_INFO" --json e.vts >e.json
"$VT_CLI_CHECK" json e.json totals.stored=0 totals.bits_per_texel=null totals.compression_ratio=null
"$VT_INFO" --verify e.vts
"$VT_INFO" --extract 0 --tile 97,68 -o t.png e.vts
echo "empty tile: exit 0"
"$VT_INFO" --extract 0 -o l.png e.vts
