# An input cannot be standard input (exit 2); -o - when standard output is an input is refused,
# the input intact (exit 1).
set -euo pipefail
"$VT_SYNTH" build.vts --codec png
"$VT_STORE_CHECK" split build.vts a.vts b.vts
cp a.vts keep.vts
rc=0; "$VT_MERGE" - b.vts -o out.vts <a.vts || rc=$?; echo "an input -: exit $rc"
rc=0; "$VT_MERGE" a.vts b.vts -o - 1<>a.vts || rc=$?; echo "stdout is an input: exit $rc"
cmp a.vts keep.vts
ls -A
exit $rc
