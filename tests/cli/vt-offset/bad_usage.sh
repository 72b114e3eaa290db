# Missing or malformed arguments: exit 2 with one specific reason each, nothing written.
set -euo pipefail
"$VT_OFFSET_GEN" layout atlas.json 1024 1024 a:0,0,512,512
printf 'v 0 0 0\nvt 0 0\nusemtl a\nf 1/1 1/1 1/1\n' >s.obj
while read -r args; do
  rc=0; "$VT_OFFSET" $args 2>&1 || rc=$?; echo "exit $rc: $args"
done <<'CASES'
s.obj atlas.json
s.obj -o out.obj
-o out.obj
s.obj atlas.json extra.json -o out.obj
s.obj atlas.json -o out.obj --precision 0
s.obj atlas.json -o out.obj --precision 18
s.obj atlas.json -o out.obj --precision x
s.obj atlas.json -o out.obj --mtl out.obj
s.obj atlas.json -o out.obj --unknown
s.obj atlas.json -o
CASES
ls -A
