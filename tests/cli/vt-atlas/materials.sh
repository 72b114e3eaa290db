# Every used material is recorded with its constants, the layers it has a map in and its alpha
# mode (materials.inc lists the rule each one shows); materials sharing an entry (team, team2)
# keep their own constants and modes. -v names the reason for each mode.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/materials.inc"
materials_scene
"$VT_ATLAS" m.obj -o atlas.json -v 2>&1 | grep -E "alpha|gone" || true
"$VT_ATLAS_DUMP" atlas.json | grep -A1 "^material"
