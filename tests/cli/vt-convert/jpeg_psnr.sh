# JPEG on smooth content (a generated gradient image tiled by vt-tiles as png): PSNR against the
# png tiles >= 40 dB at quality 90 (4:2:0 and 4:4:4), >= 30 dB at quality 50.
set -euo pipefail
"$VT_STORE_CHECK" smooth-png smooth.png 512 384
"$VT_TILES" -q smooth.png -o s.vts --codec png --tile-size 128
"$VT_CONVERT" s.vts -o j420.vts --codec jpeg --quality 90
"$VT_STORE_CHECK" same-tiles s.vts 0 j420.vts 0 --psnr 40
"$VT_CONVERT" s.vts -o j444.vts --codec jpeg --quality 90 --subsampling 444
"$VT_STORE_CHECK" same-tiles s.vts 0 j444.vts 0 --psnr 40
"$VT_CONVERT" s.vts -o j50.vts --codec jpeg --quality 50
"$VT_STORE_CHECK" same-tiles s.vts 0 j50.vts 0 --psnr 30
"$VT_STORE_CHECK" structure s.vts j50.vts
"$VT_INFO" j444.vts | grep -E '^layer |^  convert'
