# Option conflicts of the selections (--colour index, --filter nearest|mode|min|max), each one
# line and exit 2 with nothing written: an index with an interpolating filter, a selection on
# colour, a selection with --layout, an unknown filter; and the lossy codecs and the float-as-png
# conversion a selection refuses once the input is known.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/../vt-atlas/materials.inc"
materials_scene
"$VT_ATLAS" -q m.obj -o atlas.json
"$VT_SYNTH_IMAGE" c.png --format png --size 96x64 --channels 1
"$VT_SYNTH_IMAGE" e.tif --format tiff --size 96x64 --channels 1 --sample f32
try() { rc=0; "$VT_TILES" "$@" 2>&1 || rc=$?; echo "exit $rc"; }
try c.png -o out.vts --colour index --filter lanczos3
try c.png -o out.vts --filter nearest --colour srgb
try c.png -o out.vts --colour normal --filter max
try --layout atlas.json -o out.vts --filter mode
try c.png -o out.vts --filter median
try c.png -o out.vts --colour index --codec jpeg
try c.png -o out.vts --filter min --codec bc3
try e.tif -o out.vts --filter max --codec png
ls out.vts 2>&1 || true
"$VT_TILES" c.png -o ok.vts --filter max -q
"$VT_INFO" ok.vts | grep -E '^layer 0|filter='
