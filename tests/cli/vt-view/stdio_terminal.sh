# A PNG is not written to a terminal: one line, exit 2, before any work; --stats - (text) is
# written there (run under script(1), which gives the tool a pseudo-terminal).
set -euo pipefail
if ! script -qec true /dev/null >/dev/null 2>&1; then
  echo "skip: no pseudo-terminal here (script -qec true failed)"
  exit 77
fi
export MESA_SHADER_CACHE_DISABLE=true EGL_LOG_LEVEL=fatal
on_tty() { script -qec "$1" /dev/null </dev/null | tr -d '\r'; }
"$VT_SYNTH_IMAGE" photo.png --format png --size 96x64 --channels 3 --seed 4
"$VT_TILES" -q photo.png -o s.vts --codec png
view="'$VT_VIEW' s.vts --headless --size 64x48 --frames 1 --sync"
rc=0; on_tty "$view --screenshot -" || rc=$?; echo "--screenshot - to a terminal: exit $rc"
rc=0; on_tty "$view --stats -" | head -n 2 || rc=$?; echo "--stats - to a terminal: exit $rc"
ls -A
