# A store is not written to a terminal, nor an image read from one: one line, exit 2, before any
# work (run under script(1), which gives the tool a pseudo-terminal).
set -euo pipefail
if ! script -qec true /dev/null >/dev/null 2>&1; then
  echo "skip: no pseudo-terminal here (script -qec true failed)"
  exit 77
fi
on_tty() { script -qec "$1" /dev/null </dev/null | tr -d '\r'; }
"$VT_SYNTH_IMAGE" photo.png --format png --size 96x64 --channels 3 --seed 4
rc=0; on_tty "'$VT_TILES' photo.png -o -" || rc=$?; echo "-o - to a terminal: exit $rc"
rc=0; on_tty "'$VT_TILES' - -o out.vts" || rc=$?; echo "- from a terminal: exit $rc"
ls -A
