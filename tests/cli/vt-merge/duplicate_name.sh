# Layer merges need unique layer names: exit 1 naming the name and both files; when the layer
# tables have the same names, the message also says why they are not shards (the first field that
# differs). Nothing written.
set -euo pipefail
"$VT_SYNTH" raw.vts
"$VT_SYNTH" png.vts --codec png
"$VT_SYNTH" u16.vts --sample u16
"$VT_SYNTH" two.vts --layers 2 --channels 3
"$VT_STORE_CHECK" rename two.vts other.vts 0 other
while read -r args; do
  rc=0; "$VT_MERGE" $args -o out.vts 2>&1 || rc=$?
  echo "exit $rc: $args"
done <<'CASES'
raw.vts png.vts
raw.vts u16.vts
raw.vts two.vts
other.vts two.vts
CASES
ls -A
