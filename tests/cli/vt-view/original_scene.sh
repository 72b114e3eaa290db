# A scene whose MTL maps textures but no store (the OBJ before vt-offset) is refused with one line
# naming it, exit 1: its UVs do not lie on the atlas. The same faces with an MTL that maps the
# store (as vt-offset writes it), or with no MTL at all, are drawn.
set -euo pipefail
export MESA_SHADER_CACHE_DISABLE=true EGL_LOG_LEVEL=fatal
"$VT_SYNTH_IMAGE" photo.png --format png --size 96x64 --channels 3 --seed 4
"$VT_TILES" -q photo.png -o s.vts --codec png
quad='v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nusemtl m\nf 1/1 2/2 3/3 4/4\n'
printf "mtllib orig.mtl\n$quad" >orig.obj
printf 'newmtl m\nKd 1 1 1\nmap_Kd -clamp on tex/photo.png\n' >orig.mtl
printf "mtllib orig.vt.mtl\n$quad" >orig.vt.obj
printf 'newmtl m\nKd 1 1 1\nmap_Kd s.vts#diffuse\n' >orig.vt.mtl
printf "$quad" >bare.obj
for scene in orig.obj orig.vt.obj bare.obj; do
  rc=0; "$VT_VIEW" s.vts "$scene" --headless --size 32x32 --frames 1 2>&1 || rc=$?
  echo "$scene: exit $rc"
done
