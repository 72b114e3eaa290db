# Missing, conflicting or malformed options: exit 2 with one specific reason each, nothing written.
set -euo pipefail
"$VT_SYNTH" s.vts
while read -r args; do
  rc=0; "$VT_CONVERT" $args 2>&1 || rc=$?; echo "exit $rc: $args"
done <<'CASES'
s.vts --codec png
-o out.vts --codec png
s.vts -o out.vts
s.vts -o out.vts --codec webp
s.vts -o out.vts --codec
s.vts -o out.vts --codec png --quality 90
s.vts -o out.vts --codec raw --subsampling 444
s.vts -o out.vts --codec jpeg --quality 0
s.vts -o out.vts --codec jpeg --quality 101
s.vts -o out.vts --codec jpeg --subsampling 422
s.vts -o out.vts --codec jpeg --mode best
s.vts -o out.vts --codec png --mode slow
s.vts -o out.vts --codec png --layer x
s.vts -o out.vts --codec png --layer 1
s.vts -o out.vts --codec png -j 0
s.vts -o out.vts --codec png -j 257
s.vts -o out.vts --codec png --qual 90
s.vts -o out.vts --codec png --help=1
s.vts t.vts -o out.vts --codec png
CASES
[ ! -e out.vts ] || { echo "out.vts written"; exit 3; }
