# --textures LIST: one entry per line (blank lines and # comments skipped), paths relative to
# the list; a missing one names the list's line with --missing fail, or is left out with a warning (the default).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/scene.inc"
tex t/a.png 512x300 1
tex t/b.png 40x20 2
printf 'a.png\n\n# comment\nb.png\n' > t/list.txt
"$VT_ATLAS" --textures t/list.txt -o atlas.json
"$VT_ATLAS_DUMP" atlas.json
printf 'a.png\nnope.png\n' > t/bad.txt
"$VT_ATLAS" --textures t/bad.txt -o bad.json --missing fail || echo "exit $?"
ls
"$VT_ATLAS" --textures t/bad.txt -o skip.json # the default: warn, no entry
"$VT_ATLAS_DUMP" skip.json | grep entry
