# float32 holds every half texel between 2^22 and 2^23 texels: a coordinate 0.13 texel away from
# one loses more than 1/8 texel (warning), 0.12 does not.
set -euo pipefail
"$VT_OFFSET_GEN" layout atlas.json 8388608 256 a:0,0,8388608,256
# u = texel / 2^23 for texels 5195304.62 and 5195304.63 (0.12 and 0.13 past 5195304.5)
printf 'v 0 0 0\nvt 0.619328572750091566 0.5\nusemtl a\nf 1/1 1/1 1/1\n' >near.obj
printf 'v 0 0 0\nvt 0.619328573942184435 0.5\nusemtl a\nf 1/1 1/1 1/1\n' >far.obj
"$VT_OFFSET" near.obj atlas.json -o near.out.obj
"$VT_OFFSET" far.obj atlas.json -o far.out.obj
grep ^vt near.out.obj far.out.obj
