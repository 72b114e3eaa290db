# An input that does not exist or is not a store: exit 1, one line naming the file, nothing written.
set -euo pipefail
"$VT_SYNTH" s.vts
echo "not a store" >text.vts
rc=0; "$VT_MERGE" s.vts text.vts -o out.vts || rc=$?
echo "not a store: exit $rc"
ls -A
"$VT_MERGE" s.vts missing.vts -o out.vts
