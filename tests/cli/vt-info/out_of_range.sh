# A level, tile or layer the store does not have is bad usage (exit 2) with the valid range.
set -euo pipefail
"$VT_SYNTH" s.vts --layers 2
for args in "--extract 4" "--extract 1 --tile 3,0" "--extract 1 --tile 0,2" "--extract 0 --layer 2"; do
  rc=0; "$VT_INFO" $args -o out.png s.vts 2>&1 || rc=$?; echo "exit $rc: $args"
done
[ ! -e out.png ] || { echo "out.png written"; exit 3; }
