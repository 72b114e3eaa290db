# An OBJ or MTL output that is an input is refused before any work (exit 1, one line naming both,
# every input untouched): -o the scene (its default MTL would be the scene's MTL too), --mtl the
# scene's MTL (named by its mtllib line), --mtl the layout, -o a hard link to the scene, --mtl a
# symbolic link to the OBJ output.
set -euo pipefail
"$VT_OFFSET_GEN" layout atlas.json 1024 1024 brick:0,0,512,512
printf 'mtllib scene.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nusemtl brick\nf 1/1 2/2 3/3\n' >scene.obj
printf 'newmtl brick\nmap_Kd brick.png\n' >scene.mtl
cp scene.obj keep.obj
cp scene.mtl keep.mtl
cp atlas.json keep.json
ln scene.obj hard.obj
ln -s out.obj out-link.mtl
for args in "-o out.obj --mtl scene.mtl" "-o out.obj --mtl atlas.json" "-o hard.obj" \
            "-o out.obj --mtl out-link.mtl"; do
  rc=0; "$VT_OFFSET" scene.obj atlas.json $args || rc=$?
  echo "vt-offset scene.obj atlas.json $args: exit $rc"
  cmp scene.obj keep.obj && cmp scene.mtl keep.mtl && cmp atlas.json keep.json
done
ls -A
"$VT_OFFSET" scene.obj atlas.json -o scene.obj
