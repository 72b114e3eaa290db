# Any geometry mismatch is refused (exit 1) naming the field, both values and both files; nothing
# written.
set -euo pipefail
"$VT_SYNTH" a.vts --tile 248 --border 4 --size 1000x700
while read -r name opts; do
  "$VT_SYNTH" $name $opts
  rc=0; "$VT_MERGE" a.vts $name -o out.vts 2>&1 || rc=$?
  echo "exit $rc: $opts"
done <<'CASES'
b.vts --tile 120 --border 4 --size 1000x700
w.vts --tile 248 --border 4 --size 999x700
h.vts --tile 248 --border 4 --size 1000x701
r.vts --tile 248 --border 3 --size 1000x700
CASES
ls -A
