# Only the layers the scene uses (diffuse, normal); all layers of a material share its rectangle;
# a material without a normal map gets (0.5,0.5,1,1), one without any texture a 4x4 cell filled
# from Kd; the unused material is left out; paths are relative to the atlas's directory.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/scene.inc"
scene
mkdir out
"$VT_ATLAS" scene.obj -o out/atlas.json
"$VT_ATLAS_DUMP" out/atlas.json
