# A missing texture fails with --missing fail, naming the MTL file:line of its map statement, and leaves no output;
# by default it is a warning and the layer falls back to the constant.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/scene.inc"
scene
rm tex/wall_n.png
"$VT_ATLAS" scene.obj -o atlas.json --missing fail || echo "exit $?"
ls
"$VT_ATLAS" scene.obj -o atlas.json # the default: a warning and the constant
"$VT_ATLAS_DUMP" atlas.json | grep -A1 "'wall'"
