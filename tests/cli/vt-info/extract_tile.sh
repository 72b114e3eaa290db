# --extract LEVEL --tile X,Y writes that tile's whole payload, border included (68x68 for 64 px
# tiles with border 2); edge tiles hold the clamped texels the generator wrote.
set -euo pipefail
opts="--size 300x200 --tile 64 --border 2"
"$VT_SYNTH" s.vts $opts
for args in "0 1,1" "0 0,0" "0 4,3" "2 1,0" "3 0,0"; do
  set -- $args
  "$VT_INFO" --extract "$1" --tile "$2" -o t.png s.vts
  "$VT_CLI_CHECK" png t.png --level "$1" --at "$2" --layer 0 $opts
done
# the second layer of a two-layer PNG store
"$VT_SYNTH" two.vts $opts --layers 2 --codec png
"$VT_INFO" --extract 0 --tile 2,1 --layer 1 -o t1.png two.vts
"$VT_CLI_CHECK" png t1.png --level 0 --at 2,1 --layer 1 $opts --layers 2
"$VT_INFO" --extract 1 --layer 1 -o l1.png two.vts
"$VT_CLI_CHECK" png l1.png --level 1 --layer 1 $opts --layers 2
