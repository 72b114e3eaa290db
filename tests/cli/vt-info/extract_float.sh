# f16 and f32 layers give 16-bit PNGs clamped to [0,1], with a warning (none with -q).
set -euo pipefail
opts="--channels 1 --sample f32"
"$VT_SYNTH" f32.vts $opts
"$VT_INFO" --extract 0 -o f32.png f32.vts
"$VT_CLI_CHECK" png f32.png --level 0 --layer 0 $opts
opts="--channels 3 --sample f16 --empty"
"$VT_SYNTH" f16.vts $opts
"$VT_INFO" -q --extract 0 -o f16.png f16.vts
"$VT_CLI_CHECK" png f16.png --level 0 --layer 0 $opts
"$VT_INFO" --extract 1 --tile 0,1 -o f16t.png f16.vts
"$VT_CLI_CHECK" png f16t.png --level 1 --at 0,1 --layer 0 $opts
