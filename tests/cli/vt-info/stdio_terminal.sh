# A PNG is not written to a terminal, nor a store read from one: one line, exit 2, before any
# work (run under script(1), which gives the tool a pseudo-terminal). The text modes (summary,
# --json) still print to a terminal.
set -euo pipefail
if ! script -qec true /dev/null >/dev/null 2>&1; then
  echo "skip: no pseudo-terminal here (script -qec true failed)"
  exit 77
fi
on_tty() { script -qec "$1" /dev/null </dev/null | tr -d '\r'; }
"$VT_SYNTH" s.vts
rc=0; on_tty "'$VT_INFO' --extract 0 -o - s.vts" || rc=$?; echo "-o - to a terminal: exit $rc"
rc=0; on_tty "'$VT_INFO' - </dev/tty" || rc=$?; echo "- from a terminal: exit $rc"
on_tty "'$VT_INFO' --json s.vts" | head -n 2
ls -A
