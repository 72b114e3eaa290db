# IIIF level 0 and XYZ, PNG tiles, another tile size than the store's: tiles equal the extracts;
# info.json as the Image API 3.0 writes it; XYZ tiles padded with zeros to the full edge. A tile
# of the wrong size fails the check.
set -euo pipefail
[ -n "${VT_PYTHON:-}" ] || { echo "skip: no Python 3 with numpy and PIL (scripts/setup)"; exit 77; }
"$VT_SYNTH_IMAGE" img.png --format png --size 1000x700 --photo
"$VT_TILES" -q img.png -o s.vts --codec png --tile-size 128 --keep payload
levels=()
for l in 0 1 2 3 4; do
  "$VT_INFO" --extract $l -o e$l.png s.vts
  levels+=("$l:e$l.png")
done
"$VT_EXPORT" -q s.vts -o iiif --layout iiif --format png --iiif-id https://example.org/iiif/s
cat iiif/info.json
"$VT_PYTHON" "$VT_EXPORT_CHECK" iiif --layout iiif --levels "${levels[@]}"
"$VT_EXPORT" -q s.vts -o xyz --layout xyz --format png --tile-size 100 -j 1
ls xyz | tr '\n' ' '; echo
"$VT_PYTHON" "$VT_EXPORT_CHECK" xyz --layout xyz --xyz 1000,700,100,png --levels "${levels[@]}"
cp xyz/4/0/0.png xyz/3/1/0.png
rc=0; "$VT_PYTHON" "$VT_EXPORT_CHECK" xyz --layout xyz --xyz 1000,700,100,png --levels 1:e1.png || rc=$?
echo "wrong tile: exit $rc"
