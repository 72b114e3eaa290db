# -o one of the inputs (the last one, or a symbolic link to the first) is refused before any
# work: exit 1, one line naming both; every input unchanged.
set -euo pipefail
"$VT_SYNTH" one.vts --seed 1
"$VT_STORE_CHECK" split one.vts a.vts b.vts
cp a.vts keep_a.vts
cp b.vts keep_b.vts
ln -s a.vts link.vts
rc=0; "$VT_MERGE" a.vts b.vts -o link.vts || rc=$?
echo "-o a link to the first input: exit $rc"
rc=0; "$VT_MERGE" a.vts b.vts -o b.vts || rc=$?
echo "-o the last input: exit $rc"
cmp a.vts keep_a.vts
cmp b.vts keep_b.vts
ls -A
exit $rc
