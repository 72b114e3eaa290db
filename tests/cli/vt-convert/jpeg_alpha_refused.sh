# jpeg cannot store an RGBA (or grey+alpha) layer: exit 1 with the codec's reason before any tile is
# written; no output and no temporary file is left.
set -euo pipefail
"$VT_SYNTH" a.vts --codec png --channels 2
rc=0; "$VT_CONVERT" a.vts -o out.vts --codec jpeg || rc=$?
echo "grey+alpha: exit $rc"
"$VT_SYNTH" s.vts --codec png
rc=0; "$VT_CONVERT" s.vts -o out.vts --codec jpeg -j 2 || rc=$?
ls -A
exit $rc
