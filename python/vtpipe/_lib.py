"""ctypes bindings of libvts (vts.h) and libvts-decode (vts_decode.h): the few functions the
package calls, their argument types, and where the libraries are found."""
import ctypes
import os

from . import _paths

ERROR_MESSAGE_MAX = 256
LAYER_NAME_BYTES = 32
STATUS_RANGE = -7
STATUS_ARG = -10
DECODE_NO_BORDER = 1 << 0


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
