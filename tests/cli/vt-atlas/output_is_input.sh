# atlas.json or the --deps file that is an input is refused before anything is written (exit 1,
# one line naming both, every input untouched): -o the scene (before any work), --deps the scene's
# MTL or -o one of its textures (known once the scene is scanned), --deps atlas.json itself.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/scene.inc"
scene
mkdir keep
cp -r scene.obj scene.mtl tex keep/
for args in "-o atlas.json --deps scene.mtl" "-o tex/wall.png" "-o atlas.json --deps atlas.json"; do
  rc=0; "$VT_ATLAS" -q scene.obj $args || rc=$?
  echo "vt-atlas scene.obj $args: exit $rc"
  diff -r keep/tex tex && cmp keep/scene.obj scene.obj && cmp keep/scene.mtl scene.mtl
done
ls -A
"$VT_ATLAS" -q scene.obj -o scene.obj
