# A categorical store (vt-tiles --colour index: mode) exports as PNG by default, and the levels
# coarser than the store's are reduced by the store's selection: every texel of every tile is one
# of the input's classes. The same map built with --colour data (box) fails that check (its
# coarse levels mix classes), which shows the check can fail.
set -euo pipefail
[ -n "${VT_PYTHON:-}" ] || { echo "skip: no Python 3 with numpy and PIL (scripts/setup)"; exit 77; }
"$VT_PYTHON" - <<'PY'
import numpy as np
from PIL import Image
rng = np.random.default_rng(5)
classes = np.array([3, 7, 12, 200], dtype=np.uint8)
cells = rng.integers(0, 3, size=(500 // 9 + 1, 700 // 11 + 1))
m = classes[cells.repeat(9, axis=0).repeat(11, axis=1)[:500, :700]]
m[:, 17::41] = 200  # 1-texel roads
Image.fromarray(m, "L").save("classes.png")
PY
check() {  # DIR: every tile's values within the classes
  "$VT_PYTHON" - "$1" <<'PY'
import glob, sys
import numpy as np
from PIL import Image
tiles = sorted(glob.glob(sys.argv[1] + "/*_files/*/*"))
bad = [t for t in tiles if not set(np.unique(np.asarray(Image.open(t)))) <= {3, 7, 12, 200}]
print(len(tiles), "tiles,", "all png" if all(t.endswith(".png") for t in tiles) else "not all png",
      ",", len(bad), "with values outside the classes")
sys.exit(1 if bad else 0)
PY
}
"$VT_TILES" -q classes.png -o index.vts --colour index --tile-size 64
"$VT_EXPORT" -q index.vts -o out -j 2
ls out/index_files | sort -n | tr '\n' ' '; echo
check out
"$VT_TILES" -q classes.png -o box.vts --colour data --tile-size 64 --codec png
"$VT_EXPORT" -q box.vts -o box --format png
rc=0; check box || rc=$?
echo "box store: exit $rc"
