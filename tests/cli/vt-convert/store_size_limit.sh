# --max-store-size: a limit the output would pass fails with exit 1 and one line naming the
# output, leaving nothing; a limit it fits in works; a bad size is a usage error.
set -euo pipefail
"$VT_SYNTH" s.vts --size 1000x1000 --tile 256 --channels 3 --codec raw >/dev/null
"$VT_CONVERT" s.vts -o fits.vts --codec png -j 1 --max-store-size 64M
echo "fits: $(test -s fits.vts && echo written)"
rc=0; "$VT_CONVERT" s.vts -o o.vts --codec png -j 1 --max-store-size 1x 2>/dev/null || rc=$?
echo "bad size: exit $rc"
rc=0; "$VT_CONVERT" s.vts -o o.vts --codec png -j 1 --max-store-size 100K || rc=$?
echo "too small: exit $rc"
[ ! -e o.vts ] || { echo "o.vts written"; exit 3; }
ls -A | sort
