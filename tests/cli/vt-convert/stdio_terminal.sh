# A store is not written to a terminal: one line, exit 2, before any work (run under script(1),
# which gives the tool a pseudo-terminal).
set -euo pipefail
if ! script -qec true /dev/null >/dev/null 2>&1; then
  echo "skip: no pseudo-terminal here (script -qec true failed)"
  exit 77
fi
"$VT_SYNTH" in.vts
rc=0; script -qec "'$VT_CONVERT' in.vts -o - --codec png" /dev/null </dev/null | tr -d '\r' || rc=$?
echo "-o - to a terminal: exit $rc"
ls -A
