# --extract -o - writes the PNG to standard output: the same bytes as -o FILE (a level, a tile,
# into a file and through a pipe); no file named '-' appears and nothing else is on stdout.
set -euo pipefail
"$VT_SYNTH" s.vts --codec png --empty
"$VT_INFO" --extract 1 -o level.png s.vts
"$VT_INFO" --extract 1 -o - s.vts >dash.png
cmp level.png dash.png && echo "ok level 1 through - equals the file"
"$VT_INFO" --extract 0 --tile 2,1 -o tile.png s.vts
"$VT_INFO" --extract 0 --tile 2,1 --output - s.vts | cat >piped.png
cmp tile.png piped.png && echo "ok tile 2,1 through a pipe equals the file"
"$VT_INFO" -v --extract 2 -o - s.vts >l2.png
"$VT_CLI_CHECK" png l2.png --level 2 --layer 0 --codec png --empty
ls -A
