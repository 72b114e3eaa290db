# Resource limits and usage errors: clear messages, exit 1 (limits) or 2 (usage), no output.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/scene.inc"
scene
"$VT_ATLAS" scene.obj -o a.json --max-textures 2 || echo "exit $?"
"$VT_ATLAS" scene.obj -o a.json --max-pixels 10000 || echo "exit $?"
"$VT_ATLAS" scene.obj -o a.json --max-line-bytes 16 || echo "exit $?"
"$VT_ATLAS" scene.obj -o a.json --max-size 256 || echo "exit $?"
"$VT_ATLAS" scene.obj -o a.json --tile-size 100 || echo "exit $?"
"$VT_ATLAS" scene.obj || echo "exit $?"
"$VT_ATLAS" --textures x.txt scene.obj -o a.json || echo "exit $?"
"$VT_ATLAS" scene.obj -o a.json --wrap mirror || echo "exit $?"
ls
