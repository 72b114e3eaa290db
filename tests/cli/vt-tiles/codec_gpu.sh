# --codec gpu: GPU blocks chosen per layer (formats/codec/vt_tile_sink.c): bc4 for one channel,
# bc5 for a normal map (3 channels kept: z rebuilt on decoding) and for grey + alpha, bc3 for
# kept alpha, bc1 otherwise; --codec bc4 on RGB says what to use instead (exit 1).
set -euo pipefail
"$VT_SYNTH_IMAGE" grey.png --format png --size 96x64 --channels 1 --seed 1
"$VT_SYNTH_IMAGE" rgb.png --format png --size 96x64 --channels 3 --seed 2
"$VT_SYNTH_IMAGE" ga.png --format png --size 96x64 --channels 2 --alpha smooth --seed 3
"$VT_SYNTH_IMAGE" rgba.png --format png --size 96x64 --channels 4 --alpha smooth --seed 4
for run in "grey.png --colour data" "rgb.png --colour normal" "ga.png" "rgba.png" "rgb.png"; do
  set -- $run
  "$VT_TILES" "$@" -o out.vts --codec gpu --tile-size 32 --mode best
  echo "$run: $("$VT_INFO" out.vts | grep '^layer 0')"
  "$VT_INFO" --verify out.vts >/dev/null && echo "  verified"
done
"$VT_TILES" rgb.png -o bad.vts --codec bc4
