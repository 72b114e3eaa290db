# --store, --mtl and --precision; an OBJ without mtllib gets one first; -q prints nothing.
set -euo pipefail
"$VT_OFFSET_GEN" layout atlas.json 3000 3000 a:7,11,1000,1000
printf 'v 0 0 0\nvt 0.3 0.7\nusemtl a\nf 1/1 1/1 1/1\n' >scene.obj
"$VT_OFFSET" scene.obj atlas.json -o scene.vt.obj --store city.vts --mtl atlas.mtl --precision 4
cat scene.vt.obj
grep map_Kd atlas.mtl
"$VT_OFFSET" -q scene.obj atlas.json -o default.obj
cat default.obj
grep map_Kd default.mtl
# the default store of NAME.vt.obj is NAME.vts, the one scripts/vt.mk builds next to it
"$VT_OFFSET" -q scene.obj atlas.json -o city.vt.obj
grep map_Kd city.vt.mtl
