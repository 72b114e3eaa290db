# Materials with the same texture file in every layer (the same constant where there is none) and
# the same scale share one entry: the first one used names it, the others are its aliases.
#   a (UVs 0..1), b (u 1..2.5, 2 copies alone; the same file as './tex/../tex/s.png') and f (no texcoords) share;
#   the entry's copies cover the union of their UV ranges (origin 0, 3 copies along u);
#   c (u -5..-4) stays apart: with a and b it would need 8 copies instead of 3 + 1;
#   e has s.png and a normal map: apart; k1 and k2 are the same constant and share, k3 is not;
#   --max-repeat 2 keeps b apart (the union would need 3 copies).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/scene.inc"
tex tex/s.png 64x32 1
tex tex/n.png 64x32 2
cat > s.mtl <<'MTL'
newmtl a
map_Kd tex/s.png
newmtl b
Kd 1 0 0
map_Kd ./tex/../tex/s.png
newmtl c
map_Kd tex/s.png
newmtl e
map_Kd tex/s.png
norm tex/n.png
newmtl f
map_Kd tex/s.png
newmtl k1
Kd 0.5 0.5 0.5
newmtl k2
Kd 0.5 0.5 0.5
newmtl k3
Kd 0.5 0.5 0.25
MTL
cat > s.obj <<'OBJ'
mtllib s.mtl
v 0 0 0
v 1 0 0
v 1 1 0
vt 0 0
vt 1 1
vt 0.5 0.5
vt 1 0
vt 2.5 1
vt -5 0
vt -4 1
vt 1.5 0.5
usemtl a
f 1/1 2/2 3/3
usemtl b
f 1/4 2/5 3/8
usemtl c
f 1/6 2/7 3/6
usemtl e
f 1/1 2/2 3/3
usemtl k1
f 1 2 3
usemtl f
f 1 2 3
usemtl k2
f 1 2 3
usemtl k3
f 1 2 3
OBJ
"$VT_ATLAS" s.obj -o atlas.json --wrap replicate --deps atlas.d
"$VT_ATLAS_DUMP" atlas.json
grep -c '"aliases"' atlas.json
cat atlas.d
"$VT_ATLAS" s.obj -o r2.json --wrap replicate --max-repeat 2
"$VT_ATLAS_DUMP" r2.json | grep -A1 -e "^entry 'a'" -e "^entry 'b'"
# --textures: two lines naming one file share; --grid pieces never do.
printf 'tex/s.png\n./tex/s.png\ntex/n.png\n' > list.txt
"$VT_ATLAS" --textures list.txt -o list.json
"$VT_ATLAS_DUMP" list.json | grep -v '^  [a-z]*:'
"$VT_ATLAS" --grid 1x2 tex/s.png ./tex/s.png -o grid.json
"$VT_ATLAS_DUMP" grid.json | grep -v '^  [a-z]*:'
