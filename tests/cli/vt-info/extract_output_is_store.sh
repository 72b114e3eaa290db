# --extract with -o the store itself (or a link to it) is refused before any work: exit 1, one
# line naming both; the store stays valid and unchanged.
set -euo pipefail
"$VT_SYNTH" s.vts
cp s.vts keep.vts
ln -s s.vts link.png
rc=0; "$VT_INFO" --extract 0 -o link.png s.vts || rc=$?
echo "-o a link to the store: exit $rc"
cmp s.vts keep.vts
rc=0; "$VT_INFO" --extract 0 -o s.vts s.vts || rc=$?
echo "-o the store: exit $rc"
cmp s.vts keep.vts
"$VT_INFO" --verify s.vts
ls -A
exit $rc
