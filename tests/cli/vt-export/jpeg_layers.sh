# JPEG tiles (the default for 8-bit RGB) within 30 dB of the extract; a layer chosen by name;
# u16 layers give 16-bit PNG by default; the same tiles for -j 1 and -j 2.
set -euo pipefail
[ -n "${VT_PYTHON:-}" ] || { echo "skip: no Python 3 with numpy and PIL (scripts/setup)"; exit 77; }
"$VT_SYNTH_IMAGE" img.png --format png --size 600x400 --photo
"$VT_TILES" -q img.png -o s.vts --codec png --tile-size 128 --keep payload --name albedo
"$VT_EXPORT" -q s.vts -o j --layer albedo --quality 95
ls j
"$VT_INFO" --extract 0 -o e0.png s.vts
"$VT_PYTHON" "$VT_EXPORT_CHECK" j --layout dzi --name s --levels 0:e0.png --psnr 30
"$VT_EXPORT" -q s.vts -o j1 -j 1 --quality 95
diff -r j j1 && echo "ok -j 1 and -j 2 give the same files"
"$VT_SYNTH" u16.vts --size 300x200 --tile 64 --channels 1 --sample u16 --codec png
"$VT_EXPORT" -q u16.vts -o w --layout xyz
"$VT_PYTHON" -c '
from PIL import Image
im = Image.open("w/0/0/0.png"); print("u16 tile:", im.mode, im.size)'
