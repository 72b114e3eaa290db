# UVs outside [0,1] are an error by default, naming the material and its range; no output left.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/scene.inc"
GROUND_VT="8 8" scene
trap 'ls' EXIT
"$VT_ATLAS" scene.obj -o atlas.json --deps atlas.d
