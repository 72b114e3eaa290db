# UVs outside [0,1] are an error with --wrap report, naming the material, its range as written and its charts moved; no output left.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/scene.inc"
GROUND_VT="8 8" scene
trap 'ls' EXIT
"$VT_ATLAS" scene.obj -o atlas.json --deps atlas.d --wrap report
