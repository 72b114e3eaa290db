# u16 layers give 16-bit PNGs (here gray + alpha), raw and PNG-coded.
set -euo pipefail
for codec in raw png; do
  opts="--channels 2 --sample u16 --codec $codec"
  "$VT_SYNTH" $codec.vts $opts
  "$VT_INFO" --extract 0 -o $codec-l0.png $codec.vts
  "$VT_CLI_CHECK" png $codec-l0.png --level 0 --layer 0 $opts
  "$VT_INFO" --extract 1 --tile 2,1 -o $codec-t.png $codec.vts
  "$VT_CLI_CHECK" png $codec-t.png --level 1 --at 2,1 --layer 0 $opts
done
"$VT_SYNTH" gray.vts --channels 1 --sample u16 --empty
"$VT_INFO" --extract 0 -o gray.png gray.vts
"$VT_CLI_CHECK" png gray.png --level 0 --layer 0 --channels 1 --sample u16 --empty
