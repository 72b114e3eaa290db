# A missing texture fails with the MTL file:line of its map statement and leaves no output;
# --missing skip warns and falls back to the layer's constant.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/scene.inc"
scene
rm tex/wall_n.png
"$VT_ATLAS" scene.obj -o atlas.json || echo "exit $?"
ls
"$VT_ATLAS" scene.obj -o atlas.json --missing skip
"$VT_ATLAS_DUMP" atlas.json | grep -A1 "'wall'"
