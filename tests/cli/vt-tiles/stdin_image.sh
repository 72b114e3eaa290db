# INPUT - reads the image from standard input, copied to a temporary file in $TMPDIR (removed at
# the end) that the readers open as a file: the store equals the one built from that file. The
# metadata's source is '<stdin>', so the file run reads a copy named '<stdin>' and the stores
# are compared byte for byte (PNG, and a tiled TIFF that every worker opens on its own); from a
# pipe, and - to -.
set -euo pipefail
mkdir tmp
export TMPDIR=$PWD/tmp
"$VT_SYNTH_IMAGE" photo.png --format png --size 96x64 --channels 3 --seed 4
"$VT_SYNTH_IMAGE" tiled.tif --format tiff --size 300x200 --channels 4 --tile 64 --seed 2
cp photo.png '<stdin>'
"$VT_TILES" '<stdin>' -o file.vts --codec png
"$VT_TILES" - -o stdin.vts --codec png <photo.png
cmp file.vts stdin.vts && echo "ok - equals the file (png)"
"$VT_INFO" stdin.vts | grep -E '^  source='
cat photo.png | "$VT_TILES" - -o - --codec png | cmp - file.vts && echo "ok - to - through pipes"
cp tiled.tif '<stdin>'
"$VT_TILES" '<stdin>' -o tiff_file.vts --codec png -j 3
"$VT_TILES" -v - -o tiff_stdin.vts --codec png -j 3 <tiled.tif 2>err.txt
cmp tiff_file.vts tiff_stdin.vts && echo "ok - equals the file (tiled tiff, -j 3)"
grep -c "^vt-tiles: wrote 'tiff_stdin.vts'" err.txt
ls -A . tmp
