#!/bin/bash
# The optional MeshLab stage of samples/Makefile (MESHLAB=1, the %.clean.obj rule of
# scripts/vt.mk running scripts/mesh-clean): OBJ -> PLY -> meshlabserver under xvfb-run -> OBJ
# with the material names restored. Checks that the cleaned scene has every face
# (as triangles) and material, that vt-atlas lays it out exactly as the original scene, and that
# a second make does nothing. Uses the real vt-atlas and vt-offset (TOOLS_DIR) and the stand-in
# store tools of tests/e2e/samples/fake.
# Usage: meshlab.sh WORKDIR SOURCE_DIR GENERATOR MAKE TOOLS_DIR
set -euo pipefail
work=$1
src=$2
gen=$(realpath "$3")
make=$4
tools=$5
rm -rf "$work"
mkdir -p "$work/bin"
ln -s "$tools/vt-atlas" "$tools/vt-offset" "$tools/vt-obj2ply" "$work/bin/"
ln -s "$src/tests/e2e/samples/fake/vt-tiles" "$src/tests/e2e/samples/fake/vt-info" "$work/bin/"
fail() {
    echo "FAIL: $*" >&2
    exit 1
}
m() {
    "$make" --no-print-directory -f "$src/samples/Makefile" VT_BIN="$work/bin" \
        VT_SAMPLE_SCENE="$gen" O="$work/o" SAMPLE_FLAGS="--shrink 4" "$@"
}
m >"$work/plain.log" 2>&1 || { cat "$work/plain.log"; fail "plain build"; }
cp "$work/o/out/scene.atlas.json" "$work/plain.atlas.json"
m MESHLAB=1 >"$work/meshlab.log" 2>&1 || { cat "$work/meshlab.log"; fail "MESHLAB=1 build"; }
clean=$work/o/src/scene.clean.obj
faces=$(grep -c '^f ' "$clean")
quads=$(grep -c '^f [^ ]* [^ ]* [^ ]* [^ ]*$' "$work/o/src/scene.obj")
all=$(grep -c '^f ' "$work/o/src/scene.obj")
echo "cleaned scene: $faces triangles (from $all faces, $quads of them quads)"
[ "$faces" -eq $((all + quads)) ] || fail "expected $((all + quads)) triangles"
[ "$(grep '^usemtl' "$clean" | sort -u | wc -l)" -eq 44 ] || fail "materials lost"
grep -q "^mtllib scene.mtl\$" "$clean" || fail "mtllib not restored"
cmp "$work/o/out/scene.atlas.json" "$work/plain.atlas.json" || fail "the layout changed"
again=$(m MESHLAB=1 2>&1) || fail "make: $again"
[ -z "$again" ] || fail "second MESHLAB=1 make printed: $again"
echo "MeshLab stage ok"
