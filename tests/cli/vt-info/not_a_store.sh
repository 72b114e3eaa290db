# A text file is not a store: exit 1, one line naming the file (short and long files).
set -euo pipefail
echo "hello" >short.txt
rc=0; "$VT_INFO" short.txt 2>&1 || rc=$?; echo "exit $rc"
seq 1 2000 >notes.txt
"$VT_INFO" notes.txt
