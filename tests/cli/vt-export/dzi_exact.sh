# Deep Zoom, PNG tiles: every tile of every store level equals the same rectangle of
# vt-info --extract of that level (the checker computes the tile grid itself), the descriptor is
# as Deep Zoom defines it, and the levels coarser than the store's go down to 1x1, reduced from
# the store's coarsest level in linear light. Two tiles of
# the same size swapped, and a level shifted by one texel, fail the same check.
set -euo pipefail
[ -n "${VT_PYTHON:-}" ] || { echo "skip: no Python 3 with numpy and PIL (scripts/setup)"; exit 77; }
"$VT_SYNTH_IMAGE" img.png --format png --size 1000x700 --photo
"$VT_TILES" -q img.png -o s.vts --codec png --tile-size 128 --keep payload
"$VT_EXPORT" -q s.vts -o out --format png -j 2
cat out/s.dzi
ls out/s_files | sort -n | tr '\n' ' '; echo
levels=()
for l in 0 1 2 3 4; do
  "$VT_INFO" --extract $l -o e$l.png s.vts
  levels+=("$l:e$l.png")
done
"$VT_PYTHON" "$VT_EXPORT_CHECK" out --layout dzi --name s --levels "${levels[@]}" --coarse 4:e4.png
rc=0; "$VT_PYTHON" "$VT_EXPORT_CHECK" out --layout dzi --name s --levels 4:e4.png --coarse 4:e3.png || rc=$?
echo "coarse levels from the wrong level: exit $rc"
"$VT_PYTHON" -c 'from PIL import Image; print("level 0:", Image.open("out/s_files/0/0_0.png").size)'
cp -r out swapped
mv swapped/s_files/10/1_1.png t.png
mv swapped/s_files/10/2_1.png swapped/s_files/10/1_1.png
mv t.png swapped/s_files/10/2_1.png
rc=0; "$VT_PYTHON" "$VT_EXPORT_CHECK" swapped --layout dzi --name s --levels 0:e0.png || rc=$?
echo "swapped tiles: exit $rc"
"$VT_PYTHON" -c '
from PIL import Image
im = Image.open("e1.png"); im.crop((1, 0, im.width, im.height)).save("shifted.png")'
rc=0; "$VT_PYTHON" "$VT_EXPORT_CHECK" out --layout dzi --name s --levels 1:shifted.png || rc=$?
echo "shifted level: exit $rc"
