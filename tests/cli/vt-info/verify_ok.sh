# --verify on good stores: exit 0, silent by default, "verified N tiles" with -v (stored tiles
# only: 26 with 3 empty), nothing with -q.
set -euo pipefail
"$VT_SYNTH" raw.vts --empty
"$VT_SYNTH" png.vts --codec png --flat --layers 2
"$VT_SYNTH" f16.vts --sample f16 --channels 3 --codec raw
"$VT_INFO" --verify raw.vts
"$VT_INFO" -q --verify raw.vts
"$VT_INFO" -v --verify raw.vts
"$VT_INFO" -v --verify png.vts
"$VT_INFO" --verbose --verify f16.vts
