# STORE - reads the store from standard input (copied to a temporary file in $TMPDIR, removed
# at the end): the summary, --json, --verify and --extract give what the file gives, the store
# named '<stdin>'; a pipe works as well as a redirected file.
set -euo pipefail
mkdir tmp
export TMPDIR=$PWD/tmp
"$VT_SYNTH" s.vts --codec png --empty --flat
"$VT_INFO" - <s.vts >from_stdin.txt
"$VT_INFO" s.vts >from_file.txt
head -n 1 from_stdin.txt
diff <(tail -n +2 from_file.txt) <(tail -n +2 from_stdin.txt) && echo "ok the summary of - is the file's"
cat s.vts | "$VT_INFO" --json - >stdin.json
"$VT_CLI_CHECK" json stdin.json file='"<stdin>"' width=300 height=200 totals.stored=26
"$VT_INFO" --json s.vts | sed 's/"s.vts"/"<stdin>"/' | cmp - stdin.json && echo "ok --json of - is the file's"
"$VT_INFO" -v --verify - <s.vts
"$VT_INFO" --extract 1 -o file.png s.vts
"$VT_INFO" --extract 1 -o stdin.png - <s.vts
cmp file.png stdin.png && echo "ok --extract from - equals the file's"
cat s.vts | "$VT_INFO" --extract 1 -o - - | cmp - file.png && echo "ok - to - through pipes"
ls -A . tmp
