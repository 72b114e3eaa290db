# --help on stdout, exit 0; --version.
set -euo pipefail
"$VT_OFFSET" --help
"$VT_OFFSET" --version | head -1 | sed 's/ [0-9][0-9.]*$/ VERSION/'
