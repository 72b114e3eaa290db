# No STORE argument: exit 2.
set -euo pipefail
"$VT_INFO"
