#!/usr/bin/env bash
# Two builds writing the same output at the same time (docs/robustness.md, "Concurrent builds of
# one output"): builds A and B (different inputs, the same -o) are released at the same moment,
# ROUNDS times, alternately over a previous output and with none. Both must exit 0; the output
# must then be byte for byte A's or B's output built alone (never a mix, never a partial file);
# nothing else may be left in the directory (no temporary).
# The two runs wait on a FIFO that the test holds open and writes one line per run into, so that
# neither starts before both are ready; no step waits a fixed time. How many rounds really
# overlapped (each run's start before the other's end, from bash's clock) is printed, not
# required: a loaded machine may serialise them.
# usage: tool_concurrent.sh WORKDIR BIN_DIR TEST_BIN_DIR GROUP [ROUNDS]
# GROUP: vt-tiles, vt-tiles-layout, vt-merge, vt-atlas, vt-offset.
set -uo pipefail
work=$1 bin=$2 tbin=$3 group=$4 rounds=${5:-5}
rm -rf "$work" && mkdir -p "$work/log" && cd "$work" || exit 1
fail=0
err() { echo "FAIL ($group): $*" >&2; fail=1; }
image() { "$tbin/vt-synth-image" "$@" >/dev/null || exit 1; }
# shellcheck source=tool_scene.inc
source "$(dirname "${BASH_SOURCE[0]}")/tool_scene.inc"

# A small scene (three materials, a PNG, a JPEG and a tiled TIFF of 512x512), as in tool_eio.sh.
make_scene() {
  write_scene 512 ta.png tb.jpg tc.tif
}

outs=(out.vts)
case $group in
vt-tiles)
  image a.png --format png --size 1024x1024 --photo --seed 1
  image b.png --format png --size 1024x1024 --photo --seed 2
  cmd_a=("$bin/vt-tiles" a.png -o out.vts -q -j 1 --tile-size 128)
  cmd_b=("$bin/vt-tiles" b.png -o out.vts -q -j 1 --tile-size 128) ;;
vt-tiles-layout)
  make_scene
  "$bin/vt-atlas" scene.obj -o atlas64.json --tile-size 64 -q || exit 1
  "$bin/vt-atlas" scene.obj -o atlas32.json --tile-size 32 -q || exit 1
  cmd_a=("$bin/vt-tiles" --layout atlas64.json -o out.vts -q -j 1)
  cmd_b=("$bin/vt-tiles" --layout atlas32.json -o out.vts -q -j 1) ;;
vt-merge)
  image a.png --format png --size 1024x1024 --photo --seed 1
  image b.png --format png --size 1024x1024 --photo --seed 2
  for x in a b; do
    for i in 1 2; do
      "$bin/vt-tiles" $x.png -o $x$i.vts -q --tile-size 128 --shard $i/2 || exit 1
    done
  done
  cmd_a=("$bin/vt-merge" a1.vts a2.vts -o out.vts -q -j 1)
  cmd_b=("$bin/vt-merge" b1.vts b2.vts -o out.vts -q -j 1) ;;
vt-atlas)
  make_scene
  outs=(out.json)
  cmd_a=("$bin/vt-atlas" scene.obj -o out.json --tile-size 64 -q)
  cmd_b=("$bin/vt-atlas" scene.obj -o out.json --tile-size 32 -q) ;;
vt-offset)
  # a 4 MB scene (vt-offset-gen) on two atlases of different widths: different vt lines
  "$tbin/vt-offset-gen" bench . 4 >/dev/null || exit 1
  sed '0,/"width": 1048576/s//"width": 2097152/' atlas.json >atlas2.json
  outs=(out.obj out.mtl)
  cmd_a=("$bin/vt-offset" scene.obj atlas.json -o out.obj -q)
  cmd_b=("$bin/vt-offset" scene.obj atlas2.json -o out.obj -q) ;;
*)
  echo "tool_concurrent.sh: unknown group '$group'" >&2
  exit 2 ;;
esac

listing() { find . -mindepth 1 -maxdepth 1 ! -name log -printf '%f\n' | LC_ALL=C sort; }
remove_outputs() { local o; for o in "${outs[@]}"; do rm -f "$o"; done; }

# References: each build alone; they must differ (else the test shows nothing).
for x in a b; do
  remove_outputs
  declare -n cmd=cmd_$x
  "${cmd[@]}" 2>log/ref.err || { err "build $x alone failed: $(cat log/ref.err)"; exit 1; }
  for o in "${outs[@]}"; do cp "$o" "log/$x.$o"; done
done
for o in "${outs[@]}"; do
  cmp -s "log/a.$o" "log/b.$o" && [ "$o" = "${outs[0]}" ] && err "builds a and b write the same $o"
done
[ $fail -eq 0 ] || exit 1

# whose OUTPUT: a or b when it is byte for byte that build's, else "neither".
whose() {
  if cmp -s "$1" "log/a.$1"; then echo a
  elif cmp -s "$1" "log/b.$1"; then echo b
  else echo neither; fi
}

overlapped=0 mixed=0
mkfifo log/go
for round in $(seq 1 "$rounds"); do
  remove_outputs
  if [ $((round % 2)) -eq 0 ]; then
    for o in "${outs[@]}"; do printf 'previous %s\n' "$o" >"$o"; done
  fi
  before=$(listing)
  exec 3<>log/go # held open: a run that opens the FIFO late still finds its line
  for x in a b; do
    declare -n cmd=cmd_$x
    (
      read -r _ <log/go
      start=$EPOCHREALTIME
      "${cmd[@]}"
      s=$?
      echo "$start $EPOCHREALTIME" >log/$x.time
      exit $s
    ) 2>log/$x.err &
    eval "pid_$x=\$!"
  done
  printf 'go\ngo\n' >&3
  wait "$pid_a"; status_a=$?
  wait "$pid_b"; status_b=$?
  exec 3>&-
  [ "$status_a" -eq 0 ] || err "round $round: build a exited $status_a: $(cat log/a.err)"
  [ "$status_b" -eq 0 ] || err "round $round: build b exited $status_b: $(cat log/b.err)"
  [ -s log/a.err ] || [ -s log/b.err ] && err "round $round: messages: $(cat log/a.err log/b.err)"
  owners=""
  for o in "${outs[@]}"; do
    w=$(whose "$o")
    [ "$w" != neither ] || err "round $round: $o is neither build's output ($(wc -c <"$o") bytes)"
    owners+="$o=$w "
  done
  # vt-offset: OUT.obj and OUT.mtl are two files, each renamed on its own: they may come from
  # different builds (only the MTL's comment lines differ). Counted, not a failure.
  [ ${#outs[@]} -gt 1 ] && [ "$(echo "$owners" | tr ' ' '\n' | cut -d= -f2 | sort -u | grep -c .)" -gt 1 ] &&
    mixed=$((mixed + 1))
  after=$(listing)
  expected=$( (echo "$before"; printf '%s\n' "${outs[@]}") | grep . | LC_ALL=C sort -u)
  [ "$after" = "$expected" ] ||
    err "round $round: left: $(comm -13 <(echo "$expected") <(echo "$after") | tr '\n' ' ')"
  read -r a0 a1 <log/a.time
  read -r b0 b1 <log/b.time
  awk -v a0="$a0" -v a1="$a1" -v b0="$b0" -v b1="$b1" 'BEGIN { exit !(a0 < b1 && b0 < a1) }' &&
    overlapped=$((overlapped + 1))
  printf 'round %d: %s(a %.2f s, b %.2f s)\n' "$round" "$owners" \
    "$(awk -v s="$a0" -v e="$a1" 'BEGIN { print e - s }')" \
    "$(awk -v s="$b0" -v e="$b1" 'BEGIN { print e - s }')"
done
echo "tool_concurrent $group: $rounds rounds, $overlapped overlapped in time$([ ${#outs[@]} -gt 1 ] && echo ", $mixed with ${outs[*]} from different builds")"
[ $fail -eq 0 ] && echo "tool_concurrent $group: ok"
exit $fail
