# Empty tiles are written as zeros: transparent black with alpha, black without. Extracting an
# empty tile alone warns.
set -euo pipefail
for channels in 4 3; do
  opts="--empty --channels $channels"
  "$VT_SYNTH" s$channels.vts $opts
  "$VT_INFO" --extract 0 -o l$channels.png s$channels.vts
  "$VT_CLI_CHECK" png l$channels.png --level 0 --layer 0 $opts
done
"$VT_INFO" --extract 0 --tile 1,1 -o t.png s4.vts
"$VT_CLI_CHECK" png t.png --level 0 --at 1,1 --layer 0 --empty
"$VT_INFO" --extract 0 --tile 3,0 -o e.png s4.vts
"$VT_CLI_CHECK" png e.png --level 0 --at 3,0 --layer 0 --empty
