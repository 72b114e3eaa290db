# A store that does not exist: exit 1, one line naming the file.
set -euo pipefail
"$VT_INFO" missing.vts
