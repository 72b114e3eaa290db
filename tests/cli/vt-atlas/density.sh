# --density: two quads of one world unit^2, textures 512^2 and 128^2 (densities 262144 and
# 16384): the target is the lower median (16384) so 'a' gets scale 1/4; --max-scale 2 limits it.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/scene.inc"
tex a.png 512x512 1
tex b.png 128x128 2
printf 'newmtl a\nmap_Kd a.png\nnewmtl b\nmap_Kd b.png\n' > d.mtl
printf 'mtllib d.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n' > d.obj
printf 'usemtl a\nf 1/1 2/2 3/3 4/4\nusemtl b\nf 1/1 2/2 3/3 4/4\n' >> d.obj
"$VT_ATLAS" d.obj -o n.json
"$VT_ATLAS_DUMP" n.json | grep entry
"$VT_ATLAS" -v d.obj -o d.json --density
"$VT_ATLAS_DUMP" d.json | grep entry
"$VT_ATLAS" d.obj -o e.json --density --max-scale 2
"$VT_ATLAS_DUMP" e.json | grep entry
