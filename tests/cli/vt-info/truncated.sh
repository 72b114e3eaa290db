# Truncated stores: exit 1 with one line naming the file, at every size tried; the golden stderr
# is the message for the first 1000 bytes.
set -euo pipefail
"$VT_SYNTH" s.vts
size=$(stat -c %s s.vts)
for n in 0 8 63 64 200 700 704 5000 $((size / 2)) $((size - 1)); do
  head -c "$n" s.vts >t.vts
  rc=0; "$VT_INFO" t.vts >out.txt 2>err.txt || rc=$?
  lines=$(wc -l <err.txt)
  grep -q "^vt-info: .*'t.vts'" err.txt || { echo "message does not name the file: $(cat err.txt)"; exit 3; }
  [ ! -s out.txt ] || { echo "stdout not empty at $n bytes"; exit 3; }
  echo "truncated to a prefix: exit $rc, $lines stderr line(s)"
done
head -c 1000 s.vts >t.vts
"$VT_INFO" t.vts
