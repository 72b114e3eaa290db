# Conflicting or incomplete options and malformed numbers: exit 2 with one specific reason each.
set -euo pipefail
"$VT_SYNTH" s.vts
while read -r args; do
  rc=0; "$VT_INFO" $args 2>&1 || rc=$?; echo "exit $rc: $args"
done <<'CASES'
--tile 0,0 s.vts
--layer 0 s.vts
-o out.png s.vts
--extract 0 s.vts
--json --verify s.vts
--json=1 s.vts
--json --extract 0 -o out.png s.vts
--extract abc -o out.png s.vts
--extract -1 -o out.png s.vts
--extract 99999999999 -o out.png s.vts
--extract 0 --tile 1 -o out.png s.vts
--extract 0 --tile 1,x -o out.png s.vts
--extract 0 --layer 1.5 -o out.png s.vts
--extract 0 -o out.jpg s.vts
--extract 0 -o dir/OUT.EXR s.vts
s.vts other.vts
CASES
for f in out.png out.jpg; do [ ! -e "$f" ] || { echo "$f written"; exit 3; }; done
