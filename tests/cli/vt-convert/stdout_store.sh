# -o - writes the converted store to standard output (spooled in $TMPDIR, then copied): the same
# bytes as -o FILE, into a file or a pipe, for every -j; no file named '-' appears, no spool is
# left and nothing else is on stdout.
set -euo pipefail
mkdir tmp
export TMPDIR=$PWD/tmp
"$VT_SYNTH" in.vts --layers 2 --empty --flat
"$VT_CONVERT" in.vts -o file.vts --codec png
"$VT_CONVERT" in.vts -o - --codec png >dash.vts
cmp file.vts dash.vts && echo "ok -o - equals -o FILE"
"$VT_CONVERT" -v in.vts --output - --codec png -j 3 | cat >piped.vts
cmp file.vts piped.vts && echo "ok -o - through a pipe equals -o FILE (-j 3)"
"$VT_INFO" --verify piped.vts
ls -A . tmp
