# Standard input and output refused or failing cleanly: an empty, non-image or truncated stdin
# names '<stdin>' (exit 1, nothing written); `- -o X <X` (device and inode of stdin against the
# output, before it is read) and -o - when stdout is the input are refused with the input intact
# (exit 1), as is -o - when stdout is the --export-atlas file; --shard and --layout cannot read
# stdin, nor --export-atlas write stdout (exit 2).
set -euo pipefail
"$VT_SYNTH_IMAGE" photo.png --format png --size 96x64 --channels 3 --seed 4
"$VT_TILES" photo.png -o s.vts --codec png
cp s.vts keep.vts
cp photo.png keep.png
rc=0; "$VT_TILES" - -o out.vts </dev/null || rc=$?; echo "empty stdin: exit $rc"
rc=0; echo "not an image" | "$VT_TILES" - -o out.vts || rc=$?; echo "junk stdin: exit $rc"
rc=0; head -c 300 photo.png | "$VT_TILES" - -o out.vts || rc=$?; echo "truncated stdin: exit $rc"
rc=0; "$VT_TILES" - -o s.vts <s.vts || rc=$?; echo "stdin is the output: exit $rc"
cmp s.vts keep.vts
rc=0; "$VT_TILES" photo.png -o - 1<>photo.png || rc=$?; echo "stdout is the input: exit $rc"
cmp photo.png keep.png
rc=0; "$VT_TILES" - -o - <photo.png 1<>photo.png || rc=$?; echo "stdout is stdin: exit $rc"
cmp photo.png keep.png
rc=0; "$VT_TILES" - -o out.vts --shard 1/2 <photo.png || rc=$?; echo "--shard from stdin: exit $rc"
rc=0; "$VT_TILES" --layout - -o out.vts || rc=$?; echo "--layout -: exit $rc"
printf 'photo.png\n' >list.txt
"$VT_ATLAS" -q --textures list.txt -o atlas.json
touch export.png
rc=0; "$VT_TILES" --layout atlas.json -o - --export-atlas export.png 1<>export.png || rc=$?
echo "stdout is the export: exit $rc"
rc=0; "$VT_TILES" --layout atlas.json --export-atlas - || rc=$?; echo "--export-atlas -: exit $rc"
ls -A
exit $rc
