# --stats - and --screenshot - write to standard output (headless, --sync): the statistics equal
# those of --stats FILE but for the timings, the screenshot the PNG of --screenshot FILE (into a
# file and through a pipe); no file named '-' appears and nothing else is on stdout.
set -euo pipefail
export MESA_SHADER_CACHE_DISABLE=true EGL_LOG_LEVEL=fatal
"$VT_SYNTH_IMAGE" photo.png --format png --size 300x200 --channels 3 --seed 4
"$VT_TILES" -q photo.png -o s.vts --codec png --tile-size 64
view() { "$VT_VIEW" s.vts --headless --size 64x48 --frames 3 --sync "$@"; }
view --stats stats.json --screenshot shot.png
view --stats - >dash.json
grep -v timing_ms stats.json >a.txt
grep -v timing_ms dash.json >b.txt
cmp a.txt b.txt && echo "ok --stats - equals --stats FILE (timings aside)"
head -n 2 dash.json
view --screenshot - >dash.png
cmp shot.png dash.png && echo "ok --screenshot - equals --screenshot FILE"
view --screenshot - --stats piped.json | cat >piped.png
cmp shot.png piped.png && echo "ok --screenshot - through a pipe"
ls -A
