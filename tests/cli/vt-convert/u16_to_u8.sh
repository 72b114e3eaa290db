# u16 layers become u8 for jpeg, bc1 and bc3, rounded, with one warning per layer; png keeps u16.
set -euo pipefail
"$VT_SYNTH" s.vts --sample u16 --channels 3 --codec png --layers 2
"$VT_CONVERT" s.vts -o j.vts --codec jpeg --quality 100 --subsampling 444
"$VT_STORE_CHECK" same-tiles s.vts 1 j.vts 1 --psnr 40
"$VT_INFO" j.vts | grep -E '^layer '
"$VT_CONVERT" s.vts -o p.vts --codec png
"$VT_STORE_CHECK" same-tiles s.vts 1 p.vts 1
"$VT_CONVERT" s.vts -o b.vts --codec bc1 --layer 0
"$VT_INFO" b.vts | grep -E '^layer '
