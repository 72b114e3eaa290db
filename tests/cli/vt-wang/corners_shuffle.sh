# Corner tiles: K^4 tiles in K^2 x 2K^2 (even K); a shuffled pack records its order. The
# summary shows both; regions assemble.
set -euo pipefail
"$VT_SYNTH_IMAGE" sample.png --format png --size 200x200 --channels 3 --photo --seed 2
"$VT_WANG" sample.png -o c.vts --tile 32 --corners --colours 2x2 --hash 64 --codec png --store-tile 32 --border 2
"$VT_INFO" c.vts | grep -E '^(size|levels|wang)'
"$VT_WANG" sample.png -o s.vts --tile 32 --colours 2x2 --hash 64 --shuffle 9 --codec png --store-tile 32 --border 2
"$VT_INFO" s.vts | grep -E '^(size|levels|wang|  wang.order)'
"$VT_INFO" --extract 1 --wang-region 5,7,64,64 -o r.png s.vts
echo done
