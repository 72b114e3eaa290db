# Missing, conflicting or malformed options: exit 2 with one specific reason each, nothing written.
set -euo pipefail
"$VT_SYNTH" s.vts
"$VT_SYNTH" u16.vts --sample u16 --codec png
while read -r args; do
  rc=0; "$VT_EXPORT" $args 2>&1 || rc=$?; echo "exit $rc: $args"
done <<'CASES'
s.vts
-o out
s.vts -o out --layout tms
s.vts -o out --format webp
s.vts -o out --format png --quality 90
s.vts -o out --quality 90
u16.vts -o out --quality 90
s.vts -o out --format jpeg --quality 0
s.vts -o out --tile-size 0
s.vts -o out --tile-size 4097
s.vts -o out --overlap 257
s.vts -o out --layout iiif --overlap 1
s.vts -o out --layout xyz --name x
s.vts -o out --iiif-id http://x/
s.vts -o out --name a/b
s.vts -o out --openseadragon osd.js
s.vts -o out --layer 7
s.vts -o out --layer normal
s.vts -o out --tile-size 8 --overlap 9
s.vts -o out -j 0
s.vts -o out --tile 8
s.vts t.vts -o out
CASES
[ ! -e out ] || { echo "out written"; exit 3; }
ls
