"""The clipmap arithmetic of libvts (vts_clipmap.h, docs/clipmap.md) from Python: windows snapped to
the tile grid, toroidal slots, strips, each level's front (loaded) and back (target) window, and
the load plan. Pure computation: the caller reads the planned tiles (Store.tile) and uploads them.

    import vtpipe
    with vtpipe.open("scene.vts") as s, vtpipe.Clipmap(s, 8) as cm:
        cm.move_all(cx, cy)                  # the paging centre, in level-0 texels
        for t in cm.plan(16):                # at most 16 tiles this frame
            pixels = s.tile(0, t.level, t.x, t.y)   # upload into slot (t.slot_x, t.slot_y)
            cm.loaded(t)
        x0, y0, x1, y1 = cm.valid(2, 0.5)    # where level 2 may be sampled, its texels

Integer arguments (levels, tiles, n, budgets) must be ints (Python or numpy, not floats):
another type raises TypeError, a negative or too large one VtsRangeError. Centres and insets are
numbers (floats). A level outside the clipmap raises VtsRangeError in every per-level method.
"""
import collections
import ctypes
import math
import numbers
import operator

from . import _lib
from ._errors import VtsError, VtsRangeError, raise_error

__all__ = ["Clipmap", "TileRect", "ClipmapTile"]

TileRect = collections.namedtuple("TileRect", "x0 y0 x1 y1")
TileRect.__doc__ = ("Tiles x0 <= x < x1, y0 <= y < y1 of one level (empty when x0 >= x1 or "
                    "y0 >= y1).")
ClipmapTile = collections.namedtuple("ClipmapTile", "level x y slot_x slot_y")
ClipmapTile.__doc__ = "A tile to load: level, position in the level's tile grid, toroidal slot."


def _int(value, what):
    """value as a uint32 argument: an int (bool and float are refused), 0 .. 2^32 - 1."""
    if isinstance(value, bool):
        raise TypeError(f"{what} must be an int, not bool")
    try:
        value = operator.index(value)
    except TypeError:
        raise TypeError(f"{what} must be an int, not {type(value).__name__}") from None
    if not 0 <= value < 2**32:
        raise VtsRangeError(_lib.STATUS_RANGE, f"{what} {value} is out of range")
    return value


def _real(value, what):
    """value as a double argument: any real number (int, float, numpy), never a string."""
    if not isinstance(value, numbers.Real):
        raise TypeError(f"{what} must be a number, not {type(value).__name__}")
    return float(value)


def _rect(r, what="rect"):
    """A C TileRect from a TileRect or any 4 ints (x0, y0, x1, y1)."""
    try:
        x0, y0, x1, y1 = r
    except (TypeError, ValueError):
        raise TypeError(f"{what} must be 4 ints (x0, y0, x1, y1), not {r!r}") from None
    return _lib.TileRect(_int(x0, what + ".x0"), _int(y0, what + ".y0"), _int(x1, what + ".x1"),
                         _int(y1, what + ".y1"))


def _tuple(r):
    return TileRect(r.x0, r.y0, r.x1, r.y1)


def _geometry(source):
    """A C Geometry from a Store (its geometry) or a Geometry-like object (its named fields)."""
    g = getattr(source, "geometry", source)
    try:
        return _lib.Geometry(*(_int(getattr(g, f), "geometry." + f)
                               for f, _ in _lib.Geometry._fields_))
    except AttributeError as e:
        raise TypeError("Clipmap needs a vtpipe Store or a Geometry (width, height, "
                        "tile_content_px, border_px, tile_payload_px, level_count, layer_count, "
                        f"flags): {e}") from None


class Clipmap:
    """n x n tile windows over every level of a store's pyramid (struct vts_clipmap), all empty
    until the first move. source is a vtpipe Store or a Geometry (vtpipe.Geometry or any object
    with its fields); n is 1 .. 256. Free the C struct with close() or use it as a context
    manager. One thread's at a time (no locking, as in C)."""

    def __init__(self, source, n):
        self._c = None
        geometry = _geometry(source)
        c = _lib.Clipmap()
        err = _lib.Error()
        if _lib.vts.vts_clipmap_init(ctypes.byref(c), ctypes.byref(geometry), _int(n, "n"),
                                     ctypes.byref(err)) != 0:
            raise_error(err)
        self._c = c

    def close(self):
        """Frees the C struct's slot tables (again: nothing)."""
        if self._c is not None:
            _lib.vts.vts_clipmap_free(ctypes.byref(self._c))
            self._c = None

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def __del__(self):
        self.close()

    def __repr__(self):
        if self._c is None:
            return "<vtpipe.Clipmap (closed)>"
        return f"<vtpipe.Clipmap n={self._c.n} {self._c.level_count} levels>"

    def _struct(self):
        if self._c is None:
            raise VtsError(_lib.STATUS_ARG, "clipmap: closed")
        return self._c

    def _level(self, level):
        c = self._struct()
        level = _int(level, "level")
        if level >= c.level_count:
            raise VtsRangeError(_lib.STATUS_RANGE, f"clipmap: no level {level} (the clipmap has "
                                f"{c.level_count})")
        return c, level

    @property
    def n(self):
        """Window edge, tiles."""
        return self._struct().n

    @property
    def levels(self):
        """Number of levels (the store's level_count)."""
        return self._struct().level_count

    def tiles(self, level):
        """(tiles_x, tiles_y) of level."""
        c, level = self._level(level)
        return c.levels[level].tiles_x, c.levels[level].tiles_y

    def window(self, level, cx, cy):
        """The TileRect level holds for a paging centre (cx, cy) in that level's texels, snapped to
        the tile grid: x0 = floor(cx / C - n / 2 + 1/2) clamped to 0 .. tiles_x - n,
        x1 = min(x0 + n, tiles_x), likewise y (vts_clipmap_window)."""
        c, level = self._level(level)
        out = _lib.TileRect()
        _lib.vts.vts_clipmap_window(ctypes.byref(c), level, _real(cx, "cx"), _real(cy, "cy"),
                                    ctypes.byref(out))
        return _tuple(out)

    def slot(self, x, y):
        """The toroidal slot (x mod n, y mod n) of tile (x, y)."""
        c = self._struct()
        sx, sy = ctypes.c_uint32(), ctypes.c_uint32()
        _lib.vts.vts_clipmap_slot(ctypes.byref(c), _int(x, "x"), _int(y, "y"), ctypes.byref(sx),
                                  ctypes.byref(sy))
        return sx.value, sy.value

    @staticmethod
    def strips(from_rect, to_rect):
        """to_rect minus from_rect as at most four disjoint TileRects, in loading order: the columns
        left and right of from_rect over the rows both share, then the rows above and below over
        to_rect's whole width (vts_clipmap_strips); [to_rect] when they do not overlap."""
        a, b = _rect(from_rect, "from_rect"), _rect(to_rect, "to_rect")
        out = (_lib.TileRect * 4)()
        count = _lib.vts.vts_clipmap_strips(ctypes.byref(a), ctypes.byref(b), out)
        return [_tuple(out[i]) for i in range(count)]

    def move(self, level, rect):
        """Sets level's target (back) window to rect (a TileRect, from window()): the front shrinks
        to its intersection with it, then regrows over tiles already in their slots. An empty rect
        empties the level. VtsRangeError for a rect wider than n or outside the level."""
        c, level = self._level(level)
        r = _rect(rect)
        if _lib.vts.vts_clipmap_move(ctypes.byref(c), level, ctypes.byref(r)) != 0:
            L = c.levels[level]
            raise VtsRangeError(_lib.STATUS_RANGE,
                                f"clipmap: target {_tuple(r)} of level {level} is wider than "
                                f"{c.n} tiles or outside the level's {L.tiles_x}x{L.tiles_y} "
                                "tiles")

    def move_all(self, cx0, cy0):
        """Moves every level l to window(l, cx0 / 2^l, cy0 / 2^l): one paging centre given in
        level-0 texels, halved per level. A convenience of the Python side (no such C function);
        it is the rule vt-view's clipmap mode follows every frame (tools/vt-view/vtv_clipmap.c),
        so the windows of the levels nest. Returns the list of the levels' targets."""
        cx0, cy0 = _real(cx0, "cx0"), _real(cy0, "cy0")
        targets = []
        for level in range(self.levels):
            w = self.window(level, math.ldexp(cx0, -level), math.ldexp(cy0, -level))
            self.move(level, w)
            targets.append(w)
        return targets

    def plan(self, max_tiles):
        """The next tiles to load, at most max_tiles, as ClipmapTiles: coarsest level first,
        within a level its strips in loading order, each row by row, skipping tiles already in
        their slots (vts_clipmap_plan). Changes nothing: call loaded() for each tile uploaded."""
        c = self._struct()
        max_tiles = min(_int(max_tiles, "max_tiles"), _lib.vts.vts_clipmap_pending(
            ctypes.byref(c)))
        if max_tiles == 0:
            return []
        out = (_lib.ClipmapTile * max_tiles)()
        count = _lib.vts.vts_clipmap_plan(ctypes.byref(c), out, max_tiles)
        return [ClipmapTile(t.level, t.x, t.y, t.slot_x, t.slot_y) for t in out[:count]]

    def pending(self):
        """How many tiles the targets still need (the length of the unlimited plan)."""
        return _lib.vts.vts_clipmap_pending(ctypes.byref(self._struct()))

    def loaded(self, tile):
        """Records that tile (a ClipmapTile from plan(), or (level, x, y)) is now in its slot and
        grows its level's front. VtsRangeError when the tile is outside its level's target;
        VtsError (status "arg") when a ClipmapTile's slot is not (x mod n, y mod n)."""
        try:
            level, x, y, *slot = tile
        except (TypeError, ValueError):
            raise TypeError(f"tile must be a ClipmapTile or (level, x, y), not {tile!r}") from None
        c, level = self._level(level)
        x, y = _int(x, "x"), _int(y, "y")
        t = _lib.ClipmapTile(level, x, y, x % c.n, y % c.n)
        if slot and tuple(slot) != (t.slot_x, t.slot_y):
            raise VtsError(_lib.STATUS_ARG, f"clipmap: tile {x},{y} of level {level} has slot "
                           f"{t.slot_x},{t.slot_y}, not {','.join(map(str, slot))}")
        if _lib.vts.vts_clipmap_loaded(ctypes.byref(c), ctypes.byref(t)) != 0:
            raise VtsRangeError(_lib.STATUS_RANGE, f"clipmap: tile {x},{y} is outside level "
                                f"{level}'s target {self.back(level)}")

    def complete(self, level):
        """True when level's front equals its target (false before the level's first move)."""
        c, level = self._level(level)
        return bool(_lib.vts.vts_clipmap_complete(ctypes.byref(c), level))

    def valid(self, level, inset=0.0):
        """(x0, y0, x1, y1) floats: the texels of level a filter reaching inset texels may sample,
        the front clipped to the level and shrunk by inset on the sides inside the level
        (vts_clipmap_valid); empty (x0 >= x1) when nothing is usable."""
        c, level = self._level(level)
        v = [ctypes.c_double() for _ in range(4)]
        _lib.vts.vts_clipmap_valid(ctypes.byref(c), level, _real(inset, "inset"),
                                   *(ctypes.byref(d) for d in v))
        return tuple(d.value for d in v)

    def front(self, level):
        """The TileRect of level the renderer may sample: every tile loaded (within the back)."""
        c, level = self._level(level)
        return _tuple(c.levels[level].front)

    def back(self, level):
        """The TileRect of level's target window (empty before its first move)."""
        c, level = self._level(level)
        return _tuple(c.levels[level].back)
