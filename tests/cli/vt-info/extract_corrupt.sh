# --extract of a level with a corrupt tile: exit 1 naming the tile, no PNG under the name.
set -euo pipefail
"$VT_SYNTH" s.vts --codec png
read -r offset length < <("$VT_CLI_CHECK" tile-offset s.vts 0 1 1 0)
printf 'XXXX' | dd of=s.vts bs=1 seek=$((offset + 20)) conv=notrunc status=none
"$VT_INFO" --extract 1 --tile 0,0 -o ok.png s.vts
echo "other tile: exit 0"
rc=0; "$VT_INFO" --extract 1 -o bad.png s.vts || rc=$?
echo "level: exit $rc"
[ ! -e bad.png ] || { echo "bad.png written"; exit 3; }
ls -A | grep -v '^s.vts$' | grep -v '^ok.png$' && { echo "left-over files"; exit 3; }
echo "no left-over files"
