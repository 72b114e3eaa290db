# Bad input (vertex index out of range, NaN texcoord, missing MTL, truncated texture, missing
# OBJ): each fails with file:line, exit 1, and leaves no output.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/scene.inc"
scene
cp scene.obj ok.obj
printf 'f 1/1 2/2 9/3\n' >> scene.obj
"$VT_ATLAS" scene.obj -o a.json || echo "exit $?"
cp ok.obj nan.obj
printf 'vt nan 0\n' >> nan.obj
"$VT_ATLAS" nan.obj -o a.json || echo "exit $?"
sed 's/scene.mtl/nothere.mtl/' ok.obj > nomtl.obj
"$VT_ATLAS" nomtl.obj -o a.json || echo "exit $?"
head -c 20 tex/wall_n.png > tex/wall.png
"$VT_ATLAS" ok.obj -o a.json || echo "exit $?"
"$VT_ATLAS" missing.obj -o a.json || echo "exit $?"
ls
