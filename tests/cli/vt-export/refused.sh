# Layers that cannot be exported as asked (float samples, alpha as JPEG) and outputs that would
# replace something: exit 1 with one line, nothing written, the existing folder untouched;
# --force replaces a folder, but never the one that holds the store.
set -euo pipefail
"$VT_SYNTH" f.vts --size 64x64 --tile 32 --sample f32 --codec raw
"$VT_SYNTH" a.vts --size 64x64 --tile 32 --channels 4 --codec png
rc=0; "$VT_EXPORT" f.vts -o out || rc=$?; echo "float: exit $rc"
rc=0; "$VT_EXPORT" a.vts -o out --format jpeg || rc=$?; echo "alpha as jpeg: exit $rc"
rc=0; "$VT_EXPORT" missing.vts -o out || rc=$?; echo "missing store: exit $rc"
mkdir busy && touch busy/keep
rc=0; "$VT_EXPORT" a.vts -o busy || rc=$?; echo "non-empty folder: exit $rc"
touch file
rc=0; "$VT_EXPORT" a.vts -o file || rc=$?; echo "a file: exit $rc"
ls busy
"$VT_EXPORT" -q a.vts -o busy --force && ls busy
mkdir inside && cp a.vts inside/
rc=0; "$VT_EXPORT" inside/a.vts -o inside --force || rc=$?; echo "holds the store: exit $rc"
ls inside
mkdir empty && "$VT_EXPORT" -q a.vts -o empty/ && ls empty
ls | grep -c tmp- || true
