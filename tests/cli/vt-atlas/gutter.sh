# --gutter: a sub-tile texture's cell starts one gutter before it (cell_x/cell_y in atlas.json,
# written only then) and the texture stays at a multiple of the gutter; large textures keep
# whole tiles without gutter; --gutter 0 gives the power-of-two cells of old (no cell_x);
# a gutter that is not a power of two, or not below the tile size, is a usage error.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/scene.inc"
scene
"$VT_ATLAS" scene.obj -o g8.json --gutter 8 -q
"$VT_ATLAS_DUMP" g8.json
grep -c '"cell_x"' g8.json
"$VT_ATLAS" scene.obj -o g0.json --gutter 0 -q
"$VT_ATLAS_DUMP" g0.json
grep -c '"cell_x"' g0.json || true
"$VT_ATLAS" scene.obj -o bad.json --gutter 3 || echo "exit $?"
"$VT_ATLAS" scene.obj -o bad.json --gutter 256 || echo "exit $?"
"$VT_ATLAS" scene.obj -o bad.json --gutter 16 --tile-size 16 || echo "exit $?"
