#!/usr/bin/env bash
# vt-view --wang (tests/e2e/view/CMakeLists.txt): packs built by vt-wang from a generated
# photo-like sample, rendered headless (EGL surfaceless, llvmpipe) with TileTex and with
# --reference (the output assembled on the CPU by lib/wang through libvts's vts_wang API).
# usage: run_wang_test.sh CASE VT_VIEW VT_WANG VT_SYNTH_IMAGE VTV_WANG_CHECK VTV_CHECK WORKDIR
set -euo pipefail
case_name=$1 view=$2 wang=$3 synth=$4 check=$5 vcheck=$6 work=$7
rm -rf "$work"
mkdir -p "$work"
cd "$work"
export MESA_SHADER_CACHE_DISABLE=true EGL_LOG_LEVEL=fatal
fail() { echo "FAIL: $*" >&2; exit 1; }
vt() { "$view" --headless --size 256x256 "$@"; }
# edge_db A B TILES: the PSNR at tile edges (within 2 pixels)
edge_db() { "$check" edges "$1" "$2" "$3" 2 | tee /dev/stderr | awk '{print $2}'; }
"$synth" sample.png --format png --size 384x384 --channels 3 --photo --seed 7
pack() { "$wang" sample.png --tile 64 --hash 64 --codec png --store-tile 64 --border 2 "$@"; }

case "$case_name" in
wang_filtering)
  # Wei's figure 5: with the TileIndex packing, hardware bilinear + mipmap filtering across tile
  # edges matches the CPU-assembled reference (>= 40 dB at the edges); tiles in an arbitrary
  # order give wrong neighbours at every edge (>= 5 dB lower). Extents off the texel grid:
  # magnified (3 tiles: level 0 between texels), minified (6 and 11 tiles: levels 0-2). Edge
  # tiles differ near tile corners (four diamonds meet there); corner tiles filter exactly.
  for kind in edge corner; do
    opts=""
    if [ $kind = corner ]; then opts="--corners --colours 2x2"; fi
    pack -o good.vts $opts
    pack -o shuffled.vts --shuffle 5 $opts
    for extent in 3 6 11; do
      vt --wang good.vts --extent ${extent}x$extent --screenshot good$extent.png
      vt --wang shuffled.vts --extent ${extent}x$extent --screenshot shuffled$extent.png
      vt --wang good.vts --extent ${extent}x$extent --reference --screenshot ref$extent.png
      vt --wang shuffled.vts --extent ${extent}x$extent --reference --screenshot refs$extent.png
      cmp ref$extent.png refs$extent.png || fail "the references of the two packs differ"
      g=$(edge_db good$extent.png ref$extent.png $extent)
      s=$(edge_db shuffled$extent.png ref$extent.png $extent)
      echo "$kind tiles, extent $extent: TileIndex $g dB, shuffled $s dB at tile edges"
      awk -v g="$g" -v s="$s" 'BEGIN { exit !(g >= 40 && s <= g - 5) }' ||
        fail "extent $extent: $g dB (want >= 40), shuffled $s dB (want <= $g - 5)"
    done
  done
  ;;
wang_hash_agrees)
  # TileTex's GLSL hash and TileIndex against the C API: at scales where every pixel samples one
  # texel centre (1:1 on level 0, 4:1 on level 2), the render is the reference exactly, for
  # edge packs of 2x2 and 3x2 colours over 4096 tiles and a corner pack. A different tile choice
  # is caught: the same tiles with another hash permutation (--hash 63) score far lower.
  for colours in 2x2 3x2; do
    "$wang" sample.png -o p$colours.vts --tile 16 --colours $colours --hash 64 --codec png \
      --store-tile 32 --border 2
    vt --wang p$colours.vts --extent 64x64 --screenshot t.png
    vt --wang p$colours.vts --extent 64x64 --reference --screenshot r.png
    "$vcheck" psnr t.png r.png --min 99
    vt --wang p$colours.vts --extent 16x16 --screenshot t.png
    vt --wang p$colours.vts --extent 16x16 --reference --screenshot r.png
    "$vcheck" psnr t.png r.png --min 99
    # 2 texels per tile: level 3, past the store's levels (64, 32, 16 texels): made by vt-view
    # from the coarsest stored level (one rounding to 8 bits more than the reference's chain)
    vt --wang p$colours.vts --extent 128x128 --screenshot t.png
    vt --wang p$colours.vts --extent 128x128 --reference --screenshot r.png
    "$vcheck" psnr t.png r.png --min 45
  done
  "$wang" sample.png -o other.vts --tile 16 --colours 3x2 --hash 63 --codec png \
    --store-tile 32 --border 2
  vt --wang other.vts --extent 16x16 --reference --screenshot o.png
  if "$vcheck" psnr t.png o.png --min 30; then fail "another hash gives the same output"; fi
  # far out: tiles 4294967290.. of a 4096-entry hash (across its wrap at 4096 too), the origin an
  # integer in the shader: as exact as at 0,0
  "$wang" sample.png -o far.vts --tile 16 --colours 2x2 --hash 4096 --codec png \
    --store-tile 32 --border 2
  vt --wang far.vts --extent 16x16 --origin 4294967290,4090 --screenshot t.png
  vt --wang far.vts --extent 16x16 --origin 4294967290,4090 --reference --screenshot r.png
  "$vcheck" psnr t.png r.png --min 99
  vt --wang far.vts --extent 16x16 --reference --screenshot o.png
  if "$vcheck" psnr t.png o.png --min 30; then fail "the origin changes nothing"; fi
  "$wang" sample.png -o corner.vts --tile 16 --corners --colours 3x3 --hash 64 --codec png \
    --store-tile 32 --border 2
  vt --wang corner.vts --extent 16x16 --screenshot t.png
  vt --wang corner.vts --extent 16x16 --reference --screenshot r.png
  "$vcheck" psnr t.png r.png --min 99
  # --tilemap (the hash precomputed with the C API, one fetch) draws what the GLSL hash draws:
  # every tile of a 64-entry hash (64 x 64 tiles, off the texel grid), shuffled and corner packs
  "$wang" sample.png -o shuffled.vts --tile 16 --colours 3x2 --hash 64 --codec png \
    --store-tile 32 --border 2 --shuffle 3
  for p in p2x2 shuffled corner; do
    vt --wang $p.vts --extent 64x64 --origin 7,3 --screenshot t.png
    vt --wang $p.vts --extent 64x64 --origin 7,3 --tilemap --screenshot m.png
    "$vcheck" psnr t.png m.png --min 99
  done
  vt --wang p2x2.vts --extent 64x64 --origin 8,3 --tilemap --screenshot m.png
  if "$vcheck" psnr t.png m.png --min 30; then fail "a tile off gives the same frame"; fi
  ;;
wang_scene)
  # A scene material that names a pack (.vt.mtl "vt_wang PACK.vts scale S", docs/wang.md "Packs
  # in scenes"): a 6 x 6 quad with UVs 0..6 drawn with TileTex from the pack, beside a quad whose
  # map_Kd streams from a store. Seen square-on filling the frame (fovy 90 from 3 units), the pack
  # quad shows output tiles (u, -v) = x 0..5, y -6..-1, i.e. --origin 0,58 of the 64-entry hash:
  # compared with that region assembled on the CPU (--reference: lib/wang through libvts's
  # vts_wang API) and with the 2D TileTex view. A wrong scale, a region one tile off and a pack
  # of another seed fail the comparison; the streamed quad draws byte-identically with and
  # without the pack material. A third quad above, UVs 0..12, names another pack at scale 0.5:
  # the same 6 x 6 tiles of that pack (two packs, one program).
  pack -o pack.vts
  pack -o other.vts --seed 11
  "$synth" wall.png --format png --size 256x256 --channels 3 --photo --seed 3
  "$wang" wall.png -o store.vts --tile 32 --hash 64 --codec png --store-tile 64 --border 2
  {
    echo "mtllib scene.vt.mtl"
    printf 'v %s\n' "-3 -3 0" "3 -3 0" "3 3 0" "-3 3 0" "5 -3 0" "11 -3 0" "11 3 0" "5 3 0"
    printf 'v %s\n' "-3 5 0" "3 5 0" "3 11 0" "-3 11 0"
    printf 'vt %s\n' "0 0" "6 0" "6 6" "0 6" "0 0" "1 0" "1 1" "0 1" "0 0" "12 0" "12 12" "0 12"
    printf 'usemtl ground\nf 1/1 2/2 3/3 4/4\nusemtl wall\nf 5/5 6/6 7/7 8/8\n'
    printf 'usemtl sand\nf 9/9 10/10 11/11 12/12\n'
  } >scene.vt.obj
  mtl() { # the ground material's vt_wang statement (none: empty)
    printf 'newmtl ground\nKd 1 1 1\nillum 0\n%s\n\nnewmtl wall\nKd 1 1 1\nillum 0\n' "$1"
    printf 'map_Kd store.vts#diffuse\n\nnewmtl sand\nillum 0\nvt_wang other.vts scale 0.5\n'
  }
  echo "0 0 3 0 0 0 90" >pack.cam
  echo "4 0 9 4 0 0 90" >both.cam
  scene() { vt store.vts scene.vt.obj --frames 2 --sync "$@"; }
  mtl "vt_wang pack.vts scale 1" >scene.vt.mtl
  scene --camera pack.cam --screenshot s.png
  scene --camera both.cam --screenshot both.png --stats both.json
  echo "0 8 3 0 8 0 90" >sand.cam
  scene --camera sand.cam --screenshot sand.png
  grep -q '{"features": \["wang"\], "faces": 2}' both.json || fail "one wang variant: $(cat both.json)"
  vt --wang pack.vts --extent 6x6 --origin 0,58 --reference --screenshot ref.png
  vt --wang pack.vts --extent 6x6 --origin 0,58 --screenshot tiletex.png
  "$vcheck" psnr s.png ref.png --min 40 || fail "the pack material against the CPU assembly"
  "$check" edges s.png ref.png 6 2
  "$vcheck" psnr s.png tiletex.png --min 60 || fail "the pack material against the 2D TileTex"
  vt --wang pack.vts --extent 6x6 --origin 0,57 --reference --screenshot off.png
  if "$vcheck" psnr s.png off.png --min 30; then fail "a region one tile off passes"; fi
  vt --wang other.vts --extent 6x6 --origin 0,58 --reference --screenshot seed.png
  if "$vcheck" psnr s.png seed.png --min 30; then fail "a pack of another seed passes"; fi
  "$vcheck" psnr sand.png seed.png --min 40 || fail "the second pack at scale 0.5"
  mtl "vt_wang pack.vts scale 2" >scene.vt.mtl
  scene --camera pack.cam --screenshot s2.png
  if "$vcheck" psnr s2.png ref.png --min 30; then fail "scale 2 passes"; fi
  # without the statement: the ground is its Kd; the streamed quad (right half) is unchanged
  mtl "" >scene.vt.mtl
  scene --camera both.cam --screenshot plain.png
  "$vcheck" maxdiff both.png plain.png 128 0 128 256 --max 0 || fail "the streamed quad changed"
  if "$vcheck" maxdiff both.png plain.png 0 0 128 256 --max 8; then fail "no pack drawn"; fi
  # a statement naming a file that is not a pack: one line naming it, exit 1
  mtl "vt_wang wall.png" >scene.vt.mtl
  rc=0
  scene --camera pack.cam --screenshot x.png 2>err.txt || rc=$?
  [ $rc = 1 ] && grep -q "wall.png" err.txt || fail "a pack that is not one: rc $rc, $(cat err.txt)"
  ;;
wang_pipeline)
  # A SOURCE scene whose ground material names a pack ("vt_wang pack.vts scale 1" in scene.mtl,
  # docs/wang.md "Packs in scenes") through the normal pipeline: vt-atlas (no entry for it: its
  # pack in atlas.json's "wang_materials"), vt-offset (its faces' vt copied as written, the
  # statement in the .vt.mtl), vt-tiles --layout, vt-view. The 6 x 6 ground quad (UVs 0..6,
  # repeats) must match the CPU assembly of output tiles x 0..5, y -6..-1 (--origin 0,58 of the
  # 64-entry hash) as in wang_scene; the wall quad (map_Kd) must match --reference-scene.
  # Negative controls: the same pipeline without the statement, and with scale 2, fail.
  atlas=${VT_ATLAS:?} offset=${VT_OFFSET:?} tiles=${VT_TILES:?}
  pack -o pack.vts
  "$synth" wall.png --format png --size 128x128 --channels 3 --photo --seed 3
  {
    echo "mtllib scene.mtl"
    printf 'v %s\n' "-3 -3 0" "3 -3 0" "3 3 0" "-3 3 0" "5 -3 0" "11 -3 0" "11 3 0" "5 3 0"
    printf 'vt %s\n' "0 0" "6 0" "6 6" "0 6" "0 0" "1 0" "1 1" "0 1"
    printf 'usemtl ground\nf 1/1 2/2 3/3 4/4\nusemtl wall\nf 5/5 6/6 7/7 8/8\n'
  } >scene.obj
  mtl() { # the ground material's vt_wang statement (none: empty)
    printf 'newmtl ground\nKd 1 1 1\nillum 0\n%s\n\nnewmtl wall\nKd 1 1 1\nillum 0\n' "$1"
    printf 'map_Kd wall.png\n'
  }
  echo "0 0 3 0 0 0 90" >pack.cam
  echo "8 0 3 8 0 0 90" >wall.cam
  # pipeline TAG: source scene -> store and .vt.obj in TAG/, the ground quad shot as TAG.png
  pipeline() {
    mkdir -p "$1"
    "$atlas" scene.obj -o "$1/atlas.json" --tile-size 64 --border 2 -q
    "$offset" scene.obj "$1/atlas.json" -o "$1/scene.vt.obj" -q
    "$tiles" --layout "$1/atlas.json" -o "$1/scene.vts" --codec png -q
    vt "$1/scene.vts" "$1/scene.vt.obj" --frames 2 --sync --camera pack.cam --screenshot "$1.png"
  }
  mtl "vt_wang pack.vts scale 1" >scene.mtl
  pipeline p
  grep -q '"wang_materials"' p/atlas.json || fail "no wang_materials in atlas.json"
  if grep -q '"name": "ground"' <(sed -n '/"entries"/,/"materials"/p' p/atlas.json); then
    fail "the pack material has an entry"
  fi
  grep -qx 'vt_wang ../pack.vts scale 1' p/scene.vt.mtl || fail "no statement: $(cat p/scene.vt.mtl)"
  diff <(grep '^vt' scene.obj | head -4) <(grep '^vt' p/scene.vt.obj | head -4) ||
    fail "the pack faces' vt changed"
  vt --wang pack.vts --extent 6x6 --origin 0,58 --reference --screenshot ref.png
  "$vcheck" psnr p.png ref.png --min 40 || fail "the pack material against the CPU assembly"
  "$check" edges p.png ref.png 6 2
  # the textured quad against the original scene drawn by --reference-scene
  vt p/scene.vts p/scene.vt.obj --frames 20 --sync --camera wall.cam --screenshot wall.png
  vt p/scene.vts p/scene.vt.obj --frames 1 --camera wall.cam --reference --reference-scene \
    scene.obj --screenshot wallref.png
  "$vcheck" psnr wall.png wallref.png --min 35 || fail "the textured quad against its texture"
  if "$vcheck" psnr p.png wallref.png --min 35; then fail "the wall check passes the ground"; fi
  # negative controls: without the statement (the ground is an atlas material) and scale 2
  mtl "" >scene.mtl
  pipeline n
  if "$vcheck" psnr n.png ref.png --min 30; then fail "the pipeline without vt_wang passes"; fi
  mtl "vt_wang pack.vts scale 2" >scene.mtl
  pipeline s
  if "$vcheck" psnr s.png ref.png --min 30; then fail "scale 2 passes"; fi
  ;;
wang_window)
  # The GLFW window (under xvfb-run) draws what the headless run draws. LeakSanitizer is off for
  # the window (the window case of run_view_test.sh says why).
  pack -o good.vts
  ASAN_OPTIONS=${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0 \
    xvfb-run -a "$view" --wang good.vts --extent 5x5 --frames 3 --size 256x256 \
    --screenshot win.png || fail "window run"
  vt --wang good.vts --extent 5x5 --screenshot head.png
  "$vcheck" psnr win.png head.png --min 99
  ;;
*)
  fail "unknown case $case_name"
  ;;
esac
echo "ok $case_name"
