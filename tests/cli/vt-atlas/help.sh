# --help prints the usage on stdout and exits 0.
set -euo pipefail
"$VT_ATLAS" --help
