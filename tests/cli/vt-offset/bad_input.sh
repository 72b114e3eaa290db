# Bad input or output: one line naming file:line, exit 1, no output and no temporary file left.
set -euo pipefail
"$VT_OFFSET_GEN" layout atlas.json 1024 1024 a:0,0,512,512
printf '{"format": "vtpipe-atlas", "version": 1' >broken.json
printf 'v 0 0 0\nvt 0 0\nusemtl a\nf 1/1 1/1 1/1\n' >ok.obj
printf 'v 0 0 0\nvt 0 0\nusemtl a\nf 1/1 1/2 1/1\n' >range.obj
printf 'v 0 0 0\nvt 0.5 nan\nusemtl a\nf 1/1 1/1 1/1\n' >nan.obj
printf 'v 0 0 0\nvt 0 0\nusemtl b\nf 1/1 1/1 1/1\n' >material.obj
printf 'v 0 0 0\nvt 0 0.5\nvt 0 1.25\nusemtl a\nf 1/1 1/1 1/2\n' >outside.obj # one chart across v = 1
printf 'v 0 0 0\nvt 0 0\nf 1/1 1/1 1/1\n' >nomaterial.obj
while read -r args; do
  rc=0; "$VT_OFFSET" $args -o out.obj 2>&1 || rc=$?; echo "exit $rc: $args"
done <<'CASES'
missing.obj atlas.json
ok.obj missing.json
ok.obj broken.json
range.obj atlas.json
nan.obj atlas.json
material.obj atlas.json
outside.obj atlas.json
nomaterial.obj atlas.json
CASES
# outputs that cannot be created: exit 1, the other output not left either
rc=0; "$VT_OFFSET" ok.obj atlas.json -o nodir/out.obj 2>&1 || rc=$?; echo "exit $rc: -o nodir/out.obj"
rc=0; "$VT_OFFSET" ok.obj atlas.json -o out.obj --mtl nodir/out.mtl 2>&1 || rc=$?
echo "exit $rc: -o out.obj --mtl nodir/out.mtl"
ls -A
