"""ctypes bindings of libvts (vts.h, vts_clipmap.h) and libvts-decode (vts_decode.h): the few
functions the package calls, their argument types and structs, and where the libraries are found."""
import ctypes
import os

from . import _paths

ERROR_MESSAGE_MAX = 256
LAYER_NAME_BYTES = 32
STATUS_RANGE = -7
STATUS_ARG = -10
DECODE_NO_BORDER = 1 << 0
MAX_LEVELS = 32
CLIPMAP_MAX_N = 256


class Error(ctypes.Structure):
    _fields_ = [("status", ctypes.c_int), ("message", ctypes.c_char * ERROR_MESSAGE_MAX)]


class Geometry(ctypes.Structure):
    _fields_ = [(n, ctypes.c_uint32) for n in ("width", "height", "tile_content_px", "border_px",
                                               "tile_payload_px", "level_count", "layer_count",
                                               "flags")]


class Layer(ctypes.Structure):
    _fields_ = [("codec", ctypes.c_uint32), ("channels", ctypes.c_uint8),
                ("sample", ctypes.c_uint8), ("colour", ctypes.c_uint8), ("flags", ctypes.c_uint8),
                ("codec_param", ctypes.c_uint32), ("name", ctypes.c_char * LAYER_NAME_BYTES)]


class Level(ctypes.Structure):
    _fields_ = [("width", ctypes.c_uint32), ("height", ctypes.c_uint32),
                ("tiles_x", ctypes.c_uint32), ("tiles_y", ctypes.c_uint32),
                ("first_tile", ctypes.c_uint64)]


class TileRect(ctypes.Structure):
    _fields_ = [(n, ctypes.c_uint32) for n in ("x0", "y0", "x1", "y1")]


class ClipmapTile(ctypes.Structure):
    _fields_ = [(n, ctypes.c_uint32) for n in ("level", "x", "y", "slot_x", "slot_y")]


class ClipmapLevel(ctypes.Structure):
    _fields_ = [("width", ctypes.c_uint32), ("height", ctypes.c_uint32),
                ("tiles_x", ctypes.c_uint32), ("tiles_y", ctypes.c_uint32),
                ("back", TileRect), ("front", TileRect),
                ("slot_tile", ctypes.POINTER(ctypes.c_uint64))]


class Clipmap(ctypes.Structure):
    """struct vts_clipmap of vts_clipmap.h (held by value: the caller owns it)."""
    _fields_ = [("n", ctypes.c_uint32), ("content_px", ctypes.c_uint32),
                ("level_count", ctypes.c_uint32), ("levels", ClipmapLevel * MAX_LEVELS)]


def _load():
    """libvts-decode from the directory _paths names (relative to this package when installed,
    the build tree's when built), else through the loader's path (LD_LIBRARY_PATH, ldconfig);
    then libvts, which libvts-decode has already loaded (its NEEDED entry)."""
    name = "libvts-decode.so.0"
    here = os.path.dirname(os.path.abspath(__file__))
    candidate = os.path.normpath(os.path.join(here, _paths.DECODE_LIBRARY_DIR, name))
    decode = ctypes.CDLL(candidate if os.path.exists(candidate) else name)
    return ctypes.CDLL("libvts.so.0"), decode


vts, decode = _load()
_P = ctypes.c_void_p
_U32 = ctypes.c_uint32
_ERR = ctypes.POINTER(Error)
_CM = ctypes.POINTER(Clipmap)
_RECT = ctypes.POINTER(TileRect)
_PU32 = ctypes.POINTER(ctypes.c_uint32)
_PD = ctypes.POINTER(ctypes.c_double)
for lib, fn, restype, argtypes in [
    (vts, "vts_open", _P, [ctypes.c_char_p, _ERR]),
    (vts, "vts_close", None, [_P]),
    (vts, "vts_store_geometry", ctypes.POINTER(Geometry), [_P]),
    (vts, "vts_store_layer", ctypes.POINTER(Layer), [_P, _U32]),
    (vts, "vts_store_level", ctypes.c_int, [_P, _U32, ctypes.POINTER(Level)]),
    (vts, "vts_store_meta_count", _U32, [_P]),
    (vts, "vts_store_meta_key", ctypes.c_char_p, [_P, _U32]),
    (vts, "vts_store_meta_value", ctypes.c_char_p, [_P, _U32]),
    (vts, "vts_status_name", ctypes.c_char_p, [ctypes.c_int]),
    (vts, "vts_sample_name", ctypes.c_char_p, [_U32]),
    (vts, "vts_colour_name", ctypes.c_char_p, [_U32]),
    (vts, "vts_codec_name", None, [_U32, ctypes.c_char * 5]),
    (vts, "vts_version_string", ctypes.c_char_p, []),
    (vts, "vts_full_level_count", _U32, [_U32, _U32, _U32]),
    (vts, "vts_clipmap_init", ctypes.c_int, [_CM, ctypes.POINTER(Geometry), _U32, _ERR]),
    (vts, "vts_clipmap_free", None, [_CM]),
    (vts, "vts_clipmap_window", ctypes.c_int,
     [_CM, _U32, ctypes.c_double, ctypes.c_double, _RECT]),
    (vts, "vts_clipmap_slot", None, [_CM, _U32, _U32, _PU32, _PU32]),
    (vts, "vts_clipmap_strips", _U32, [_RECT, _RECT, _RECT]),
    (vts, "vts_clipmap_move", ctypes.c_int, [_CM, _U32, _RECT]),
    (vts, "vts_clipmap_plan", _U32, [_CM, ctypes.POINTER(ClipmapTile), _U32]),
    (vts, "vts_clipmap_pending", ctypes.c_uint64, [_CM]),
    (vts, "vts_clipmap_loaded", ctypes.c_int, [_CM, ctypes.POINTER(ClipmapTile)]),
    (vts, "vts_clipmap_complete", ctypes.c_bool, [_CM, _U32]),
    (vts, "vts_clipmap_valid", None, [_CM, _U32, ctypes.c_double] + [_PD] * 4),
    (decode, "vts_decode_texel_bytes", ctypes.c_size_t, [_P, _U32]),
    (decode, "vts_decode_check", ctypes.c_int, [_P, _U32, _ERR]),
    (decode, "vts_decode_tile", ctypes.c_int,
     [_P, _U32, _U32, _U32, _U32, ctypes.c_uint, _P, ctypes.c_size_t, ctypes.c_size_t, _ERR]),
    (decode, "vts_decode_region", ctypes.c_int,
     [_P, _U32, _U32, _U32, _U32, _U32, _U32, ctypes.c_uint, _P, ctypes.c_size_t,
      ctypes.c_size_t, _ERR]),
]:
    f = getattr(lib, fn)
    f.restype = restype
    f.argtypes = argtypes
