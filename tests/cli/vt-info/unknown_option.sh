# Unknown options, and abbreviations of known ones (no GNU prefix matching): exit 2, the reason
# and a pointer to --help on stderr.
set -euo pipefail
"$VT_SYNTH" s.vts
for args in "-x s.vts" "--js s.vts" "--ext 0 -o x.png s.vts" "--ver s.vts" "-qz s.vts"; do
  rc=0; "$VT_INFO" $args 2>&1 || rc=$?; echo "exit $rc: $args"
done
"$VT_INFO" --bogus s.vts
