# A rebuilt store keeps the permission bits of the one it replaces (0600 stays 0600), and, as root,
# its owner and group; a new store gets the usual 0666 & ~umask.
set -euo pipefail
umask 022
"$VT_SYNTH_IMAGE" photo.png --format png --size 96x64 --channels 3 --seed 4
"$VT_TILES" photo.png -o new.vts
stat -c 'new.vts: %a' new.vts
"$VT_TILES" photo.png -o secret.vts
chmod 600 secret.vts
chown 1234:5678 secret.vts
"$VT_TILES" photo.png -o secret.vts --codec png
stat -c 'secret.vts: %a %u:%g' secret.vts
"$VT_INFO" --verify secret.vts
