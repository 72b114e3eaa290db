# f16 and f32 layers convert to raw only: png, jpeg and bc refuse them with the codec's reason
# (exit 1, nothing written).
set -euo pipefail
"$VT_SYNTH" f.vts --sample f32 --channels 3
"$VT_SYNTH" h.vts --sample f16 --channels 4
for codec in png jpeg bc3; do
  rc=0; "$VT_CONVERT" h.vts -o out.vts --codec $codec 2>&1 || rc=$?
  echo "f16 to $codec: exit $rc"
done
ls -A
"$VT_CONVERT" f.vts -o out.vts --codec png
