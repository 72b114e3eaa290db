# Standard input and output refused or failing cleanly: an empty or non-store stdin names
# '<stdin>' (exit 1); -o - when standard output is the store, or -o the store when standard input
# is (compared by device and inode, before anything is read), is refused (exit 1) and the store
# stays intact; -o - without --extract is a usage error (exit 2).
set -euo pipefail
"$VT_SYNTH" s.vts
cp s.vts keep.vts
rc=0; "$VT_INFO" - </dev/null || rc=$?; echo "empty stdin: exit $rc"
rc=0; echo "not a store" | "$VT_INFO" --json - || rc=$?; echo "junk stdin: exit $rc"
rc=0; head -c 1000 s.vts | "$VT_INFO" --verify - || rc=$?; echo "truncated stdin: exit $rc"
rc=0; "$VT_INFO" --extract 0 -o - s.vts 1<>s.vts || rc=$?; echo "stdout is the store: exit $rc"
cmp s.vts keep.vts
rc=0; "$VT_INFO" --extract 0 -o s.vts - <s.vts || rc=$?; echo "-o the store read from stdin: exit $rc"
cmp s.vts keep.vts
rc=0; "$VT_INFO" --extract 0 -o ./- - <s.vts || rc=$?; echo "-o ./- (a file named -): exit $rc"
rm ./-
rc=0; "$VT_INFO" -o - s.vts || rc=$?; echo "-o - without --extract: exit $rc"
ls -A
exit $rc
