#!/bin/bash
# End-to-end test of scripts/vt.mk on the sample scene (samples/Makefile):
#   1. a full build; every output is there and verified
#   2. make again: prints nothing, make -q says up to date, no output file changes
#   3. touch one texture: the atlas step runs, the store is rebuilt and verified; the rewritten
#      OBJ is not (its inputs, the OBJ and an unchanged layout, did not change)
#   3b. edit the OBJ: the OBJ is rewritten again, the store is not (same layout)
#   4. SIGINT to the whole make (as Ctrl-C does) while vt-tiles writes the store: no temporary
#      file is left, and the next make rebuilds a store that verifies
# No step waits a fixed time for something to happen: the SIGINT goes once vt-tiles is seen writing
# the store, and a source is changed only once the clock has moved past the outputs' dates, so a
# slow or loaded machine only makes the test slower.
#   5. a clean make -j4: the same store, byte for byte
#   6. deliveries (VT_DELIVERY): one codec for every layer, and one codec per layer; verified,
#      the first named by the rewritten MTL
#   7. changing a tool option rebuilds what that tool makes
# Usage: make_rules.sh fake|hybrid|real WORKDIR SOURCE_DIR GENERATOR MAKE [TOOLS_DIR]
#   fake: the stand-in tools of tests/e2e/samples/fake (obey the CLI contract; the store is a text
#         file that vt-info checks), with a 4x smaller scene
#   hybrid: the real vt-atlas and vt-offset of TOOLS_DIR, the stand-ins for the rest
#   real: the tools in TOOLS_DIR, the full-size scene (generator options: $VT_SAMPLE_TEST_FLAGS);
#         exits 77 (skipped) while vt-tiles lacks --layout
set -euo pipefail
mode=$1
work=$2
src=$3
gen=$(realpath "$4")
make=$5
case $mode in
fake)
    bin=$src/tests/e2e/samples/fake
    flags=--shrink\ 4
    export FAKE_LOG=$work/tools.log
    ;;
hybrid)
    # the real vt-atlas and vt-offset (TOOLS_DIR), stand-ins for the store tools
    bin=$work.tools
    rm -rf "$bin"
    mkdir -p "$bin"
    ln -s "$6/vt-atlas" "$6/vt-offset" "$bin/"
    ln -s "$src/tests/e2e/samples/fake/vt-tiles" "$src/tests/e2e/samples/fake/vt-info" \
        "$src/tests/e2e/samples/fake/vt-convert" "$bin/"
    flags=--shrink\ 4
    ;;
real)
    bin=$6
    flags=${VT_SAMPLE_TEST_FLAGS-}
    if ! "$bin/vt-tiles" --help 2>&1 | grep -- "--layout" >/dev/null; then
        echo "SKIP: $bin/vt-tiles has no --layout option yet"
        exit 77
    fi
    ;;
*) echo "usage: make_rules.sh fake|hybrid|real WORKDIR SOURCE_DIR GENERATOR MAKE [TOOLS_DIR]" >&2; exit 2 ;;
esac

rm -rf "$work"
mkdir -p "$work"
cd "$work"
out=$work/o/out
srcdir=$work/o/src
fail() {
    echo "FAIL: $*" >&2
    exit 1
}
m() {
    "$make" --no-print-directory -f "$src/samples/Makefile" VT_BIN="$bin" VT_SAMPLE_SCENE="$gen" \
        O="$work/o" SAMPLE_FLAGS="$flags" "$@"
}
# Dates (ns) of every file under o/, one "path date" per line.
dates() {
    find "$work/o" -type f -printf '%p %T@\n' | sort
}
date_of() {
    stat -c %.9Y "$1"
}
no_temp_files() {
    local left
    left=$(find "$work/o" \( -name '.*' -o -name '*.new' -o -name '*.tmp' -o -name '*.part' \) -print)
    [ -z "$left" ] || fail "temporary files left: $left"
}
verify_store() {
    if [ "$mode" = real ]; then
        "$bin/vt-info" --verify "$1" || fail "vt-info --verify $1"
    else
        "$bin/vt-info" "$1" || fail "fake verify $1"
    fi
}
step() {
    echo "== $*"
}
# The newest file under o/.
newest() {
    find "$work/o" -type f -printf '%T@ %p\n' | sort -n | tail -n 1 | cut -d ' ' -f 2-
}
# Waits until a file changed now gets a later date than every output (dates come from a coarse
# clock: a change in the same tick as the last output would look no newer to make).
wait_past_outputs() {
    local ref
    ref=$(newest)
    for _ in $(seq 1 600); do
        touch "$work/clock"
        [ "$work/clock" -nt "$ref" ] && return 0
        sleep 0.01
    done
    fail "the clock did not move past $ref"
}

step "1. full build"
t0=$(date +%s.%N)
m >"$work/build1.log" 2>&1 || { cat "$work/build1.log"; fail "first make"; }
t1=$(date +%s.%N)
awk -v a="$t0" -v b="$t1" 'BEGIN { printf "full build: %.2f s\n", b - a }'
for f in scene.atlas.json scene.atlas.d scene.vts scene.vt.obj scene.vt.mtl scene.vts.ok; do
    [ -s "$out/$f" ] || [ "$f" = scene.vts.ok ] || fail "$f missing or empty"
    [ -e "$out/$f" ] || fail "$f missing"
done
grep -q "scene.vts" "$out/scene.vt.mtl" || fail "scene.vt.mtl does not name scene.vts"
grep -q "textures/t07.png" "$out/scene.atlas.d" || fail "scene.atlas.d does not list t07.png"
grep -q "scene.mtl" "$out/scene.atlas.d" || fail "scene.atlas.d does not list scene.mtl"
verify_store "$out/scene.vts"
no_temp_files
cp "$out/scene.vts" "$work/first.vts"

step "2. make again: nothing to do"
before=$(dates)
wait_past_outputs # a file rewritten now would get another date
again=$(m 2>&1) || fail "second make: $again"
[ -z "$again" ] || fail "second make printed: $again"
m -q || fail "make -q: not up to date"
[ "$before" = "$(dates)" ] || fail "files changed on a no-op make"

step "3. touch one texture"
atlas_date=$(date_of "$out/scene.atlas.json")
store_date=$(date_of "$out/scene.vts")
obj_date=$(date_of "$out/scene.vt.obj")
wait_past_outputs
touch "$srcdir/textures/t07.png"
log=$(m 2>&1) || fail "make after touch: $log"
echo "$log"
grep -q -- "--layout" <<<"$log" || fail "vt-tiles did not run"
[ "$(date_of "$out/scene.vts")" != "$store_date" ] || fail "store not rebuilt"
if [ "$(date_of "$out/scene.atlas.json")" = "$atlas_date" ]; then
    # the layout did not change, so the rewritten OBJ must not be made again
    [ "$(date_of "$out/scene.vt.obj")" = "$obj_date" ] || fail "scene.vt.obj rebuilt for a texel change"
else
    echo "note: vt-atlas wrote a different layout for the same inputs; the OBJ was rewritten"
fi
verify_store "$out/scene.vts"
cmp -s "$out/scene.vts" "$work/first.vts" || fail "same texels, different store"
again=$(m 2>&1) || fail "make: $again"
[ -z "$again" ] || fail "make after the rebuild printed: $again"

step "3b. edit the OBJ (not its materials)"
store_date=$(date_of "$out/scene.vts")
obj_date=$(date_of "$out/scene.vt.obj")
wait_past_outputs
echo "# edited" >>"$srcdir/scene.obj"
log=$(m 2>&1) || fail "make after the OBJ edit: $log"
[ "$(date_of "$out/scene.vt.obj")" != "$obj_date" ] || fail "scene.vt.obj not rebuilt"
if [ "$(date_of "$out/scene.atlas.json")" = "$atlas_date" ]; then
    [ "$(date_of "$out/scene.vts")" = "$store_date" ] || fail "store rebuilt for an OBJ edit"
fi
again=$(m 2>&1) || fail "make: $again"
[ -z "$again" ] || fail "make after the OBJ edit printed: $again"

step "4. SIGINT while the store is written"
export FAKE_TILES_SLEEP=5
out_phys=$(cd "$out" && pwd -P) # as /proc/PID/fd shows it
# The vt-tiles processes of make's process group $1.
tiles_pids() {
    ps -eo pid=,pgid=,args= | awk -v g="$1" '$2 == g && /--layout/ { print $1 }'
}
# True once vt-tiles writes the store: a hidden temporary of it exists (the stand-in writes one
# after setting its SIGINT trap), or a vt-tiles holds an unnamed spool (O_TMPFILE) or a hidden
# temporary of it open (the real one, whose handlers are set before it creates any).
store_writing() {
    local pid
    compgen -G "$out/.scene.vts.*" >/dev/null && return 0
    for pid in $(tiles_pids "$1"); do
        [ -n "$(find /proc/"$pid"/fd -maxdepth 1 \( -lname "$out_phys/#*" -o \
            -lname "$out_phys/.scene.vts.*" \) -print -quit 2>/dev/null)" ] && return 0
    done
    return 1
}
# Running (not exited, not a zombie).
running() {
    local _pid _comm state
    read -r _pid _comm state _ 2>/dev/null </proc/"$1"/stat && [ "$state" != Z ]
}
# Polls until the store is being written (SIGINT to the whole make then) or make exits; a real
# vt-tiles can be done before it is seen, then the build is made again (up to 10 times).
caught=
for attempt in $(seq 1 10); do
    wait_past_outputs
    touch "$srcdir/textures/t07.png"
    # Job control on: the background make gets its own process group and SIGINT is not ignored
    # (without it, bash starts background commands with SIGINT ignored, and make keeps it so).
    set -m
    "$make" --no-print-directory -f "$src/samples/Makefile" VT_BIN="$bin" VT_SAMPLE_SCENE="$gen" \
        O="$work/o" SAMPLE_FLAGS="$flags" >"$work/interrupted.log" 2>&1 &
    pid=$!
    set +m
    deadline=$((SECONDS + 300)) # far beyond any build: only stops a hung one
    while running "$pid" && [ $SECONDS -lt $deadline ]; do
        if store_writing "$pid"; then
            caught=1
            kill -INT -- "-$pid" 2>/dev/null || true
            break
        fi
        sleep 0.01
    done
    rc=0
    wait "$pid" || rc=$?
    # make waits for its jobs, but look for temporaries only once no vt-tiles is left at all
    while [ -n "$(tiles_pids "$pid")" ] && [ $SECONDS -lt $deadline ]; do
        sleep 0.01
    done
    [ -z "$(tiles_pids "$pid")" ] || fail "vt-tiles still runs after the interrupted make"
    cat "$work/interrupted.log"
    if [ -n "$caught" ]; then
        echo "interrupted make (run $attempt, SIGINT while vt-tiles wrote the store): exit $rc"
        break
    fi
    [ "$rc" -eq 0 ] || fail "make (not interrupted) failed: exit $rc"
    echo "run $attempt: vt-tiles finished before it was seen writing; again"
done
[ -n "$caught" ] || fail "vt-tiles was never seen writing the store (10 runs)"
# GNU make dies of the SIGINT (130), or stops with "wait: No child processes" (2) when vt-tiles,
# dying of it too, was reaped first: either way not 0
[ "$rc" -ne 0 ] || fail "the interrupted make exited 0"
unset FAKE_TILES_SLEEP
no_temp_files
if [ -e "$out/scene.vts" ]; then
    # what is left under the final name is a complete store (the previous one)
    verify_store "$out/scene.vts"
fi
log=$(m 2>&1) || fail "make after the interrupt: $log"
grep -q -- "--layout" <<<"$log" || fail "the store was not rebuilt after the interrupt"
verify_store "$out/scene.vts"
cmp -s "$out/scene.vts" "$work/first.vts" || fail "store after the interrupt differs"
no_temp_files
again=$(m 2>&1) || fail "make: $again"
[ -z "$again" ] || fail "make after the interrupted build printed: $again"

step "5. clean make -j4"
rm -rf "$out"
m -j4 >"$work/build-j4.log" 2>&1 || { cat "$work/build-j4.log"; fail "make -j4"; }
cmp -s "$out/scene.vts" "$work/first.vts" || fail "make -j4 built a different store"
[ -e "$out/scene.vts.ok" ] || fail "not verified"
no_temp_files
again=$(m -j4 2>&1) || fail "make -j4: $again"
[ -z "$again" ] || fail "make -j4 again printed: $again"

step "6. deliveries: png for every layer, and gpu = bc3 for layer 0, bc1 for layer 1"
dl=(VT_DELIVERY="png gpu" VT_gpu_LAYERS="0:bc3 1:bc1")
m -j4 "${dl[@]}" >"$work/delivery.log" 2>&1 || { cat "$work/delivery.log"; fail "delivery"; }
[ -e "$out/scene.png.vts.ok" ] || fail "scene.png.vts not verified"
[ -e "$out/scene.gpu.vts.ok" ] || fail "scene.gpu.vts not verified"
grep -q "scene.png.vts" "$out/scene.vt.mtl" || fail "scene.vt.mtl does not name scene.png.vts"
verify_store "$out/scene.png.vts"
verify_store "$out/scene.gpu.vts"
if [ "$mode" = real ]; then
    "$bin/vt-info" "$out/scene.gpu.vts" | grep "^layer"
    "$bin/vt-info" "$out/scene.gpu.vts" | grep "^layer 0 'diffuse': bc3" >/dev/null || fail "layer 0 not bc3"
    "$bin/vt-info" "$out/scene.gpu.vts" | grep "^layer 1 'normal': bc1" >/dev/null || fail "layer 1 not bc1"
    "$bin/vt-info" "$out/scene.gpu.vts" | grep "^layer 2 'alpha': png" >/dev/null || fail "layer 2 not kept"
fi
no_temp_files
again=$(m "${dl[@]}" 2>&1) || fail "make: $again"
[ -z "$again" ] || fail "delivery make again printed: $again"
m >/dev/null 2>&1 || fail "back to no delivery"
if grep -q "scene.png.vts" "$out/scene.vt.mtl" || ! grep -q "scene.vts" "$out/scene.vt.mtl"; then
    fail "scene.vt.mtl still names the delivery store"
fi

step "7. a changed tool option rebuilds what the tool makes"
obj_date=$(date_of "$out/scene.vt.obj")
log=$(m VT_TILES_FLAGS=-j2 2>&1) || fail "make with VT_TILES_FLAGS: $log"
grep -q -- "--layout" <<<"$log" || fail "vt-tiles did not rerun for new options"
[ "$(date_of "$out/scene.vt.obj")" = "$obj_date" ] || fail "vt-offset reran for a vt-tiles option"
no_temp_files
echo "all make-rule checks passed ($mode tools)"
