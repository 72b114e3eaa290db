# -h and --help print the same help on stdout and exit 0.
set -euo pipefail
"$VT_CONVERT" -h >short.txt
cmp short.txt - < <("$VT_CONVERT" --help)
"$VT_CONVERT" --help
