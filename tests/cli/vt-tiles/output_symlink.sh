# An output that is a symbolic link is written through: the link stays a link, its target (in
# another folder, or not there yet) gets the store, the temporary was made next to the target.
set -euo pipefail
"$VT_SYNTH_IMAGE" photo.png --format png --size 96x64 --channels 3 --seed 4
"$VT_TILES" photo.png -o ref.vts
mkdir sub
echo "old" >sub/store.vts
ln -s sub/store.vts link.vts
ln -s sub/new.vts dangling.vts
"$VT_TILES" photo.png -o link.vts
"$VT_TILES" photo.png -o dangling.vts
for f in link.vts dangling.vts; do
  [ -L "$f" ] && echo "ok $f is still a link to $(readlink "$f")"
done
cmp ref.vts sub/store.vts && echo "ok the target holds the store"
cmp ref.vts sub/new.vts && echo "ok the dangling link's target was created"
ls -A . sub
