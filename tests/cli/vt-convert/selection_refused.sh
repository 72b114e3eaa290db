# A store built with a selection (vt-tiles --colour index: filter=mode, exact values; RGB classes,
# which bc1 could otherwise store) converts to lossless codecs only: jpeg and bc1 refuse it
# (exit 1, nothing written); raw keeps every texel.
set -euo pipefail
"$VT_SYNTH" s.vts --channels 3 --size 300x200
"$VT_INFO" --extract 0 -o in.png s.vts
"$VT_TILES" in.png -o idx.vts --colour index --tile-size 64 -q
for codec in jpeg bc1; do
  rc=0; "$VT_CONVERT" idx.vts -o out.vts --codec $codec 2>&1 || rc=$?
  echo "index to $codec: exit $rc"
done
ls -A
"$VT_CONVERT" idx.vts -o raw.vts --codec raw
"$VT_INFO" raw.vts | grep -E '^layer 0|filter='
for l in 0 1 2; do
  "$VT_INFO" --extract $l -o a$l.png idx.vts
  "$VT_INFO" --extract $l -o b$l.png raw.vts
  cmp a$l.png b$l.png
done
echo "raw conversion: levels 0-2 identical"
