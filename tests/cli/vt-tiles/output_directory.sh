# An output that is an existing directory (or a link to one) is refused before any work: exit 1,
# one line; the directory stays empty and no temporary or pass file is left anywhere.
set -euo pipefail
"$VT_SYNTH_IMAGE" photo.png --format png --size 96x64 --channels 3 --seed 4
mkdir out.vts
ln -s out.vts link.vts
rc=0; "$VT_TILES" photo.png -o link.vts || rc=$?
echo "link to a directory: exit $rc"
ls -A . out.vts
"$VT_TILES" photo.png -o out.vts
