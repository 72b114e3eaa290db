# -h and --help print the same help on stdout and exit 0.
set -euo pipefail
"$VT_INFO" -h >short.txt
cmp short.txt - < <("$VT_INFO" --help)
"$VT_INFO" --help
