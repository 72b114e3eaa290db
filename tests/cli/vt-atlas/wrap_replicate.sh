# --wrap replicate: copies for the UV range (u -1..2.5 -> origin -1, 4 copies; v 0..8 -> 8);
# a tolerance of 1e-6 around [0,1] is not a wrap; --max-repeat limits the copies.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/scene.inc"
GROUND_VT="2.5 8" scene
sed -i 's/^vt 0 0$/vt -1 -0.0000005/' scene.obj
"$VT_ATLAS" scene.obj -o atlas.json --wrap replicate
"$VT_ATLAS_DUMP" atlas.json | grep -A2 "'ground'"
"$VT_ATLAS" scene.obj -o atlas2.json --wrap replicate --max-repeat 4 || echo "exit $?"
ls
