# --extract LEVEL stitches the tile contents of a level (no borders) into one PNG: every texel is
# compared with the generator. 300x200, 64 px tiles, border 2: levels 300x200 .. 38x25.
set -euo pipefail
opts="--size 300x200 --tile 64 --border 2"
"$VT_SYNTH" s.vts $opts
for level in 0 1 2 3; do
  "$VT_INFO" --extract "$level" -o "l$level.png" s.vts
  "$VT_CLI_CHECK" png "l$level.png" --level "$level" --layer 0 $opts
done
# a PNG-coded store, an odd size and tile size (partial tiles on both edges), RGB
opts="--size 257x131 --tile 32 --border 3 --channels 3 --codec png --seed 7"
"$VT_SYNTH" p.vts $opts
"$VT_INFO" --extract 0 -o p0.png p.vts
"$VT_CLI_CHECK" png p0.png --level 0 --layer 0 $opts
"$VT_INFO" --extract 1 --output p1.png p.vts
"$VT_CLI_CHECK" png p1.png --level 1 --layer 0 $opts
