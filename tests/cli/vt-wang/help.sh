# -h and --help print the same help on stdout and exit 0.
set -euo pipefail
"$VT_WANG" -h >short.txt
cmp short.txt - < <("$VT_WANG" --help)
"$VT_WANG" --help
