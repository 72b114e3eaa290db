"""vtpipe: read .vts virtual-texture stores from Python, tiles and regions decoded to numpy arrays.

    import vtpipe
    with vtpipe.open("scene.vts") as s:
        print(s.geometry, s.layers, s.metadata)
        img = s.level("diffuse", 2)          # (height, width, channels) numpy array
        tile = s.tile(0, 0, 3, 1)            # one tile with its border
        part = s.region(0, 0, 100, 50, 640, 480)

A thin ctypes layer over libvts (vts.h) and libvts-decode (vts_decode.h); see docs/python.md.
Arrays are uint8 (u8 layers), uint16 (u16) or float32 (f32 layers, and f16 layers converted from
their half floats), always of shape (height, width, channels). Failures raise VtsError with the
library's message; an out-of-range layer, level, tile or rectangle raises VtsRangeError (also an
IndexError). A Store may be read from several threads (the library calls release the GIL).
Clipmap (vtpipe.clipmap) is libvts's clipmap arithmetic (vts_clipmap.h) over a store's pyramid.
"""
import collections
import ctypes
import os

import numpy as np

from . import _lib
from ._errors import VtsError, VtsRangeError, raise_error as _raise
from .clipmap import Clipmap, ClipmapTile, TileRect

__all__ = ["open", "Store", "VtsError", "VtsRangeError", "Geometry", "Layer", "Level",
           "library_version", "full_level_count", "Clipmap", "ClipmapTile", "TileRect"]

Geometry = collections.namedtuple(
    "Geometry", "width height tile_content_px border_px tile_payload_px level_count layer_count "
    "flags")
Layer = collections.namedtuple("Layer", "name channels sample colour codec codec_param flags")
Level = collections.namedtuple("Level", "width height tiles_x tiles_y")

_DTYPES = {"u8": np.uint8, "u16": np.uint16, "f16": np.float16, "f32": np.float32}


def _u32(value, what):
    """value as a uint32 argument; a negative or too large one is out of range, not wrapped."""
    value = int(value)
    if not 0 <= value < 2**32:
        raise VtsRangeError(_lib.STATUS_RANGE, f"{what} {value} is out of range")
    return value


def library_version():
    """Version of the libvts loaded, "MAJOR.MINOR.PATCH"."""
    return _lib.vts.vts_version_string().decode()


def full_level_count(width, height, tile_content_px):
    """Levels from level 0 down to the first that fits in one tile (vts_full_level_count): the
    level_count of a whole pyramid, e.g. for a Geometry given to Clipmap without a store."""
    return _lib.vts.vts_full_level_count(_u32(width, "width"), _u32(height, "height"),
                                         _u32(tile_content_px, "tile_content_px"))


def open(path):
    """Opens and validates the store at path (str or os.PathLike); a Store."""
    return Store(path)


class Store:
    """An open .vts store. Close with close() or use it as a context manager."""

    def __init__(self, path):
        err = _lib.Error()
        self._handle = _lib.vts.vts_open(os.fsencode(path), ctypes.byref(err))
        if not self._handle:
            _raise(err)
        self.path = os.fspath(path)
        g = _lib.vts.vts_store_geometry(self._handle).contents
        self.geometry = Geometry(*(getattr(g, f) for f in Geometry._fields))
        self.layers = [self._layer(i) for i in range(g.layer_count)]
        self.levels = [self._level(i) for i in range(g.level_count)]
        self.metadata = {
            _lib.vts.vts_store_meta_key(self._handle, i).decode():
            _lib.vts.vts_store_meta_value(self._handle, i).decode()
            for i in range(_lib.vts.vts_store_meta_count(self._handle))}

    def _layer(self, i):
        raw = _lib.vts.vts_store_layer(self._handle, i).contents
        codec = (ctypes.c_char * 5)()
        _lib.vts.vts_codec_name(raw.codec, codec)
        return Layer(raw.name.decode(), raw.channels, _lib.vts.vts_sample_name(raw.sample).decode(),
                     _lib.vts.vts_colour_name(raw.colour).decode(), codec.value.decode(),
                     raw.codec_param, raw.flags)

    def _level(self, i):
        raw = _lib.Level()
        _lib.vts.vts_store_level(self._handle, i, ctypes.byref(raw))
        return Level(raw.width, raw.height, raw.tiles_x, raw.tiles_y)

    def close(self):
        """Closes the store (again: nothing)."""
        if getattr(self, "_handle", None):
            _lib.vts.vts_close(self._handle)
            self._handle = None

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def __del__(self):
        self.close()

    def __repr__(self):
        g = self.geometry
        state = "" if self._handle else " (closed)"
        return f"<vtpipe.Store '{self.path}' {g.width}x{g.height} {g.level_count} levels{state}>"

    def layer_index(self, layer):
        """The index of layer, given as an index or a name."""
        if isinstance(layer, str):
            for i, l in enumerate(self.layers):
                if l.name == layer:
                    return i
            raise VtsRangeError(_lib.STATUS_RANGE, f"'{self.path}': no layer named '{layer}'")
        return _u32(layer, "layer")

    def _array(self, layer, width, height):
        """An empty (height, width, channels) array in the layer's stored sample type."""
        if not self._handle:
            raise VtsError(_lib.STATUS_ARG, f"'{self.path}': the store is closed")
        if layer >= len(self.layers):
            raise VtsRangeError(_lib.STATUS_RANGE,
                                f"'{self.path}': no layer {layer} (the store has "
                                f"{len(self.layers)})")
        l = self.layers[layer]
        return np.empty((height, width, l.channels), dtype=_DTYPES[l.sample])

    @staticmethod
    def _result(a):
        return a.astype(np.float32) if a.dtype == np.float16 else a

    def tile(self, layer, level, x, y, border=True):
        """Tile (x, y) of level: tile_payload_px square with its border, else tile_content_px
        (border=False). Empty tiles are zeros."""
        layer = self.layer_index(layer)
        g = self.geometry
        edge = g.tile_payload_px if border else g.tile_content_px
        a = self._array(layer, edge, edge)
        err = _lib.Error()
        rc = _lib.decode.vts_decode_tile(
            self._handle, layer, _u32(level, "level"), _u32(x, "tile x"), _u32(y, "tile y"),
            0 if border else _lib.DECODE_NO_BORDER, a.ctypes.data, a.strides[0], a.nbytes,
            ctypes.byref(err))
        if rc != 0:
            _raise(err)
        return self._result(a)

    def region(self, layer, level, x, y, width, height):
        """The rectangle (x, y, width, height) of level, in its texels, stitched from the tiles'
        content (empty tiles as zeros). It must lie inside the level."""
        layer = self.layer_index(layer)
        width, height = _u32(width, "width"), _u32(height, "height")
        if width == 0 or height == 0:
            raise VtsError(_lib.STATUS_ARG, f"'{self.path}': empty rectangle {width}x{height}")
        a = self._array(layer, width, height)
        err = _lib.Error()
        rc = _lib.decode.vts_decode_region(
            self._handle, layer, _u32(level, "level"), _u32(x, "x"), _u32(y, "y"), width, height,
            0, a.ctypes.data, a.strides[0], a.nbytes, ctypes.byref(err))
        if rc != 0:
            _raise(err)
        return self._result(a)

    def level(self, layer, level):
        """The whole of level, as region(layer, level, 0, 0, level width, level height)."""
        level = _u32(level, "level")
        if level >= len(self.levels):
            raise VtsRangeError(_lib.STATUS_RANGE, f"'{self.path}': no level {level} (the store "
                                f"has {len(self.levels)})")
        L = self.levels[level]
        return self.region(layer, level, 0, 0, L.width, L.height)
