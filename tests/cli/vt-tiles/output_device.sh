# A character device (a copy of /dev/null made here) and a FIFO as output: written into, never
# replaced by a regular file; the store read from the FIFO is the one a regular output gets; no
# temporary or spool is left in the folder.
set -euo pipefail
"$VT_SYNTH_IMAGE" photo.png --format png --size 96x64 --channels 3 --seed 4
"$VT_TILES" photo.png -o ref.vts --codec png
mknod null c 1 3
"$VT_TILES" photo.png -o null --codec png
stat -c 'null: %F %t,%T' null
mkfifo pipe.vts
timeout 60 cat pipe.vts >from_pipe.vts &
reader=$!
"$VT_TILES" photo.png -o pipe.vts --codec png
wait "$reader"
stat -c 'pipe.vts: %F' pipe.vts
cmp ref.vts from_pipe.vts && echo "ok the FIFO got the store"
"$VT_INFO" --verify from_pipe.vts
ls -A
