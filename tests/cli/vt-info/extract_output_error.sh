# An output that cannot be written: exit 1 naming it; nothing is left behind.
set -euo pipefail
"$VT_SYNTH" s.vts
"$VT_INFO" -v --extract 0 -o out.png s.vts
[ -s out.png ]
"$VT_INFO" --extract 0 -o no-such-dir/out.png s.vts
