#!/usr/bin/env bash
# Runs one golden CLI case and compares its stdout, stderr and exit status with the expected files
# next to it: CASE.stdout, CASE.stderr (absent = empty) and CASE.exit (absent = 0).
#
#   run_case.sh [--update] CASE.sh WORK_DIR TOOL_PATH...
#
# The case runs with bash in a fresh WORK_DIR/run (its cwd) under LC_ALL=C; each TOOL_PATH is exported
# as an upper-case variable named after the file (vt-info -> VT_INFO, vt-cli-check ->
# VT_CLI_CHECK). A case sets `set -euo pipefail`, builds its inputs with vt-synth, and its last
# command is the one under test; checks that print "ok ..." lines become part of the golden stdout.
#
# --update (or VT_UPDATE_GOLDEN=1 in the environment, e.g. `VT_UPDATE_GOLDEN=1 ctest -R cli_`)
# rewrites the expected files from this run instead of comparing; review the diff before committing.
set -uo pipefail

update=${VT_UPDATE_GOLDEN:-0}
if [ "${1:-}" = "--update" ]; then
  update=1
  shift
fi
if [ $# -lt 2 ]; then
  echo "usage: run_case.sh [--update] CASE.sh WORK_DIR TOOL_PATH..." >&2
  exit 2
fi
case_script=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
work=$2
shift 2
for tool in "$@"; do
  name=$(basename "$tool" | tr 'a-z-' 'A-Z_')
  export "$name=$tool"
done
expected=${case_script%.sh}

rm -rf "$work/run" "$work/stdout" "$work/stderr" && mkdir -p "$work/run" || exit 2
(cd "$work/run" && LC_ALL=C bash "$case_script" >"$work/stdout" 2>"$work/stderr")
status=$?

# A case that cannot run here (no pseudo-terminal for script(1)) prints "skip: <reason>" first
# and exits 77: reported as skipped (SKIP_RETURN_CODE 77 in tests/cli/CMakeLists.txt), not
# compared and not rewritten.
if [ "$status" = 77 ] && head -n 1 "$work/stdout" | grep -q '^skip: '; then
  head -n 1 "$work/stdout"
  exit 77
fi

if [ "$update" = 1 ]; then
  for stream in stdout stderr; do
    if [ -s "$work/$stream" ]; then
      cp "$work/$stream" "$expected.$stream"
    else
      rm -f "$expected.$stream"
    fi
  done
  if [ "$status" -ne 0 ]; then echo "$status" >"$expected.exit"; else rm -f "$expected.exit"; fi
  echo "updated $(basename "$expected") (exit $status)"
  exit 0
fi

fail=0
for stream in stdout stderr; do
  want="$expected.$stream"
  [ -f "$want" ] || want=/dev/null
  if ! diff -u --label "expected $stream" --label "actual $stream" "$want" "$work/$stream"; then
    fail=1
  fi
done
want_status=0
[ -f "$expected.exit" ] && want_status=$(cat "$expected.exit")
if [ "$status" != "$want_status" ]; then
  echo "exit status $status, expected $want_status"
  fail=1
fi
if [ "$fail" -ne 0 ]; then
  echo "FAIL $(basename "$case_script") (work dir: $work; rerun with --update to accept)"
  exit 1
fi
echo "ok $(basename "$case_script")"
