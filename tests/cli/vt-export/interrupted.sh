# SIGTERM in the middle of an export: the tool stops its workers, removes its staging folder and
# dies of the signal (exit 143 here); nothing under DIR, no DIR.tmp-* left. The signal is sent
# once the staging folder holds tiles (the run takes seconds: 4096x4096 texels as PNG, -j 1).
set -euo pipefail
"$VT_SYNTH" big.vts --size 4096x4096 --tile 128 --codec raw
"$VT_EXPORT" big.vts -o out --format png -j 1 2>err.txt &
pid=$!
until [ -n "$(find . -path './out.tmp-*/*.png' -print -quit 2>/dev/null)" ]; do
  kill -0 $pid 2>/dev/null || { echo "the export ended before it could be interrupted"; exit 3; }
  sleep 0.05
done
kill -TERM $pid
rc=0; wait $pid || rc=$?
echo "exit $rc"
cat err.txt
ls -A
