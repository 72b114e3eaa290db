#!/usr/bin/env bash
# Test of scripts/mesh-clean (tests/e2e/meshlab/CMakeLists.txt).
#   run.sh absent  ROOT BINDIR SCENE_EXE WORKDIR: without meshlabserver the input is copied.
#   run.sh meshlab ROOT BINDIR SCENE_EXE WORKDIR: cleaning and simplifying with meshlabserver;
#                  exits 77 (skipped) when meshlabserver or xvfb-run is not installed.
set -euo pipefail
mode=$1 root=$2 bin=$3 scene=$4 work=$5
rm -rf "$work"
mkdir -p "$work/out"
"$scene" gen "$work/in"
export VT_BIN=$bin
fail() { echo "FAIL: $*" >&2; exit 1; }

if [[ $mode == absent ]]; then
  MESHLABSERVER=no-such-meshlabserver "$root/scripts/mesh-clean" "$work/in/scene.obj" \
    "$work/in/scene.clean.obj" 2>"$work/err" || fail "exit status $?"
  cat "$work/err" >&2
  grep -qx 'mesh-clean: meshlabserver not found; skipping (copying IN.obj)' "$work/err" \
    || fail "message"
  cmp "$work/in/scene.obj" "$work/in/scene.clean.obj" || fail "copy differs"
  # usage errors: exit 2
  rc=0; "$root/scripts/mesh-clean" "$work/in/scene.obj" 2>/dev/null || rc=$?
  [[ $rc == 2 ]] || fail "missing OUT: exit $rc"
  rc=0; "$root/scripts/mesh-clean" "$work/in/scene.obj" x.obj --simplify 1.5 2>/dev/null || rc=$?
  [[ $rc == 2 ]] || fail "bad ratio: exit $rc"
  echo "ok: absent"
  exit 0
fi

if ! command -v meshlabserver >/dev/null || ! command -v xvfb-run >/dev/null; then
  echo "meshlab_clean: meshlabserver or xvfb-run not installed; skipping" \
       "(apt-get install meshlab xvfb xauth)"
  exit 77
fi
# no simplification: OUT.obj in another directory (mtllib must point back at in/scene.mtl)
"$root/scripts/mesh-clean" "$work/in/scene.obj" "$work/out/scene.clean.obj" 2>"$work/err" \
  || { cat "$work/err" >&2; fail "mesh-clean exit status"; }
cat "$work/err" >&2
grep -q 'vertices 77 -> 29, faces 39 -> 39' "$work/err" || fail "summary line"
grep -qx 'mtllib ../in/scene.mtl' "$work/out/scene.clean.obj" || fail "mtllib line"
"$scene" same "$work/in/scene.obj" "$work/out/scene.clean.obj"
[[ -z $(find "$work/out" -name '.*') ]] || fail "temporary files left"
# the checks see a moved texture coordinate (by 2e-6) and a swapped material
awk '/^vt / && !done { $2 = sprintf("%.6f", $2 + 2e-6); done = 1 } { print }' \
  "$work/out/scene.clean.obj" >"$work/out/moved_uv.obj"
awk '/^usemtl matB/ && !done { $2 = "matC"; done = 1 } { print }' \
  "$work/out/scene.clean.obj" >"$work/out/swapped.obj"
for bad in moved_uv swapped; do
  cmp -s "$work/out/scene.clean.obj" "$work/out/$bad.obj" && fail "$bad: not changed"
  rc=0; "$scene" same "$work/in/scene.obj" "$work/out/$bad.obj" 2>/dev/null || rc=$?
  [[ $rc == 1 ]] || fail "$bad: checker exit $rc"
  rc=0; "$bin/vt-obj2ply" --check --same-faces "$work/in/scene.obj" "$work/out/$bad.obj" || rc=$?
  [[ $rc == 1 ]] || fail "$bad: vt-obj2ply --check exit $rc"
done

# simplification to 50 % of the faces
"$root/scripts/mesh-clean" "$work/in/scene.obj" "$work/in/scene.simple.obj" --simplify 0.5 \
  2>"$work/err" || { cat "$work/err" >&2; fail "mesh-clean --simplify exit status"; }
cat "$work/err" >&2
grep -qx 'mtllib scene.mtl' "$work/in/scene.simple.obj" || fail "mtllib line (same directory)"
"$scene" simplified "$work/in/scene.obj" "$work/in/scene.simple.obj"

# a broken input fails with status 1 and writes nothing
printf 'v 0 0 0\nf 1 2 3\n' >"$work/in/bad.obj"
rc=0; "$root/scripts/mesh-clean" "$work/in/bad.obj" "$work/out/bad.obj" 2>"$work/err" || rc=$?
cat "$work/err" >&2
[[ $rc == 1 && ! -e $work/out/bad.obj ]] || fail "bad input: exit $rc"
echo "ok: meshlab"
