# The summary: entries, layers, atlas size in tiles, tiles used/empty and fill ratio; --tile-size
# and --border are stored in the layout.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/scene.inc"
scene
"$VT_ATLAS" scene.obj -o a.json --tile-size 128 --border 2
"$VT_ATLAS_DUMP" a.json | head -1
