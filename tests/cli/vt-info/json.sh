# --json: valid JSON on stdout with the documented keys and the same numbers as the summary.
set -euo pipefail
"$VT_SYNTH" s.vts --empty --flat --codec png
"$VT_INFO" --json s.vts >out.json
"$VT_CLI_CHECK" json out.json file='"s.vts"' format_major=1 format_minor=0 width=300 height=200 \
  tile_content_px=64 border_px=2 tile_payload_px=68 level_count=4 layer_count=1 flags='[]' \
  layers.0.name='"diffuse"' layers.0.codec='"png"' layers.0.channels=4 layers.0.sample='"u8"' \
  layers.0.colour='"srgb"' layers.0.levels.0.width=300 layers.0.levels.0.tiles_x=5 \
  layers.0.levels.0.tiles_y=4 layers.0.levels.0.tiles=20 layers.0.levels.0.stored=17 \
  layers.0.levels.0.empty=3 layers.0.levels.0.shared=3 layers.0.levels.3.width=38 \
  layers.0.levels.3.tiles=1 layers.0.totals.tiles=29 layers.0.totals.stored=26 \
  totals.stored=26 totals.empty=3 totals.shared=3 totals.raw_bytes=$((26 * 68 * 68 * 4)) \
  metadata.generator='"vt-synth"' metadata.seed='"1"'
"$VT_INFO" s.vts >out.txt
bytes=$(sed -n 's/^payload bytes: *//p' out.txt)
file_size=$(stat -c %s s.vts)
"$VT_CLI_CHECK" json out.json totals.bytes="$bytes" totals.file_size="$file_size" >/dev/null
cat out.json
