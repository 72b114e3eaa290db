# A payload with a correct CRC that its codec cannot decode: --verify and --extract exit 1 naming
# the tile and the decoder's reason (raw: wrong size; png: not a PNG).
set -euo pipefail
for codec in raw png; do
  "$VT_SYNTH" good-$codec.vts --codec $codec
  "$VT_CLI_CHECK" junk-tile good-$codec.vts $codec.vts 0 1 2 1
  rc=0; "$VT_INFO" --verify $codec.vts || rc=$?
  echo "verify $codec: exit $rc"
done
"$VT_INFO" --extract 1 --tile 1,1 -o ok.png png.vts
echo "extract another tile: exit 0"
"$VT_INFO" --extract 1 -o bad.png png.vts
