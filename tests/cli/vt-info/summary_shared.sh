# Shared payloads: with --flat the left quarter of each level is one colour, so the 4 level-0
# tiles of column 0 hold the same bytes (3 shared), in both layers (4 more shared in layer 1).
set -euo pipefail
"$VT_SYNTH" s.vts --flat --layers 2 --channels 2 --sample u16
"$VT_INFO" s.vts >out.txt
expect() { grep -qx -- "$1" out.txt || { echo "missing line: '$1'"; exit 3; }; }
expect "layer 0 'diffuse': raw, 2 channels, u16, srgb, flags none"
expect "layer 1 'layer1': raw, 2 channels, u16, srgb, flags none"
expect "      0       300x200       5x4      20       0       3        314432"
expect "      0       300x200       5x4      20       0       4        295936"
expect "tiles:             58 stored, 0 empty, 7 shared"
cat out.txt
