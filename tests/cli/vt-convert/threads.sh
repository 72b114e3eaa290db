# The output is byte-identical for every -j: png, jpeg and bc1 (payload 68, a multiple of 4).
set -euo pipefail
"$VT_SYNTH" s.vts --channels 3 --codec png --empty --flat --layers 2
for codec in png jpeg bc1; do
  "$VT_CONVERT" s.vts -o $codec-1.vts --codec $codec -j 1
  "$VT_CONVERT" s.vts -o $codec-2.vts --codec $codec -j 2
  "$VT_CONVERT" s.vts -o $codec-5.vts --codec $codec --threads 5
  cmp $codec-1.vts $codec-2.vts
  cmp $codec-1.vts $codec-5.vts
  "$VT_INFO" --verify $codec-2.vts
  echo "ok $codec: -j 1, 2 and 5 give the same bytes"
done
