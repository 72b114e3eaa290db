# -o IN itself is allowed (documented; scripts/vt.mk converts layer after layer in place): IN is
# read through the open store and replaced only by the complete conversion, which keeps IN's mode.
# -o a hard link to IN converts into a new file and leaves IN as it was. An existing directory
# as output is refused before any work: exit 1, one line.
set -euo pipefail
"$VT_SYNTH" in.vts
cp in.vts keep.vts
chmod 600 in.vts
ln in.vts hard.vts
"$VT_CONVERT" in.vts -o hard.vts --codec png
cmp in.vts keep.vts && echo "ok IN unchanged by -o a hard link to it"
"$VT_STORE_CHECK" same-tiles keep.vts 0 hard.vts 0
"$VT_CONVERT" in.vts -o in.vts --codec png
cmp -s in.vts keep.vts || echo "ok IN converted in place"
stat -c 'in.vts: %a' in.vts
"$VT_INFO" --verify in.vts
"$VT_STORE_CHECK" same-tiles keep.vts 0 in.vts 0
mkdir out.vts
ls -A
"$VT_CONVERT" in.vts -o out.vts --codec png
