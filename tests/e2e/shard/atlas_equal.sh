# vt-tiles --layout --shard I/N then vt-merge gives the single atlas build byte for byte
# (docs/sharding.md, "Atlas shards"): the sample scene's three layers (diffuse with alpha, normal,
# alpha mask), an atlas whose repeating textures wrap (--wrap split) and one that copies them
# (--wrap replicate), 1 to 16 shards, shards at -j1 and -j2, the merge at -j1 and -j2.
set -euo pipefail
"$VT_SAMPLE_SCENE" --shrink 4 -q scene
"$VT_ATLAS" scene/scene.obj -o wrap.json --tile-size 64 --border 2 --wrap split -q
"$VT_ATLAS" scene/scene.obj -o clamp.json --tile-size 64 --border 2 --wrap replicate -q
for a in wrap clamp; do
  "$VT_TILES" --layout $a.json -o $a.vts -j2 -q
  for n in 1 2 4 16; do
    for i in $(seq 1 $n); do
      "$VT_TILES" --layout $a.json -o $a-$i-of-$n.shard --shard $i/$n -j$(( i % 2 + 1 )) -q
    done
    "$VT_MERGE" $(ls $a-*-of-$n.shard | sort -r) -o $a-$n.vts -j$(( n % 3 == 1 ? 1 : 2 )) -q
    cmp $a.vts $a-$n.vts && echo "ok $a atlas: $n shards merged equal the single build"
  done
done
"$VT_INFO" wrap.vts | grep -E '^(levels|layer)'
# the comparison can fail: a build that differs in one option is told apart
"$VT_TILES" --layout wrap.json -o other.vts --quality 80 -j2 -q
cmp -s wrap.vts other.vts || echo "ok a different build differs"
# a shard decodes only the textures its part needs (and those with an alpha channel: whether
# they are opaque decides the layer's format): fewer than the single build's
"$VT_TILES" --layout wrap.json -o x.vts -j2 -v 2>&1 | grep -oE '[0-9]+ texture decodes'
for i in 1 2 3 16; do
  "$VT_TILES" --layout wrap.json -o x.vts --shard $i/16 -j2 -v 2>&1 |
    grep -oE '(shard .* carried|[0-9]+ texture decodes)' | paste -sd' '
done
