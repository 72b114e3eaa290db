# An option without its argument: exit 2 naming the option (long and short forms).
set -euo pipefail
"$VT_SYNTH" s.vts
rc=0; "$VT_INFO" s.vts --extract 0 -o 2>&1 || rc=$?; echo "exit $rc"
"$VT_INFO" s.vts --extract
