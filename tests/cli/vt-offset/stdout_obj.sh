# -o - writes the OBJ to standard output, streamed; it needs --mtl, which the mtllib line names as
# given, and the store's default name comes from the MTL's (OUT.mtl -> OUT.vts). The OBJ and MTL
# equal those of -o OUT.obj (into a file and through a pipe); no file named '-' appears and the
# summary stays on stderr.
set -euo pipefail
"$VT_OFFSET_GEN" layout atlas.json 1024 1024 brick:0,0,512,512 wood:512,0,256,1024
printf 'mtllib scene.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 0.5 0.75\n' >scene.obj
printf 'usemtl brick\nf 1/1 2/2 3/3\nusemtl wood\nf 1/3 2/1 3/2\n' >>scene.obj
"$VT_OFFSET" -q scene.obj atlas.json -o out.obj
mkdir dash
(cd dash && "$VT_OFFSET" ../scene.obj ../atlas.json -o - --mtl out.mtl >out.obj)
cmp out.obj dash/out.obj && cmp out.mtl dash/out.mtl && echo "ok -o - equals -o FILE"
"$VT_OFFSET" -q scene.obj atlas.json -o - --mtl dash/piped.mtl --store s.vts | cat >piped.obj
head -n 1 piped.obj
grep '^map_Kd' dash/piped.mtl
ls -A . dash
