# Summary of a 300x200 store, 64 px tiles, border 2, RGBA8 raw, with empty tiles: level 0 has
# 5x4 tiles of which 3 are empty ((tx + 2 ty) % 7 == 3), then 3x2, 2x1, 1x1.
set -euo pipefail
"$VT_SYNTH" s.vts --empty
"$VT_INFO" s.vts >out.txt
expect() { grep -qx -- "$1" out.txt || { echo "missing line: '$1'"; exit 3; }; }
expect "size:              300 x 200 texels"
expect "tile:              64 content + 2 x 2 border = 68 payload texels"
expect "levels:            4"
expect "      0       300x200       5x4      17       3       0        314432"
expect "      3         38x25       1x1       1       0       0         18496"
expect "  total                      29      26       3       0        480896"
expect "tiles:             26 stored, 3 empty, 0 shared"
expect "bits per texel:    32.000"
expect "compression ratio: 1.000"
expect "  generator=vt-synth"
cat out.txt
