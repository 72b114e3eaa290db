# IN cannot be standard input (exit 2); -o - when standard output is IN is refused, IN intact
# (exit 1: standard output is written into, not replaced like -o IN); --max-store-size names
# '<stdout>' (exit 1).
set -euo pipefail
"$VT_SYNTH" in.vts
cp in.vts keep.vts
rc=0; "$VT_CONVERT" - -o out.vts --codec png <in.vts || rc=$?; echo "IN -: exit $rc"
rc=0; "$VT_CONVERT" in.vts -o - --codec png 1<>in.vts || rc=$?; echo "stdout is IN: exit $rc"
cmp in.vts keep.vts
rc=0; "$VT_CONVERT" in.vts -o - --codec png --max-store-size 1K >out.vts || rc=$?
echo "--max-store-size 1K: exit $rc"
ls -A
