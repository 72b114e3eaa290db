# --screenshot and --stats cannot both be standard output, and no input can be standard input
# (exit 2); --stats - when standard output is the screenshot is refused before any work (exit 1).
set -euo pipefail
export MESA_SHADER_CACHE_DISABLE=true EGL_LOG_LEVEL=fatal
"$VT_SYNTH_IMAGE" photo.png --format png --size 96x64 --channels 3 --seed 4
"$VT_TILES" -q photo.png -o s.vts --codec png
view() { "$VT_VIEW" --headless --size 64x48 --frames 1 --sync "$@"; }
rc=0; view s.vts --screenshot - --stats - || rc=$?; echo "both on stdout: exit $rc"
rc=0; view - --stats out.json <s.vts || rc=$?; echo "STORE -: exit $rc"
rc=0; view s.vts --camera - --stats out.json || rc=$?; echo "--camera -: exit $rc"
touch shot.png
rc=0; view s.vts --stats - --screenshot shot.png 1<>shot.png || rc=$?
echo "stdout is the screenshot: exit $rc"
ls -A
exit $rc
