"""vtpipe.Clipmap (python/vtpipe/clipmap.py) against a pure-Python model written here from
vts_clipmap.h and docs/clipmap.md: level sizes; windows (exact rational arithmetic on 1/8-texel
centres: x0 = floor(cx / C - n / 2 + 1/2) clamped); slots; strips as tile sets (each tile of
to minus from in exactly one strip, disjoint, the intersection growing as a rectangle after every
strip); random walks of the paging centre with a fixed seed, some interrupted before their loads
finish: at every frame the plan equals the model's set of target tiles not in their slots (one
extra or one missing tile fails), coarsest level first, the budgeted plan is the unlimited plan's
prefix, pending matches, the front is a maximal rectangle of loaded tiles within the back that
only grows while loading, complete and valid agree with it, and a move that left P tiles pending
completes in exactly ceil(P / k) frames of k tiles. Errors raise with libvts's message (init) or
the binding's. A store built by vt-tiles: the geometry, and a paging loop that reads the planned
tiles into toroidal slot textures, which then show the level texel for texel over the valid
rectangle. Negative controls: a window model without the + 1/2, plans and strips with a tile
extra or missing, a front over an unloaded tile and a shifted slot texture are all caught by the
same checks. Run by ctest (tests/python/CMakeLists.txt, VT_TILES names vt-tiles)."""
import math
import os
import random
import subprocess
from fractions import Fraction

import numpy as np
import pytest
from PIL import Image

import vtpipe
from vtpipe import Clipmap, ClipmapTile, TileRect

# (width, height, tile_content_px): one texel; 4x4, 40x24, 10x38 tiles at level 0; partial last
# tiles; C = 3, 4, 5, 8
GEOMETRIES = [(1, 1, 4), (16, 16, 4), (160, 96, 4), (30, 114, 3), (37, 23, 5), (200, 120, 8)]


def geometry(width, height, c, border=1):
    return vtpipe.Geometry(width, height, c, border, c + 2 * border,
                           vtpipe.full_level_count(width, height, c), 1, 0)


# ---- the model -------------------------------------------------------------------------------

def model_tiles(g, level):
    """(tiles_x, tiles_y) of level: ceil(ceil(size / 2^l) / C), sizes never below 1."""
    w, h = max(1, -(-g.width // 2**level)), max(1, -(-g.height // 2**level))
    return -(-w // g.tile_content_px), -(-h // g.tile_content_px)


def model_level_size(g, level):
    return max(1, -(-g.width // 2**level)), max(1, -(-g.height // 2**level))


def model_start(centre, c, n, tiles, half=Fraction(1, 2)):
    """The window's first tile on one axis, exactly; half=0 is the deliberately wrong model."""
    if tiles <= n:
        return 0
    x0 = math.floor(Fraction(centre) / c - Fraction(n, 2) + half)
    return min(max(x0, 0), tiles - n)


def model_window(g, n, level, cx, cy, half=Fraction(1, 2)):
    tx, ty = model_tiles(g, level)
    x0 = model_start(cx, g.tile_content_px, n, tx, half)
    y0 = model_start(cy, g.tile_content_px, n, ty, half)
    return TileRect(x0, y0, min(x0 + n, tx), min(y0 + n, ty))


def tiles_of(r):
    return {(x, y) for y in range(r.y0, r.y1) for x in range(r.x0, r.x1)}


def empty(r):
    return r.x0 >= r.x1 or r.y0 >= r.y1


def bounding_rect(tiles):
    """The rectangle the tile set is, or None when it is not one."""
    if not tiles:
        return None
    xs, ys = [x for x, _ in tiles], [y for _, y in tiles]
    r = TileRect(min(xs), min(ys), max(xs) + 1, max(ys) + 1)
    return r if tiles_of(r) == set(tiles) else None


def model_valid(g, level, front, inset):
    """vts_clipmap_valid from the header's words: the front in texels, clipped to the level,
    shrunk by inset on each side inside the level."""
    if empty(front):
        return (0.0, 0.0, 0.0, 0.0)
    c = g.tile_content_px
    w, h = model_level_size(g, level)
    tx, ty = model_tiles(g, level)
    inset = max(inset, 0.0)
    x0, y0 = front.x0 * c + (inset if front.x0 > 0 else 0), front.y0 * c + (inset if front.y0 > 0
                                                                           else 0)
    x1 = min(front.x1 * c, w) - (inset if front.x1 < tx else 0)
    y1 = min(front.y1 * c, h) - (inset if front.y1 < ty else 0)
    return (0.0, 0.0, 0.0, 0.0) if x0 >= x1 or y0 >= y1 else (x0, y0, x1, y1)


# ---- the checkers: each returns a list of mismatches (empty: agree) ----------------------------

def window_mismatches(cm, g, n, centres, half=Fraction(1, 2)):
    bad = []
    for level in range(cm.levels):
        for cx, cy in centres:
            k = Fraction(1, 2**level)
            got = cm.window(level, float(cx * k), float(cy * k))
            want = model_window(g, n, level, cx * k, cy * k, half)
            if got != want:
                bad.append((level, cx, cy, got, want))
    return bad


def strip_mismatches(frm, to, strips):
    bad = []
    if len(strips) > 4 or any(empty(s) for s in strips):
        bad.append("count or an empty strip")
    want = tiles_of(to) - tiles_of(frm)
    seen = set()
    for s in strips:
        t = tiles_of(s)
        if t & seen:
            bad.append(f"strip {s} overlaps an earlier one")
        seen |= t
    if seen != want:
        bad.append(f"{len(seen - want)} tiles extra, {len(want - seen)} missing")
    inter = tiles_of(to) & tiles_of(frm)
    if not inter:
        if strips != ([to] if not empty(to) else []):
            bad.append("a jump is not the target itself")
        return bad
    grown = set(inter)
    for s in strips:  # the loading order: the intersection stays a rectangle after every strip
        grown |= tiles_of(s)
        if bounding_rect(grown) is None:
            bad.append(f"not a rectangle after {s}")
    return bad


def plan_mismatches(plan, missing):
    """plan (a list of ClipmapTiles) against the model's set of (level, x, y) not in their slots:
    the same set, no repeats, coarsest level first, slots (x mod n, y mod n) given separately."""
    bad = []
    got = [(t.level, t.x, t.y) for t in plan]
    if len(set(got)) != len(got):
        bad.append("a tile planned twice")
    if set(got) != missing:
        bad.append(f"{len(set(got) - missing)} tiles extra, {len(missing - set(got))} missing")
    levels = [t.level for t in plan]
    if levels != sorted(levels, reverse=True):
        bad.append("not coarsest level first")
    return bad


def front_mismatches(cm, g, n, level, slots, front=None):
    """The front of level (or the given one) against the model's slots: a rectangle within the
    back of tiles all in their slots, maximal (no line next to it within the back complete, and
    an empty front only while the back's top-left tile is not loaded); complete and valid."""
    bad = []
    back, front = cm.back(level), cm.front(level) if front is None else front

    def in_slot(x, y):
        return slots.get((level, x % n, y % n)) == (x, y)

    def all_in(r):
        return all(in_slot(x, y) for x, y in tiles_of(r))

    if empty(front):
        if not empty(back) and in_slot(back.x0, back.y0):
            bad.append("empty front with the back's first tile loaded")
    else:
        if not tiles_of(front) <= tiles_of(back):
            bad.append(f"front {front} outside back {back}")
        if not all_in(front):
            bad.append(f"front {front} over a tile not in its slot")
        f = front
        for line, inside in [(TileRect(f.x0 - 1, f.y0, f.x0, f.y1), f.x0 > back.x0),
                             (TileRect(f.x1, f.y0, f.x1 + 1, f.y1), f.x1 < back.x1),
                             (TileRect(f.x0, f.y0 - 1, f.x1, f.y0), f.y0 > back.y0),
                             (TileRect(f.x0, f.y1, f.x1, f.y1 + 1), f.y1 < back.y1)]:
            if inside and all_in(line):
                bad.append(f"front {front} could grow over {line}")
    if cm.complete(level) != (not empty(back) and front == back):
        bad.append("complete disagrees")
    for inset in (0.0, 0.5, 3.0):
        if cm.valid(level, inset) != model_valid(g, level, front, inset):
            bad.append(f"valid({inset}) {cm.valid(level, inset)} != "
                       f"{model_valid(g, level, front, inset)}")
    return bad


# ---- tests ----------------------------------------------------------------------------------

def eighth_centres(rng, g, count):
    """Centres on the 1/8-texel grid from two tiles before the store to two after it (exact in
    binary, so the library's double arithmetic and the model's rationals see the same value)."""
    c = g.tile_content_px
    lo_x, hi_x = -2 * c * 8, (g.width + 2 * c) * 8
    lo_y, hi_y = -2 * c * 8, (g.height + 2 * c) * 8
    return [(Fraction(rng.randint(lo_x, hi_x), 8), Fraction(rng.randint(lo_y, hi_y), 8))
            for _ in range(count)]


@pytest.mark.parametrize("dims", GEOMETRIES)
def test_levels_windows_and_slots_match_the_model(dims):
    rng = random.Random(19)
    g = geometry(*dims)
    for n in range(1, 6):
        with Clipmap(g, n) as cm:
            assert cm.n == n and cm.levels == g.level_count
            for level in range(cm.levels):
                assert cm.tiles(level) == model_tiles(g, level)
                assert cm.back(level) == cm.front(level) == TileRect(0, 0, 0, 0)
                assert not cm.complete(level)
            centres = eighth_centres(rng, g, 60)
            # snapping cell boundaries exactly, and a texel either side of them
            c = g.tile_content_px
            for b in (Fraction(c * k, 2) for k in range(-2, 12)):
                centres += [(b, b), (b - Fraction(1, 8), b + Fraction(1, 8))]
            assert window_mismatches(cm, g, n, centres) == []
            for x, y in [(0, 0), (n, 2 * n + 1), (7, 12), (2**32 - 1, 5)]:
                assert cm.slot(x, y) == (x % n, y % n)


def test_a_window_model_without_the_half_is_caught():
    rng = random.Random(3)
    for dims in GEOMETRIES[2:]:
        g = geometry(*dims)
        with Clipmap(g, 4) as cm:
            centres = eighth_centres(rng, g, 60)
            assert window_mismatches(cm, g, 4, centres) == []
            assert window_mismatches(cm, g, 4, centres, half=Fraction(0)) != []


def test_strips_are_the_new_tiles_in_loading_order():
    # every pair of rectangles of 1..3 x 1..3 tiles in a 6 x 6 grid, and the empty from
    spans = [(a, b) for a in range(6) for b in range(a + 1, min(a + 3, 6) + 1)]
    rects = [TileRect(x0, y0, x1, y1) for x0, x1 in spans for y0, y1 in spans]
    pairs = 0
    for to in rects:
        for frm in rects + [TileRect(0, 0, 0, 0)]:
            assert strip_mismatches(frm, to, Clipmap.strips(frm, to)) == [], (frm, to)
            pairs += 1
    assert pairs == len(rects) * (len(rects) + 1) == 225 * 226
    # docs/clipmap.md's example (n = 4), order included
    assert Clipmap.strips((2, 3, 6, 7), (3, 1, 7, 5)) == [TileRect(6, 3, 7, 5),
                                                         TileRect(3, 1, 7, 3)]
    assert Clipmap.strips((0, 0, 4, 4), (0, 0, 0, 0)) == []


def test_wrong_strips_are_caught():
    frm, to = TileRect(2, 3, 6, 7), TileRect(3, 1, 7, 5)
    good = Clipmap.strips(frm, to)
    assert strip_mismatches(frm, to, good) == []
    assert strip_mismatches(frm, to, good[:1]) != []                              # one missing
    assert strip_mismatches(frm, to, good + [TileRect(3, 3, 4, 4)]) != []         # one extra
    assert strip_mismatches(frm, to, good[::-1]) != []                            # out of order


def walk(g, n, budget, rng, moves=16):
    """A random walk of the paging centre: at each move every level is moved (move_all, or some
    levels to their own centres), then frames of at most budget loads run, to completion or
    (half of the moves) interrupted by the next move. Checks everything against the model at
    every frame; returns the number of frames."""
    slots = {}  # (level, slot_x, slot_y) -> (x, y) it holds
    targets = [TileRect(0, 0, 0, 0)] * g.level_count
    c = g.tile_content_px
    cx, cy = Fraction(g.width, 2), Fraction(g.height, 2)
    frames = 0
    with Clipmap(g, n) as cm:
        for m in range(moves):
            kind = rng.random()
            if kind < 0.4:    # a sub-tile step
                cx += Fraction(rng.randint(-c * 8, c * 8), 8)
                cy += Fraction(rng.randint(-c * 8, c * 8), 8)
            elif kind < 0.8:  # up to two windows
                cx += Fraction(rng.randint(-2 * n * c * 8, 2 * n * c * 8), 8)
                cy += Fraction(rng.randint(-2 * n * c * 8, 2 * n * c * 8), 8)
            else:             # a jump anywhere
                cx, cy = eighth_centres(rng, g, 1)[0]
            got = cm.move_all(float(cx), float(cy))
            for level in range(g.level_count):
                k = Fraction(1, 2**level)
                targets[level] = model_window(g, n, level, cx * k, cy * k)
            if rng.random() < 0.2:  # one level with a centre of its own
                level = rng.randrange(g.level_count)
                tx, ty = model_tiles(g, level)
                ox = Fraction(rng.randint(0, tx * c * 8), 8)
                oy = Fraction(rng.randint(0, ty * c * 8), 8)
                targets[level] = model_window(g, n, level, ox, oy)
                got[level] = cm.window(level, float(ox), float(oy))
                cm.move(level, got[level])
            assert got == targets
            assert [cm.back(level) for level in range(g.level_count)] == targets
            for level in range(g.level_count):
                assert front_mismatches(cm, g, n, level, slots) == []

            def missing():
                return {(level, x, y) for level, t in enumerate(targets) for x, y in tiles_of(t)
                        if slots.get((level, x % n, y % n)) != (x, y)}

            pending = len(missing())
            assert cm.pending() == pending
            interrupt = rng.random() < 0.5
            steps = 0
            while cm.pending():
                full = cm.plan(2**32 - 1)
                assert plan_mismatches(full, missing()) == []
                assert all((t.slot_x, t.slot_y) == (t.x % n, t.y % n) for t in full)
                plan = cm.plan(budget)
                assert plan == full[:budget]
                for t in plan:
                    before = [cm.front(level) for level in range(g.level_count)]
                    cm.loaded(t)
                    slots[(t.level, t.slot_x, t.slot_y)] = (t.x, t.y)
                    for level in range(g.level_count):
                        assert tiles_of(before[level]) <= tiles_of(cm.front(level))
                    assert front_mismatches(cm, g, n, t.level, slots) == []
                steps += 1
                frames += 1
                assert cm.pending() == len(missing())
                if interrupt and rng.random() < 0.5:
                    break
            else:
                assert steps == -(-pending // budget)
                assert cm.plan(budget) == []
                for level in range(g.level_count):
                    assert cm.complete(level) and cm.front(level) == targets[level]
    return frames


@pytest.mark.parametrize("dims", GEOMETRIES)
def test_random_walks_match_the_model(dims):
    rng = random.Random(1900 + dims[0])
    g = geometry(*dims)
    walks = [(n, budget) for n in range(1, 6) for budget in (1, 2, 3, 7)]
    frames = sum(walk(g, n, budget, rng, moves=24) for n, budget in walks)
    assert frames >= len(walks)  # every walk loads its first windows


def test_wrong_plans_and_fronts_are_caught():
    g = geometry(160, 96, 4)
    with Clipmap(g, 4) as cm:
        cm.move_all(80, 48)
        plan = cm.plan(1000)
        missing = {(t.level, t.x, t.y) for t in plan}
        assert plan_mismatches(plan, missing) == []
        assert plan_mismatches(plan[1:], missing) != []                         # one missing
        assert plan_mismatches(plan + [ClipmapTile(0, 0, 0, 0, 0)], missing) != []  # one extra
        assert plan_mismatches(plan + plan[-1:], missing) != []                 # one twice
        assert plan_mismatches(plan[::-1], missing) != []                       # finest first
        slots = {}
        for t in plan[:-1]:  # all but the last tile of level 0
            cm.loaded(t)
            slots[(t.level, t.slot_x, t.slot_y)] = (t.x, t.y)
        assert front_mismatches(cm, g, 4, 0, slots) == []
        assert front_mismatches(cm, g, 4, 0, slots, front=cm.back(0)) != []   # over the unloaded
        shrunk = cm.front(0)._replace(x1=cm.front(0).x1 - 1)
        assert front_mismatches(cm, g, 4, 0, slots, front=shrunk) != []        # not maximal


def test_errors_raise_with_the_message():
    g = geometry(160, 96, 4)
    for n in (0, 257):
        with pytest.raises(vtpipe.VtsError,
                           match=f"clipmap: window of {n} tiles is outside 1..256") as e:
            Clipmap(g, n)
        assert e.value.status_name == "arg" and e.value.status == -10
    with pytest.raises(vtpipe.VtsError, match="invalid store geometry: tile payload 7 px != "
                       "content 4 \\+ 2 \\* border 1") as e:
        Clipmap(g._replace(tile_payload_px=7), 4)
    assert e.value.status_name == "arg"
    with pytest.raises(vtpipe.VtsError, match="invalid store geometry: 9 levels requested"):
        Clipmap(g._replace(level_count=9), 4)
    with pytest.raises(TypeError, match="Store or a Geometry"):
        Clipmap("scene.vts", 4)
    with pytest.raises(TypeError, match="n must be an int, not float"):
        Clipmap(g, 4.0)
    with pytest.raises(vtpipe.VtsRangeError, match="n -1 is out of range"):
        Clipmap(g, -1)
    with pytest.raises(vtpipe.VtsRangeError, match="geometry.width 4294967296 is out of range"):
        Clipmap(g._replace(width=2**32), 4)
    cm = Clipmap(g, np.uint8(4))  # numpy ints are ints
    assert cm.levels == 7
    with pytest.raises(vtpipe.VtsRangeError, match=r"clipmap: no level 7 \(the clipmap has 7\)"):
        cm.window(7, 0, 0)
    with pytest.raises(IndexError, match="no level 8"):
        cm.front(8)
    for method in (cm.back, cm.complete, cm.valid, cm.tiles):
        with pytest.raises(vtpipe.VtsRangeError, match="no level 7"):
            method(7)
    with pytest.raises(TypeError, match="level must be an int, not bool"):
        cm.window(True, 0, 0)
    with pytest.raises(TypeError, match="cx must be a number, not str"):
        cm.window(0, "1", 0)
    with pytest.raises(vtpipe.VtsRangeError, match="x 4294967296 is out of range"):
        cm.slot(2**32, 0)
    with pytest.raises(vtpipe.VtsRangeError, match="wider than 4 tiles or outside the level's "
                       "40x24 tiles"):
        cm.move(0, TileRect(0, 0, 5, 4))
    with pytest.raises(vtpipe.VtsRangeError, match="outside the level's 40x24 tiles"):
        cm.move(0, (38, 0, 42, 4))
    with pytest.raises(TypeError, match=r"rect must be 4 ints"):
        cm.move(0, (0, 0, 4))
    with pytest.raises(TypeError, match="from_rect.x0 must be an int, not float"):
        Clipmap.strips((0.5, 0, 1, 1), (0, 0, 1, 1))
    cm.move(0, TileRect(4, 4, 8, 8))
    with pytest.raises(vtpipe.VtsRangeError, match=r"clipmap: tile 8,4 is outside level 0's "
                       r"target TileRect\(x0=4, y0=4, x1=8, y1=8\)"):
        cm.loaded((0, 8, 4))
    with pytest.raises(TypeError, match="x must be an int, not str"):
        cm.loaded((0, "4", 4))
    with pytest.raises(TypeError, match="tile must be a ClipmapTile or"):
        cm.loaded(4)
    with pytest.raises(vtpipe.VtsError, match="has slot 0,0, not 1,0") as e:
        cm.loaded(ClipmapTile(0, 4, 4, 1, 0))
    assert e.value.status_name == "arg"
    cm.loaded((0, 4, 4))
    assert cm.front(0) == TileRect(4, 4, 5, 5)
    assert cm.plan(0) == [] and len(cm.plan(100)) == 15
    with pytest.raises(vtpipe.VtsRangeError, match="max_tiles -1 is out of range"):
        cm.plan(-1)
    cm.move(0, TileRect(0, 0, 0, 0))  # an empty target empties the level
    assert cm.back(0) == cm.front(0) == TileRect(0, 0, 0, 0) and cm.pending() == 0
    cm.close()
    cm.close()
    assert "closed" in repr(cm)
    with pytest.raises(vtpipe.VtsError, match="clipmap: closed"):
        cm.plan(4)


def test_a_store_built_by_vt_tiles(tmp_path):
    """vt-tiles builds a store from a noise image; the clipmap reads its geometry, and a paging
    loop copies the planned tiles' content into one n C x n C slot texture per level; once
    complete, each level's texture read toroidally equals the level over its valid rectangle."""
    rng = np.random.default_rng(19)
    image = tmp_path / "noise.png"
    Image.fromarray(rng.integers(0, 256, (150, 230, 3), dtype=np.uint8)).save(image)
    store = tmp_path / "noise.vts"
    subprocess.run([os.environ["VT_TILES"], str(image), "-o", str(store), "--tile-size", "16",
                    "--border", "2", "--codec", "png", "-q"], check=True)
    n = 3
    with vtpipe.open(store) as s, Clipmap(s, n) as cm:
        g = s.geometry
        c = g.tile_content_px
        assert (g.width, g.height, c, cm.levels) == (230, 150, 16, g.level_count)
        assert [cm.tiles(level) for level in range(cm.levels)] == \
            [(L.tiles_x, L.tiles_y) for L in s.levels]
        textures = [np.zeros((n * c, n * c, 3), np.uint8) for _ in range(cm.levels)]
        for cx, cy in [(100.0, 70.0), (104.5, 71.0), (180.0, 20.0), (30.0, 140.0)]:
            targets = cm.move_all(cx, cy)
            assert targets == [model_window(g, n, level, Fraction(cx) / 2**level,
                                            Fraction(cy) / 2**level)
                               for level in range(cm.levels)]
            frames = 0
            while cm.pending():
                for t in cm.plan(4):  # the frame's budget: 4 tiles
                    tex = textures[t.level]
                    tex[t.slot_y * c:(t.slot_y + 1) * c, t.slot_x * c:(t.slot_x + 1) * c] = \
                        s.tile(0, t.level, t.x, t.y, border=False)
                    cm.loaded(t)
                frames += 1
                assert frames < 100
            for level in range(cm.levels):
                assert cm.complete(level) and cm.front(level) == targets[level]
                x0, y0, x1, y1 = (int(v) for v in cm.valid(level, 0))
                assert (x0, y0) == (targets[level].x0 * c, targets[level].y0 * c)
                want = s.region(0, level, x0, y0, x1 - x0, y1 - y0)
                ys, xs = np.arange(y0, y1) % (n * c), np.arange(x0, x1) % (n * c)
                got = textures[level][ys[:, None], xs[None, :]]
                assert np.array_equal(got, want), (cx, cy, level)
                if level == 0:  # a texture read one texel off does not match
                    off = textures[level][ys[:, None], ((xs + 1) % (n * c))[None, :]]
                    assert not np.array_equal(off, want)
