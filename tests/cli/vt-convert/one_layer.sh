# --layer 1 converts layer 1 only: layers 0 and 2 keep their payload bytes, layer 1 holds jpeg
# tiles of the same texels (PSNR), the metadata names the layer.
set -euo pipefail
"$VT_SYNTH" s.vts --layers 3 --channels 3 --codec png --empty
"$VT_CONVERT" s.vts -o o.vts --codec jpeg --quality 95 --subsampling 444 --layer 1
"$VT_STORE_CHECK" same-bytes s.vts 0 o.vts 0
"$VT_STORE_CHECK" same-bytes s.vts 2 o.vts 2
"$VT_STORE_CHECK" same-tiles s.vts 1 o.vts 1 --psnr 30
"$VT_STORE_CHECK" structure s.vts o.vts
"$VT_INFO" --verify o.vts
"$VT_INFO" o.vts | grep -E '^layer |^  [a-z][a-z0-9.]*='
