#!/usr/bin/env python3
"""Checker of vt-view --clipmap's per-frame uploads (tests/e2e/view/run_clipmap_test.sh).

  clipmap_check.py strips STATS.json INFO.json [--tamper drop|add] [--tile-bytes N]

A brute-force model of the clipmap, written from the rules of docs/clipmap.md and
include/vts/vts_clipmap.h and independent of libvts: per frame it recomputes every level's window
from the paging centre in the statistics with the snapping formula, moves the target, lists the
load plan (coarsest level first; the strips of target minus front, column strips beside the front
then row strips over the target's width, each row by row, skipping tiles already in their
toroidal slot; a move first grows the front over the columns and rows already in their slots),
cuts it to floor(budget / B) tiles (B, one tile's upload: C * C * 4 bytes of RGBA8, or
--tile-bytes N: C * C / 2 for BC1 blocks, C * C for BC3; the header's tile_bytes must equal it), loads them and grows the fronts.
The tiles vt-view uploaded in each frame must equal the model's exactly (same tiles, same order),
the fronts must agree, and every frame's bytes must stay within the budget. INFO.json is
`vt-info --json` of the store (the levels' tile grids). --tamper alters the uploads read from
STATS.json first (one tile dropped, or one tile added), for the test's negative control: the
check must then fail.
Exit 0 when the check holds, 1 when it does not, 2 on bad use.
"""
import json
import math
import sys


def window(cx, cy, n, c, tx, ty):
    """The level's window for a centre in its texels: [x0, x1) x [y0, y1) tiles."""

    def axis(v, tiles):
        if not math.isfinite(v):
            v = 0.0
        a = math.floor(v / c - n / 2 + 0.5)
        a = max(0, min(a, tiles - n)) if tiles > n else 0
        return a, min(a + n, tiles)

    x0, x1 = axis(cx, tx)
    y0, y1 = axis(cy, ty)
    return (x0, y0, x1, y1)


def empty(r):
    return r[0] >= r[2] or r[1] >= r[3]


def intersect(a, b):
    r = (max(a[0], b[0]), max(a[1], b[1]), min(a[2], b[2]), min(a[3], b[3]))
    return (0, 0, 0, 0) if empty(r) else r


def strips(front, to):
    """to minus front as disjoint rectangles in loading order."""
    f = intersect(front, to) if not empty(front) else (0, 0, 0, 0)
    if empty(f):
        return [to]
    out = []
    if to[0] < f[0]:
        out.append((to[0], f[1], f[0], f[3]))
    if f[2] < to[2]:
        out.append((f[2], f[1], to[2], f[3]))
    if to[1] < f[1]:
        out.append((to[0], to[1], to[2], f[1]))
    if f[3] < to[3]:
        out.append((to[0], f[3], to[2], to[3]))
    return out


class Level:
    def __init__(self, tx, ty):
        self.tx, self.ty = tx, ty
        self.back = (0, 0, 0, 0)
        self.front = (0, 0, 0, 0)
        self.slots = {}

    def holds(self, n, x, y):
        return self.slots.get((x % n, y % n)) == (x, y)

    def grow(self, n):
        b = self.back
        if empty(self.front):
            if not empty(b) and self.holds(n, b[0], b[1]):
                self.front = (b[0], b[1], b[0] + 1, b[1] + 1)
            else:
                return
        changed = True
        while changed:  # passes over the four sides, left, right, top, bottom, until none joins
            changed = False
            x0, y0, x1, y1 = self.front
            if x0 > b[0] and all(self.holds(n, x0 - 1, y) for y in range(y0, y1)):
                x0, changed = x0 - 1, True
            if x1 < b[2] and all(self.holds(n, x1, y) for y in range(y0, y1)):
                x1, changed = x1 + 1, True
            if y0 > b[1] and all(self.holds(n, x, y0 - 1) for x in range(x0, x1)):
                y0, changed = y0 - 1, True
            if y1 < b[3] and all(self.holds(n, x, y1) for x in range(x0, x1)):
                y1, changed = y1 + 1, True
            self.front = (x0, y0, x1, y1)


def model(info, n, budget, tile_bytes):
    c = info["tile_content_px"]
    levels = [Level(l["tiles_x"], l["tiles_y"]) for l in info["layers"][0]["levels"]]
    per_frame = budget // tile_bytes

    def frame(centre):
        for l, lv in enumerate(levels):
            k = 2.0**-l
            lv.back = window(centre[0] * k, centre[1] * k, n, c, lv.tx, lv.ty)
            lv.front = intersect(lv.front, lv.back) if not empty(lv.front) else (0, 0, 0, 0)
            lv.grow(n)  # tiles an unfinished earlier target left in their slots next to the front
        plan = []
        for l in range(len(levels) - 1, -1, -1):
            lv = levels[l]
            for s in strips(lv.front, lv.back):
                for y in range(s[1], s[3]):
                    for x in range(s[0], s[2]):
                        if not lv.holds(n, x, y):
                            plan.append((l, x, y))
        plan = plan[:per_frame]
        for l, x, y in plan:
            levels[l].slots[(x % n, y % n)] = (x, y)
            levels[l].grow(n)
        return plan, [lv.front for lv in levels]

    return c, frame


def main(argv):
    if len(argv) < 4 or argv[1] != "strips":
        print(__doc__, file=sys.stderr)
        return 2
    stats = json.load(open(argv[2]))
    info = json.load(open(argv[3]))
    opts = dict(zip(argv[4::2], argv[5::2]))
    tamper = opts.get("--tamper")
    cm = stats["clipmap"]
    n, budget = cm["n"], cm["budget"]
    c = info["tile_content_px"]
    tile_bytes = int(opts.get("--tile-bytes", c * c * 4))
    if cm["tile_bytes"] != tile_bytes:
        print(f"tile_bytes {cm['tile_bytes']} in the statistics, {tile_bytes} expected")
        return 1
    c, frame = model(info, n, budget, tile_bytes)
    frames = stats["frames"]
    if tamper:  # the negative control: one tile dropped from, or added to, a frame with uploads
        i = next(i for i, f in enumerate(frames) if len(f["uploaded"]) > 1)
        if tamper == "drop":
            frames[i]["uploaded"].pop()
        else:
            frames[i]["uploaded"].append(list(frames[i]["uploaded"][0]))
    bad = 0
    total = 0
    for i, f in enumerate(frames):
        want, fronts = frame(f["centre"])
        got = [tuple(t) for t in f["uploaded"]]
        total += len(got)
        if got != want:
            missing = [t for t in want if t not in got]
            extra = [t for t in got if t not in want]
            print(f"frame {i}: uploaded {len(got)} tiles, the model {len(want)}; missing "
                  f"{missing[:5]}, extra {extra[:5]}")
            bad += 1
        if f["bytes_uploaded"] > budget or f["bytes_uploaded"] != len(got) * tile_bytes:
            print(f"frame {i}: {f['bytes_uploaded']} bytes for {len(got)} tiles, budget {budget}")
            bad += 1
        norm = [(0, 0, 0, 0) if empty(r) else tuple(r) for r in f["fronts"]]
        if norm != fronts:
            print(f"frame {i}: fronts {f['fronts']}, the model's {fronts}")
            bad += 1
        if bad > 10:
            break
    print(f"{len(frames)} frames, {total} tiles uploaded: "
          f"{'as the model' if not bad else f'{bad} disagreements'}")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
