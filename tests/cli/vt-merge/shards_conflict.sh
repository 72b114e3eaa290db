# A tile stored by two inputs with different bytes: exit 1 naming the tile and both files; nothing
# written.
set -euo pipefail
"$VT_SYNTH" one.vts --seed 1
"$VT_SYNTH" two.vts --seed 2
"$VT_STORE_CHECK" split two.vts a.vts b.vts
rc=0; "$VT_MERGE" a.vts one.vts -o out.vts || rc=$?
ls -A
exit $rc
