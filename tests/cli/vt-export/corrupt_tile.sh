# A payload that does not decode, or whose CRC does not match: exit 1 naming the store, layer,
# level and tile; no output folder and no staging folder left behind, for any -j.
set -euo pipefail
"$VT_SYNTH" good.vts --codec png --layers 2 --channels 3
"$VT_CLI_CHECK" junk-tile good.vts bad.vts 1 1 2 1
for j in 1 2; do
  rc=0; "$VT_EXPORT" bad.vts -o out --layer 1 -j $j 2>&1 || rc=$?
  echo "-j $j: exit $rc"
done
read -r off len < <("$VT_CLI_CHECK" tile-offset good.vts 0 1 1 1)
cp good.vts crc.vts
printf '\x55' | dd of=crc.vts bs=1 seek=$((off + len / 2)) conv=notrunc status=none
rc=0; "$VT_EXPORT" crc.vts -o out 2>&1 || rc=$?
echo "bad CRC: exit $rc"
ls -A
"$VT_EXPORT" bad.vts -o out --layer 0 && ls out
