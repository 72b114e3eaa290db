# The MTL keeps every material the faces use (sorted by name), with the constants and alpha mode
# atlas.json records for it and one map per layer it has, naming STORE#layer; the OBJ's usemtl
# lines are copied unchanged. A material the layout lacks (faces without texcoords) gets grey.
# The scene: ../vt-atlas/materials.inc (fence map_d, cut-out tree, smooth mask, forced team-colour
# mask and its alias team2, glass d 0.5, shiny Ks/Ns/Ke/map_Ks, Tr, stray texel, missing map).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/../vt-atlas/materials.inc"
materials_scene
"$VT_ATLAS" m.obj -o atlas.json -q 2>/dev/null
{ cat m.obj; printf 'usemtl extra\nf 1 2 3\n'; } > m2.obj
"$VT_OFFSET" m2.obj atlas.json -o m.vt.obj -q --store scene.vts
diff <(grep usemtl m2.obj) <(grep usemtl m.vt.obj) && echo "ok usemtl lines kept"
cat m.vt.mtl
