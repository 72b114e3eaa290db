# --layout: the store or the exported image may not be the layout or a texture it names, nor the
# export the store: refused once the layout is read, before any texture is decoded (exit 1, one
# line naming both); every input untouched, nothing written.
set -euo pipefail
"$VT_SYNTH_IMAGE" a.png --format png --size 64x64 --channels 3 --seed 1
mkdir tex
"$VT_SYNTH_IMAGE" tex/b.png --format png --size 64x32 --channels 3 --seed 2
printf 'a.png\ntex/b.png\n' >list.txt
"$VT_ATLAS" -q --textures list.txt -o atlas.json
cp tex/b.png keep.png
cp atlas.json keep.json
ln -s tex/b.png link.png
for args in "-o link.png" "-o atlas.json" "-o s.vts --export-atlas s.vts" \
            "-o s.vts --export-atlas tex/b.png"; do
  rc=0; "$VT_TILES" --layout atlas.json $args || rc=$?
  echo "vt-tiles --layout atlas.json $args: exit $rc"
  cmp tex/b.png keep.png && cmp atlas.json keep.json
done
ls -A . tex
"$VT_TILES" --layout atlas.json --export-atlas a.png
