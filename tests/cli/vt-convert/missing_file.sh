# An input that does not exist or is not a store: exit 1, one line naming the file, nothing written.
set -euo pipefail
echo "not a store" >text.vts
rc=0; "$VT_CONVERT" text.vts -o out.vts --codec png || rc=$?
echo "not a store: exit $rc"
[ ! -e out.vts ] || { echo "out.vts written"; exit 3; }
"$VT_CONVERT" missing.vts -o out.vts --codec png
