# Outputs that are inputs are refused before any work (exit 1, one line naming both), the inputs
# untouched: -o the OBJ (also through a hard link), --restore's -o either input.
set -euo pipefail
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' >s.obj
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' >m.obj
ln s.obj hard.obj
before=$(cksum <s.obj)
rc=0; "$VT_OBJ2PLY" s.obj -o s.obj || rc=$?; echo "-o the input: exit $rc"
rc=0; "$VT_OBJ2PLY" s.obj -o hard.obj || rc=$?; echo "-o a hard link to the input: exit $rc"
rc=0; "$VT_OBJ2PLY" --restore s.obj m.obj -o m.obj || rc=$?; echo "--restore -o MESHLAB.obj: exit $rc"
rc=0; "$VT_OBJ2PLY" --restore s.obj m.obj -o s.obj || rc=$?; echo "--restore -o IN.obj: exit $rc"
[ "$(cksum <s.obj)" = "$before" ] && echo "ok input untouched"
ls -A
