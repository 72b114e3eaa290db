# Two materials sharing a vt (duplicated, faces renumbered), CRLF kept, other lines unchanged; the
# MTL names the store. Summary on stderr.
set -euo pipefail
"$VT_OFFSET_GEN" layout atlas.json 1024 1024 brick:0,0,512,512 wood:512,0,256,1024
printf '# scene\r\nmtllib scene.mtl\r\nv 0 0 0\r\nv 1 0 0\r\nv 1 1 0\r\nvn 0 0 1\r\n' >scene.obj
printf 'vt 0 0\r\nvt 1 0\r\nvt 0.5 0.75 0.25\r\nvt 0.125 0.5\r\n' >>scene.obj
printf 'g wall\r\nusemtl brick\r\nf 1/1/1 2/2/1 3/3/1\r\nusemtl wood\r\nf 1/3/1 2/4/1 3/-1/1\r\n' >>scene.obj
printf 'f 1//1 2//1 3//1\r\n' >>scene.obj
"$VT_OFFSET" scene.obj atlas.json -o out.obj
echo "--- out.obj"
cat out.obj
echo "--- out.mtl"
cat out.mtl
echo "--- files"
ls -A
