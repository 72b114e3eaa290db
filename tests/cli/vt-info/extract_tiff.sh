# --extract to a .tif writes a TIFF: u16 samples as 16-bit (the same texels as the 16-bit PNG),
# f16 and f32 as 32-bit floats with their values (the PNG clamps them): min, max and mean equal
# those of --stats; a level compared with another level's TIFF differs.
set -euo pipefail
py=/usr/bin/python3
"$VT_SYNTH" u.vts --size 150x100 --tile 64 --border 2 --channels 1 --sample u16 --seed 2
"$VT_INFO" --extract 0 -o u.png u.vts
"$VT_INFO" --extract 0 -o u.tif u.vts
"$VT_INFO" --extract 1 -o u1.tif u.vts
"$VT_SYNTH" h.vts --size 150x100 --tile 64 --border 2 --channels 1 --sample f16 --seed 2 --empty
"$VT_INFO" --extract 0 -o h.TIFF h.vts
"$VT_INFO" --stats h.vts | sed -n 2p
"$py" - <<'PY'
from PIL import Image
import numpy as np
png = np.asarray(Image.open('u.png')).astype(np.int64)
tif = np.asarray(Image.open('u.tif')).astype(np.int64)
print('u16 tif', tif.shape, 'max', tif.max(), 'equal to the png:', bool((png == tif).all()))
level1 = np.asarray(Image.open('u1.tif')).astype(np.int64)
print('level 1 tif', level1.shape, 'equal:', level1.shape == tif.shape and bool((level1 == tif[:level1.shape[0], :level1.shape[1]]).all()))
h = np.asarray(Image.open('h.TIFF'))
print('f16 tif', h.dtype, h.shape, 'min %.9g max %.9g mean %.6f' % (h.min(), h.max(), h.astype(np.float64).mean()))
PY
