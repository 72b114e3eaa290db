# Bad input: one line naming the file, exit 1; bad usage: the reason and exit 2.
set -uo pipefail
"$VT_SYNTH_IMAGE" small.png --format png --size 100x100 --channels 3 --photo
"$VT_SYNTH_IMAGE" deep.png --format png --size 300x300 --channels 3 --sample u16
"$VT_WANG" small.png -o p.vts --tile 128; echo "exit $?"
"$VT_WANG" deep.png -o p.vts --tile 64; echo "exit $?"
"$VT_WANG" missing.png -o p.vts; echo "exit $?"
"$VT_WANG" small.png -o p.vts --tile 33; echo "exit $?"
"$VT_WANG" small.png -o p.vts --colours 2x17; echo "exit $?"
"$VT_WANG" small.png -o p.vts --corners --colours 2x3; echo "exit $?"
"$VT_WANG" small.png -o p.vts --colours 16x16; echo "exit $?"
"$VT_WANG" small.png; echo "exit $?"
"$VT_WANG" small.png -o small.png; echo "exit $?"
test ! -e p.vts && echo "no pack written"
"$VT_INFO" --extract 0 --wang-region 0,0,10,10 -o r.png small.png; echo "exit $?"
"$VT_SYNTH_IMAGE" ok.png --format png --size 64x64 --channels 3 --photo
"$VT_WANG" ok.png -o ok.vts --tile 32 -q
"$VT_INFO" --extract 0 --wang-region 0,0,0,10 -o r.png ok.vts; echo "exit $?"
"$VT_INFO" --extract 9 --wang-region 0,0,10,10 -o r.png ok.vts; echo "exit $?"
