# A payload its codec cannot decode (correct CRC): exit 1 naming the store, layer, level and tile
# and the decoder's reason; nothing written, for any -j. Copied layers are not decoded, but their
# CRC is checked.
set -euo pipefail
"$VT_SYNTH" good.vts --codec png --layers 2 --channels 3
"$VT_CLI_CHECK" junk-tile good.vts bad.vts 1 1 2 1
for j in 1 2; do
  rc=0; "$VT_CONVERT" bad.vts -o out.vts --codec raw -j $j 2>&1 || rc=$?
  echo "-j $j: exit $rc"
done
"$VT_CONVERT" bad.vts -o l0.vts --codec raw --layer 0
"$VT_STORE_CHECK" same-bytes bad.vts 1 l0.vts 1
read -r off len < <("$VT_CLI_CHECK" tile-offset good.vts 0 1 1 1)
cp good.vts crc.vts
printf '\x55' | dd of=crc.vts bs=1 seek=$((off + len / 2)) conv=notrunc status=none
rc=0; "$VT_CONVERT" crc.vts -o out.vts --codec raw --layer 1 2>&1 || rc=$?
echo "bad CRC in a copied layer: exit $rc"
ls -A
"$VT_CONVERT" bad.vts -o out.vts --codec jpeg --layer 1
