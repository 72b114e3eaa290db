# -o - writes the store to standard output (spooled in $TMPDIR, then copied): the same bytes as
# -o FILE, into a file or a pipe, for an image and for --layout; no file named '-' appears, no
# spool is left and nothing else is on stdout.
set -euo pipefail
mkdir tmp
export TMPDIR=$PWD/tmp
"$VT_SYNTH_IMAGE" photo.png --format png --size 96x64 --channels 3 --seed 4
"$VT_TILES" photo.png -o file.vts --codec png
"$VT_TILES" photo.png -o - --codec png >dash.vts
cmp file.vts dash.vts && echo "ok -o - equals -o FILE"
"$VT_TILES" -v photo.png --output - --codec png -j 2 | cat >piped.vts
cmp file.vts piped.vts && echo "ok -o - through a pipe equals -o FILE"
"$VT_INFO" --verify piped.vts
mkdir tex
"$VT_SYNTH_IMAGE" tex/b.png --format png --size 64x32 --channels 3 --seed 2
printf 'photo.png\ntex/b.png\n' >list.txt
"$VT_ATLAS" -q --textures list.txt -o atlas.json
"$VT_TILES" --layout atlas.json -o atlas_file.vts --codec png
"$VT_TILES" --layout atlas.json -o - --codec png >atlas_dash.vts
cmp atlas_file.vts atlas_dash.vts && echo "ok --layout -o - equals -o FILE"
ls -A . tmp
