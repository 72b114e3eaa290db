# Missing or malformed options: exit 2 with one specific reason each, nothing written.
set -euo pipefail
"$VT_SYNTH" s.vts
while read -r args; do
  rc=0; "$VT_MERGE" $args 2>&1 || rc=$?; echo "exit $rc: $args"
done <<'CASES'
-o out.vts
s.vts s.vts
s.vts -o
s.vts -o out.vts --layer 1
s.vts -o out.vts --out m.vts
s.vts -o out.vts -j 0
CASES
[ ! -e out.vts ] || { echo "out.vts written"; exit 3; }
