# One flipped payload byte: the summary still opens the store (payloads are not read), --verify
# exits 1 naming the tile. The tile's offset comes from the index.
set -euo pipefail
"$VT_SYNTH" s.vts
read -r offset length < <("$VT_CLI_CHECK" tile-offset s.vts 0 0 2 1)
[ "$length" -eq $((68 * 68 * 4)) ]
pos=$((offset + length / 2))
byte=$(od -An -tu1 -j "$pos" -N1 s.vts | tr -d ' ')
printf "\\$(printf '%03o' $((byte ^ 255)))" | dd of=s.vts bs=1 seek="$pos" conv=notrunc status=none
"$VT_INFO" s.vts >/dev/null
echo "summary: exit 0"
"$VT_INFO" --verify s.vts
