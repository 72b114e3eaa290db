# -h and --help print the same help on stdout and exit 0.
set -euo pipefail
"$VT_EXPORT" -h >short.txt
cmp short.txt - < <("$VT_EXPORT" --help)
"$VT_EXPORT" --help
