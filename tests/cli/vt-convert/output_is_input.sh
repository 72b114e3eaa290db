# -o the input store (by name or a hard link) is refused before any work: exit 1, one line naming
# both, the input unchanged.
set -euo pipefail
"$VT_SYNTH" in.vts
cp in.vts keep.vts
ln in.vts hard.vts
rc=0; "$VT_CONVERT" in.vts -o hard.vts --codec png || rc=$?
echo "-o a hard link to the input: exit $rc"
cmp in.vts keep.vts
rc=0; "$VT_CONVERT" in.vts -o in.vts --codec png || rc=$?
echo "-o the input: exit $rc"
cmp in.vts keep.vts
ls -A
exit $rc
