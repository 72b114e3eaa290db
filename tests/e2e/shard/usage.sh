# --shard I/N: N a power of two up to 4096, I in 1..N; anything else is a usage error (exit 2);
# INPUT must be a regular file.
set -euo pipefail
"$VT_SYNTH_IMAGE" in.png --format png --size 300x200
for s in 0/4 5/4 1/3 1/0 x/4 1/4x -1/4 1/8192 ""; do
  "$VT_TILES" in.png -o out.vts --shard "$s" || echo "exit $?"
done
"$VT_TILES" in.png -o out.vts --shard 8/8 -q && echo "ok 8/8 accepted"
mkfifo fifo # every shard reads INPUT: a pipe is refused (bad input)
"$VT_TILES" fifo -o out.vts --shard 1/4 || echo "exit $?"
"$VT_TILES" --help | grep -e '--shard'
"$VT_MERGE" --help | grep -E 'shard|-j'
"$VT_MERGE" -j 0 in.png -o x.vts
