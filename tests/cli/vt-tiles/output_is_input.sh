# An output that is the input (by name, through a hard link, a symbolic link to the input, or the
# input named through a link) is refused before any work: exit 1, one line naming both, the input
# untouched, nothing else written.
set -euo pipefail
"$VT_SYNTH_IMAGE" photo.png --format png --size 96x64 --channels 3 --seed 4
cp photo.png keep.png
ln photo.png hard.png
ln -s photo.png soft.png
for args in "photo.png -o photo.png" "photo.png -o hard.png" "photo.png -o soft.png" \
            "soft.png -o photo.png"; do
  rc=0; "$VT_TILES" $args || rc=$?
  echo "vt-tiles $args: exit $rc"
  cmp photo.png keep.png
done
ls -A
"$VT_TILES" photo.png -o photo.png
