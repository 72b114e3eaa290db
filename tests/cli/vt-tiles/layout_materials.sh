# vt-tiles --layout copies atlas.json's materials (layers, constants, alpha mode of each) into the
# store's metadata under the key "materials", as compact JSON a renderer can read without the
# layout (the scene of tests/cli/vt-atlas/materials.inc).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/../vt-atlas/materials.inc"
materials_scene
"$VT_ATLAS" -q m.obj -o atlas.json
"$VT_TILES" -q --layout atlas.json -o m.vts --codec png
"$VT_INFO" --json m.vts >info.json
/usr/bin/python3 - <<'PY'
import json
info = json.load(open('info.json'))
meta = info['metadata']
mats = json.loads(meta['materials'])
layout = json.load(open('atlas.json'))['materials']
print('materials in the store:', len(mats), 'in atlas.json:', len(layout))
print('equal to atlas.json:', mats == layout)
for m in mats:
    print(m['name'], m['alpha'], ','.join(m['layers']) or '-')
PY
