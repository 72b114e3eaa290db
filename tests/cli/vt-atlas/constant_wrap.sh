# A material without textures (a constant Kd cell) whose UVs leave [0,1] is neither an error
# under the default --wrap report nor replicated under --wrap replicate: vt-offset maps all its
# UVs to the cell centre, so they do not matter.
set -euo pipefail
printf 'newmtl k\nKd 1 0 0\n' > c.mtl
printf 'mtllib c.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt -3 0\nvt 5 0\nvt 0 7\nusemtl k\nf 1/1 2/2 3/3\n' > c.obj
"$VT_ATLAS" c.obj -o a.json
"$VT_ATLAS_DUMP" a.json
"$VT_ATLAS" c.obj -o r.json --wrap replicate -q
"$VT_ATLAS_DUMP" r.json
