# -h and --help print the same help on stdout and exit 0.
set -euo pipefail
"$VT_MERGE" -h >short.txt
cmp short.txt - < <("$VT_MERGE" --help)
"$VT_MERGE" --help
