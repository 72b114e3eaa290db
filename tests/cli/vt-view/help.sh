# -h and --help print the same help on stdout and exit 0; -j is --threads, as in the other tools
# (a bad value is refused under either name).
set -euo pipefail
"$VT_VIEW" -h >short.txt
cmp short.txt - < <("$VT_VIEW" --help)
"$VT_VIEW" --help
for a in "-j 0" "--threads 65"; do
  rc=0; "$VT_VIEW" $a s.vts 2>&1 || rc=$?; echo "exit $rc: $a"
done
# --range and --ramp: malformed values are usage errors (exit 2)
for a in "--range 1" "--range 2:1" "--range 0:inf" "--range a:b" "--ramp rainbow"; do
  rc=0; "$VT_VIEW" $a s.vts 2>&1 || rc=$?; echo "exit $rc: $a"
done
