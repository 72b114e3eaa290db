# Outputs that are inputs are refused before any work (exit 1, one line naming both), the inputs
# untouched: --screenshot the store (also through a link), --stats the store, --screenshot the
# camera file, and the screenshot as the stats file.
set -euo pipefail
export MESA_SHADER_CACHE_DISABLE=true EGL_LOG_LEVEL=fatal
"$VT_SYNTH_IMAGE" photo.png --format png --size 96x64 --channels 3 --seed 4
"$VT_TILES" -q photo.png -o s.vts --codec png
echo "0 0 2 0 0 0 60" >view.cam
ln -s s.vts link.vts
before=$(cksum <s.vts)
view() { "$VT_VIEW" --headless --size 64x48 --frames 1 --sync "$@"; }
rc=0; view s.vts --screenshot s.vts || rc=$?; echo "screenshot = store: exit $rc"
rc=0; view s.vts --screenshot link.vts || rc=$?; echo "screenshot = link to the store: exit $rc"
rc=0; view s.vts --stats s.vts || rc=$?; echo "stats = store: exit $rc"
rc=0; view s.vts --camera view.cam --screenshot view.cam || rc=$?; echo "screenshot = camera: exit $rc"
rc=0; view s.vts --screenshot same.out --stats same.out || rc=$?; echo "screenshot = stats: exit $rc"
[ "$(cksum <s.vts)" = "$before" ] && echo "ok store untouched"
[ "$(cat view.cam)" = "0 0 2 0 0 0 60" ] && echo "ok camera untouched"
ls -A
