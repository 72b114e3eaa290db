# --version names the tool, the project version and the .vts format version.
set -euo pipefail
"$VT_CONVERT" --version
