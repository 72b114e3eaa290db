# --deps writes one make rule: the atlas, then every OBJ, MTL and texture read (spaces escaped).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/scene.inc"
scene
"$VT_ATLAS" -q scene.obj -o atlas.json --deps atlas.d
cat atlas.d
