# --density with shared textures: materials with the same texture share an entry only when they
# get the same scale. a1 (a.png on 1 unit^2) is 16x denser than a2 and a3 (a.png on 16 unit^2)
# and b (b.png 128^2 on 1 unit^2): the target is 16384, a1 gets scale 1/4, a2 and a3 scale 1 and
# share one entry; a1 keeps its own.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/scene.inc"
tex a.png 512x512 1
tex b.png 128x128 2
printf 'newmtl a1\nmap_Kd a.png\nnewmtl a2\nmap_Kd a.png\nnewmtl a3\nmap_Kd a.png\n' > d.mtl
printf 'newmtl b\nmap_Kd b.png\n' >> d.mtl
printf 'mtllib d.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 4 0 0\nv 4 4 0\nv 0 4 0\n' > d.obj
printf 'vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n' >> d.obj
printf 'usemtl a1\nf 1/1 2/2 3/3 4/4\nusemtl a2\nf 1/1 5/2 6/3 7/4\n' >> d.obj
printf 'usemtl b\nf 1/1 2/2 3/3 4/4\nusemtl a3\nf 1/1 5/2 6/3 7/4\n' >> d.obj
"$VT_ATLAS" d.obj -o d.json --density
"$VT_ATLAS_DUMP" d.json | grep -v '^  [a-z]*:'
# without --density all three a materials share
"$VT_ATLAS" d.obj -o n.json
"$VT_ATLAS_DUMP" n.json | grep -v '^  [a-z]*:'
