# A screenshot of a frame that still shows fallback texels (tiles not loaded yet: the first
# frame, without --sync) is written, with one warning saying so; a --sync run with frames enough
# to load every tile writes it without the warning.
set -euo pipefail
export MESA_SHADER_CACHE_DISABLE=true EGL_LOG_LEVEL=fatal
"$VT_SYNTH_IMAGE" photo.png --format png --size 300x200 --channels 3 --seed 4
"$VT_TILES" -q photo.png -o s.vts --codec png --tile-size 64
"$VT_VIEW" s.vts --headless --size 64x48 --frames 1 --screenshot a.png 2>&1 |
  sed -E 's/shows [0-9]+ fallback/shows N fallback/'
[ -s a.png ] && echo "a.png written"
"$VT_VIEW" s.vts --headless --size 64x48 --frames 8 --sync --screenshot b.png 2>&1
[ -s b.png ] && echo "b.png written"
