# A store that is not a Wang pack: vt-view --wang and vt-info --wang-region exit 1 naming it,
# before any rendering; usage errors of --wang exit 2.
set -uo pipefail
"$VT_SYNTH_IMAGE" in.png --format png --size 64x64 --channels 3
"$VT_TILES" in.png -o plain.vts -q
"$VT_VIEW" --wang plain.vts --headless; echo "exit $?"
"$VT_INFO" --extract 0 --wang-region 0,0,8,8 -o r.png plain.vts; echo "exit $?"
"$VT_VIEW" --wang missing.vts --headless; echo "exit $?"
"$VT_VIEW" --extent 4x4 plain.vts --headless; echo "exit $?"
"$VT_VIEW" --wang plain.vts plain.vts --headless; echo "exit $?"
"$VT_VIEW" --wang plain.vts --extent 0x4 --headless; echo "exit $?"
"$VT_VIEW" --wang plain.vts --orbit 3 --headless; echo "exit $?"
"$VT_VIEW" --wang plain.vts --headless --screenshot plain.vts; echo "exit $?"
"$VT_VIEW" --wang plain.vts --tilemap --reference --headless; echo "exit $?"
