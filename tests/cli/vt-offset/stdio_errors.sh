# -o - without --mtl (the MTL's name derives from OUT's) and --mtl - (the mtllib line names it)
# are usage errors (exit 2, nothing written); -o - when standard output is the scene, or is the
# MTL to write, is refused before any work (exit 1), the scene intact.
set -euo pipefail
"$VT_OFFSET_GEN" layout atlas.json 1024 1024 brick:0,0,512,512
printf 'mtllib scene.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nusemtl brick\nf 1/1 2/2 3/3\n' >scene.obj
cp scene.obj keep.obj
rc=0; "$VT_OFFSET" scene.obj atlas.json -o - || rc=$?; echo "-o - without --mtl: exit $rc"
rc=0; "$VT_OFFSET" scene.obj atlas.json -o out.obj --mtl - || rc=$?; echo "--mtl -: exit $rc"
rc=0; "$VT_OFFSET" scene.obj atlas.json -o - --mtl out.mtl 1<>scene.obj || rc=$?
echo "stdout is the scene: exit $rc"
cmp scene.obj keep.obj
touch out.mtl
rc=0; "$VT_OFFSET" scene.obj atlas.json -o - --mtl out.mtl 1<>out.mtl || rc=$?
echo "stdout is the MTL: exit $rc"
ls -A
exit $rc
