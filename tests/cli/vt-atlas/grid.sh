# --grid 2x3: six 200x100 pieces edge to edge, row-major from the top left, one group; pieces of
# another size are refused.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/scene.inc"
for i in 1 2 3 4 5 6; do tex t/p$i.png 200x100 $i; done
tex t/big.png 256x256 7
"$VT_ATLAS" --grid 2x3 t/p1.png t/p2.png t/p3.png t/p4.png t/p5.png t/p6.png -o g.json
"$VT_ATLAS_DUMP" g.json | grep -v '^  '
"$VT_ATLAS" --grid 2x2 t/p1.png t/p2.png t/p3.png t/big.png -o h.json || echo "exit $?"
"$VT_ATLAS" --grid 2x2 t/p1.png t/p2.png t/p3.png -o h.json || echo "exit $?"
ls
