# A material naming a Wang pack ("vt_wang PACK [scale S]", docs/wang.md) through vt-atlas and
# vt-offset: atlas.json records it in "wang_materials" (pack relative to atlas.json, scale, its
# constants; Kd 1 when not given) with no entry (its map_Kd and norm are dropped: its UVs address
# the pack's output); vt-offset copies its faces' vt as written (repeats 0..6, a 3-number vt, no
# cuts on integer lines) and writes the statement with the pack relative to the .vt.mtl. vt 1 is
# shared with the atlas material's face: that face gets a copy of its own (the atlas coordinate).
set -euo pipefail
mkdir -p tex packs out
"$VT_SYNTH_IMAGE" tex/wall.png --format png --size 32x32 --channels 3 --seed 1
: > packs/grass.vts # vt-atlas and vt-offset do not open the pack
cat > scene.mtl <<'MTL'
newmtl grass
map_Kd tex/wall.png
norm tex/wall.png
vt_wang packs/grass.vts scale 4
Ks 0.25 0.25 0.25

newmtl wall
map_Kd tex/wall.png
MTL
cat > scene.obj <<'OBJ'
mtllib scene.mtl
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
vt 0.25 0.5
vt 6 0
vt 6.5 6.25 0
vt -0.5 6
vt 1 1
usemtl grass
f 1/1 2/2 3/3 4/4
usemtl wall
f 1/1 2/5 3/5
OBJ
"$VT_ATLAS" scene.obj -o out/atlas.json --tile-size 64 --border 2 -v 2>&1 | grep -E "grass|wrote"
# the entries' and materials' names (wall only), then the pack materials, spaces removed
json=$(tr -d ' \n' < out/atlas.json)
echo "${json#*\"entries\":}" | grep -o '"name":"[a-z]*","x"'
echo "${json#*\"materials\":}" | grep -o '"name":"[a-z]*","entry"'
echo "${json#*\"wang_materials\":}"
"$VT_OFFSET" scene.obj out/atlas.json -o out/scene.vt.obj 2>offset.txt
head -1 offset.txt
grep -E '^(vt|f|usemtl)' out/scene.vt.obj
sed -n '/newmtl grass/,/^$/p' out/scene.vt.mtl
# the vt each corner of the pack face names, input against output, byte for byte (the atlas
# copy of the shared vt in its place fails this diff)
corners() { # OBJ: the vt lines the first face after "usemtl grass" names
  awk '/^vt/ { vt[++n] = $0 } /^usemtl/ { g = ($2 == "grass") }
       g && /^f/ { for (i = 2; i <= NF; i++) { split($i, c, "/"); print vt[c[2]] }; exit }' "$1"
}
diff <(corners scene.obj) <(corners out/scene.vt.obj) && echo "ok vt of the pack face kept"
# a scene whose every material names a pack has nothing to place: one line, exit 1
printf 'mtllib scene.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nvt 0 0\nusemtl grass\nf 1/1 2/1 3/1\n' > only.obj
rc=0
"$VT_ATLAS" only.obj -o out/only.json 2>&1 || rc=$?
echo "exit $rc"
