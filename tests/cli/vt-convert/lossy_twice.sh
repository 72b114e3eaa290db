# Re-encoding lossy tiles with a lossy codec warns once (not once per layer); lossless to lossy
# and lossy to lossless do not warn.
set -euo pipefail
"$VT_SYNTH" s.vts --channels 3 --codec png --layers 2
"$VT_CONVERT" s.vts -o j.vts --codec jpeg
"$VT_CONVERT" j.vts -o b.vts --codec bc1 --mode best
"$VT_CONVERT" b.vts -o j2.vts --codec jpeg --quality 75
"$VT_CONVERT" -q j2.vts -o j3.vts --codec jpeg
"$VT_CONVERT" j2.vts -o p.vts --codec png
"$VT_INFO" j2.vts | grep -E '^  convert'
