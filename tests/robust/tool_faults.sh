#!/usr/bin/env bash
# Fault injection against the tools that write outputs (docs/robustness.md, "Faults"): SIGINT and
# SIGTERM at several points, SIGKILL at several points, a full disk (file size limit with SIGXFSZ
# ignored, so writes fail with EFBIG like ENOSPC), and a read error (a directory as input).
# After each: the output name holds either the previous output, intact, or a complete new one that
# verifies; no hidden temporary file is left after SIGINT/SIGTERM or a failure; failures exit 1
# with one line naming the file.
# No step waits a fixed time for the tool to get somewhere: each signal is sent once the tool is
# seen writing its output (its temporary or unnamed spool open in /proc/PID/fd), then either at
# once (the tool must die of the signal, old output intact) or after a fraction of the writing
# time the reference run took (any outcome above is right). A slow machine only makes it slower.
# usage: tool_faults.sh WORKDIR TOOL_NAME BIN_DIR SYNTH SYNTH_IMAGE [SAMPLE_SCENE]
# TOOL_NAME vt-tiles-layout is vt-tiles --layout on the sample scene (SAMPLE_SCENE: the
# vt-sample-scene generator).
set -uo pipefail
work=$1 name=$2 bin=$3 synth=$4 synth_image=$5 sample_scene=${6:-}
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
here=$(pwd -P) # as /proc/PID/fd shows it
info="$bin/vt-info"
out=out.vts
fail=0
err() { echo "FAIL ($name): $*" >&2; fail=1; }

# Inputs and the command under test, one per tool; slow enough (about 1-3 s) to be interrupted.
case $name in
vt-tiles)
  "$synth_image" in.png --format png --size 3000x3000 --photo >/dev/null || exit 1
  cmd=("$bin/vt-tiles" in.png -o out.vts -q -j 1 --codec png --mode best)
  dir_cmd=("$bin/vt-tiles" indir -o out.vts -q) ;;
vt-tiles-layout)
  "$sample_scene" -q scene >/dev/null || exit 1
  "$bin/vt-atlas" scene/scene.obj -o atlas.json --wrap replicate -q || exit 1
  cmd=("$bin/vt-tiles" --layout atlas.json -o out.vts -q -j 1 --codec png --mode best)
  dir_cmd=("$bin/vt-tiles" --layout indir -o out.vts -q) ;;
vt-convert)
  "$synth" in.vts --size 3000x3000 --tile 256 --codec raw --channels 3 >/dev/null || exit 1
  cmd=("$bin/vt-convert" in.vts -o out.vts -q -j 1 --codec png --mode best)
  dir_cmd=("$bin/vt-convert" indir -o out.vts -q --codec png) ;;
vt-merge)
  # Two identical stores merge as shards (every tile the same bytes in both).
  "$synth" a.vts --size 3000x3000 --tile 256 --codec raw --channels 3 --seed 1 >/dev/null || exit 1
  cp a.vts b.vts
  cmd=("$bin/vt-merge" a.vts b.vts -o out.vts -q)
  dir_cmd=("$bin/vt-merge" indir b.vts -o out.vts -q) ;;
vt-offset)
  # A 60 MB scene (vt-offset-gen: v, vt, vn, faces of 8 materials, shared vt) and its atlas.
  "$(dirname "$synth")/vt-offset-gen" bench . 60 >/dev/null || exit 1
  out=out.obj
  cmd=("$bin/vt-offset" scene.obj atlas.json -o out.obj -q)
  dir_cmd=("$bin/vt-offset" indir atlas.json -o out.obj -q) ;;
*)
  echo "tool_faults.sh: unknown tool $name" >&2; exit 2 ;;
esac
mkdir -p indir

printf 'previous output\n' > previous.ref
previous() { cp previous.ref "$out"; }
intact() { cmp -s previous.ref "$out"; }
leftovers() { find . -maxdepth 1 -name '.out.*' | wc -l; }
# A complete output: a store that verifies, or the reference run's bytes for other outputs.
complete() {
  case $out in
  *.vts) "$info" --verify "$out" >/dev/null 2>&1 ;;
  *) cmp -s "$out" reference.out ;;
  esac
}

# writing PID: the tool has its output open: an unnamed spool (O_TMPFILE: "DIR/#INODE (deleted)")
# or a hidden temporary (.out.vts.tmp-*, .out.obj.tmp-*, .out.vts.spool-*) in this directory.
writing() {
  [ -n "$(find /proc/"$1"/fd -maxdepth 1 \( -lname "$here/#*" -o -lname "$here/.out.*" \) \
    -print -quit 2>/dev/null)" ]
}
# running PID: not exited (a zombie, exited but not yet waited for, counts as exited).
running() {
  local _pid _comm state
  read -r _pid _comm state _ 2>/dev/null </proc/"$1"/stat && [ "$state" != Z ]
}
# wait_writing PID: polls until the tool writes its output (true) or exits (false); a deadline of
# 300 s, far beyond any run, only stops a hung tool.
wait_writing() {
  local deadline=$((SECONDS + 300))
  while running "$1" && [ $SECONDS -lt $deadline ]; do
    writing "$1" && return 0
    sleep 0.005
  done
  return 1
}
now() { date +%s.%N; }
# after SECONDS_FLOAT FRACTION: the product, for sleep.
scaled() { awk -v t="$1" -v f="$2" 'BEGIN { printf "%.3f", t * f }'; }

# A reference run must succeed (else the tool or the test is broken); it also measures how long
# the tool writes (from the moment it is seen writing to its exit), for the later kills.
previous
"${cmd[@]}" 2>ref.err & pid=$!
t0=$(now)
wait_writing "$pid" && t0=$(now) # not seen writing: the whole run stands for it
wait "$pid" || { err "reference run failed: $(cat ref.err)"; exit 1; }
write_seconds=$(awk -v a="$t0" -v b="$(now)" 'BEGIN { printf "%.3f", b - a }')
echo "reference run: writes for $write_seconds s"
cp "$out" reference.out
complete || err "reference output does not verify"
[ "$(leftovers)" -eq 0 ] || err "temporary files left after a successful run"

# outcome STATUS: the output name holds the old file (interrupted) or a complete new one that
# verifies (finished; a signal that lands after the rename still kills the process).
outcome() {
  local status=$1 what=$2
  if intact; then
    [ "$status" -ne 0 ] || err "$what: exit 0 but the old output is still there"
  else
    complete || err "$what: exit $status and the output was replaced by an incomplete one"
  fi
}

# signal_run SIG FRACTION: starts the tool, waits until it writes, waits FRACTION of the reference
# writing time more, sends SIG; sets status (of the wait) and what (for messages). A run that
# finishes before it is seen writing (the poll is not instantaneous, vt-merge writes for a tenth
# of a second) must be a normal complete run, and is started again (up to 20 times).
signal_run() {
  local sig=$1 fraction=$2 attempt
  what="SIG$sig at $fraction of the writing time"
  for attempt in $(seq 1 20); do
    previous
    "${cmd[@]}" 2>/dev/null & pid=$!
    wait_writing "$pid" && break
    wait "$pid"; status=$?
    [ "$status" -eq 0 ] && complete || err "$what: a run not seen writing exited $status"
    [ "$attempt" -lt 20 ] || { err "$what: 20 runs, none seen writing"; return; }
  done
  [ "$fraction" = 0 ] || sleep "$(scaled "$write_seconds" "$fraction")"
  kill -"$sig" "$pid" 2>/dev/null
  wait "$pid" 2>/dev/null; status=$?
  [ "$attempt" -eq 1 ] || echo "$what: seen writing at run $attempt"
}

for sig in INT TERM; do
  code=$((128 + $(kill -l "$sig")))
  # at once: the tool has most of its work ahead, so it must die of the signal, cleanly
  signal_run "$sig" 0
  [ "$status" -eq "$code" ] || err "$what: exit $status, not death by the signal"
  intact || err "$what: the old output was replaced"
  [ "$(leftovers)" -eq 0 ] || err "$what: temporary files left: $(ls -a)"
  # later: interrupted or finished, both clean
  for fraction in 0.3 0.8; do
    signal_run "$sig" "$fraction"
    outcome "$status" "$what"
    [ "$status" -eq 0 ] || [ "$status" -eq "$code" ] ||
      err "$what: exit $status, not death by the signal"
    [ "$(leftovers)" -eq 0 ] || err "$what: temporary files left: $(ls -a)"
  done
done

for fraction in 0 0.3 0.8 1.5; do
  signal_run KILL "$fraction"
  if [ "$fraction" = 0 ]; then
    [ "$status" -eq 137 ] || err "$what: exit $status, not death by SIGKILL"
    intact || err "$what: the old output was replaced"
  fi
  outcome "$status" "$what"
  # A killed process cannot clean up: remove what it left before the next round.
  find . -maxdepth 1 -name '.out.*' -delete
done

# Full disk: a 256 KiB file size limit; SIGXFSZ ignored so the write fails with EFBIG.
previous
(trap '' XFSZ; ulimit -f 256; exec "${cmd[@]}") 2>full.err; status=$?
[ "$status" -eq 1 ] || err "full disk: exit $status, expected 1 ($(cat full.err))"
intact || err "full disk: the old output was replaced"
[ "$(wc -l < full.err)" -eq 1 ] || err "full disk: expected one line, got: $(cat full.err)"
grep -q "$out" full.err || err "full disk: the message does not name the output: $(cat full.err)"
[ "$(leftovers)" -eq 0 ] || err "full disk: temporary files left"

# Read error: a directory where an input file should be.
previous
"${dir_cmd[@]}" 2>dir.err; status=$?
[ "$status" -eq 1 ] || err "directory input: exit $status, expected 1 ($(cat dir.err))"
grep -q "indir" dir.err || err "directory input: the message does not name it: $(cat dir.err)"
[ "$(wc -l < dir.err)" -eq 1 ] || err "directory input: expected one line: $(cat dir.err)"
intact || err "directory input: the old output was replaced"

[ $fail -eq 0 ] && echo "tool_faults $name: ok"
exit $fail
