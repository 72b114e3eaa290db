"""Readers shared by check_texels.py and check_watertight.py: Wavefront OBJ and MTL text, and PNG
textures converted to the 8-bit layout a vtpipe store holds. Written from the file formats, not
from vtpipe's code (the checkers must not share its mistakes).

OBJ: v, vt (1 to 3 numbers, missing ones 0), vn, f (v, v/vt, v//vn, v/vt/vn; negative indices
relative to the lines read so far), usemtl, mtllib; '#' starts a comment, a '\\' at the end of a
line joins the next one, CRLF is accepted. Everything else is skipped.
"""

import math
import os
import struct
import zlib

import numpy as np
from PIL import Image


class ObjError(Exception):
    pass


class Face:
    __slots__ = ("line", "mtl", "mtl_ordinal", "v", "vt")

    def __init__(self, line, mtl, mtl_ordinal, v, vt):
        self.line = line  # 1-based line number in the file
        self.mtl = mtl  # material name (None before any usemtl)
        self.mtl_ordinal = mtl_ordinal  # index of the usemtl statement in force (-1: none)
        self.v = v  # 0-based position indices
        self.vt = vt  # 0-based texcoord indices, or None when a corner has none


class Obj:
    def __init__(self, path):
        self.path = path
        self.positions = []
        self.texcoords = []
        self.normals = 0
        self.faces = []
        self.mtllibs = []
        self.usemtl = []  # names, in order of the usemtl statements
        self._read()
        self.positions = np.array(self.positions, dtype=np.float64).reshape(-1, 3)
        self.texcoords = np.array(self.texcoords, dtype=np.float64).reshape(-1, 2)

    def _logical_lines(self):
        with open(self.path, "rb") as f:
            text = f.read().decode("utf-8", errors="replace")
        pending, start = None, 0
        for n, line in enumerate(text.split("\n"), 1):
            if line.endswith("\r"):
                line = line[:-1]
            if pending is not None:
                line = pending + " " + line
            else:
                start = n
            if line.endswith("\\"):
                pending = line[:-1]
                continue
            pending = None
            yield start, line

    def _index(self, tok, count, what, n):
        i = int(tok)
        if i > 0:
            i -= 1
        elif i < 0:
            i += count
        else:
            raise ObjError("%s:%d: %s index 0" % (self.path, n, what))
        if not 0 <= i < count:
            raise ObjError("%s:%d: %s index %s out of range (%d defined so far; a line further "
                           "down is a forward reference, which OBJ readers refuse)"
                           % (self.path, n, what, tok, count))
        return i

    def _read(self):
        mtl, ordinal = None, -1
        for n, line in self._logical_lines():
            toks = line.split()
            if not toks or toks[0].startswith("#"):
                continue
            key = toks[0]
            if key in ("usemtl", "mtllib"):
                rest = line.strip()[len(key):].strip()
                if key == "usemtl":
                    mtl, ordinal = rest, len(self.usemtl)
                    self.usemtl.append(rest)
                else:
                    self.mtllibs.extend(rest.split())
                continue
            args = []
            for t in toks[1:]:
                if t.startswith("#"):
                    break
                args.append(t)
            if key == "v":
                self.positions.extend(float(x) for x in args[:3])
            elif key == "vt":
                uv = [float(x) for x in args[:2]] + [0.0] * (2 - min(2, len(args)))
                self.texcoords.extend(uv)
            elif key == "vn":
                self.normals += 1
            elif key == "f":
                nv, nt = len(self.positions) // 3, len(self.texcoords) // 2
                vs, ts = [], []
                for c in args:
                    parts = c.split("/")
                    vs.append(self._index(parts[0], nv, "vertex", n))
                    if len(parts) > 1 and parts[1] != "":
                        ts.append(self._index(parts[1], nt, "texture", n))
                    else:
                        ts.append(None)
                if len(vs) < 3:
                    raise ObjError("%s:%d: face with %d corners" % (self.path, n, len(vs)))
                vt = ts if all(t is not None for t in ts) else None
                self.faces.append(Face(n, mtl, ordinal, vs, vt))


def read_mtl(paths):
    """Materials of the MTL files (first definition of a name wins): name -> dict with 'kd'
    (3 floats or None) and 'map_kd' (the resolved path or None), 'map_kd_line' ('file:line')."""
    mats = {}
    for path in paths:
        try:
            with open(path, "rb") as f:
                lines = f.read().decode("utf-8", errors="replace").split("\n")
        except OSError:
            continue
        cur = None
        base = os.path.dirname(path)
        for n, line in enumerate(lines, 1):
            toks = line.split()
            if not toks or toks[0].startswith("#"):
                continue
            if toks[0] == "newmtl":
                name = line.strip()[len("newmtl"):].strip()
                cur = None if name in mats else {"kd": None, "map_kd": None}
                if cur is not None:
                    mats[name] = cur
            elif cur is None:
                continue
            elif toks[0] == "Kd" and len(toks) >= 2:
                vals = [float(x) for x in toks[1:4]]
                cur["kd"] = vals * 3 if len(vals) == 1 else vals
            elif toks[0] == "map_Kd" and len(toks) >= 2:
                p = toks[-1].replace("\\", "/")
                cur["map_kd"] = p if os.path.isabs(p) else os.path.join(base, p)
                cur["map_kd_line"] = "%s:%d" % (path, n)
    return mats


def _png_header(path):
    with open(path, "rb") as f:
        head = f.read(33)
    if head[:8] != b"\x89PNG\r\n\x1a\n":
        return None
    w, h, depth, ctype, _, _, interlace = struct.unpack(">IIBBBBB", head[16:29])
    return w, h, depth, ctype, interlace


def _paeth(a, b, c):
    p = a + b - c
    pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
    if pa <= pb and pa <= pc:
        return a
    return b if pb <= pc else c


def _read_png16(path):
    """A 16-bit, non-interlaced grey / grey+alpha / RGB / RGBA PNG as uint16 (H, W, C): PIL reduces
    16-bit colour to 8 bits by truncation, so it is decoded here from the format."""
    with open(path, "rb") as f:
        data = f.read()
    pos, idat = 8, []
    w = h = depth = ctype = interlace = None
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            w, h, depth, ctype, _, _, interlace = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat.append(body)
        elif kind == b"IEND":
            break
        pos += 12 + n
    ch = {0: 1, 4: 2, 2: 3, 6: 4}[ctype]
    if depth != 16 or interlace:
        raise ValueError("%s: not a 16-bit non-interlaced PNG" % path)
    raw = zlib.decompress(b"".join(idat))
    bpp, stride = 2 * ch, 2 * ch * w
    out = np.zeros((h, stride), dtype=np.int64)
    prev = np.zeros(stride, dtype=np.int64)
    for y in range(h):
        ft = raw[y * (stride + 1)]
        row = np.frombuffer(raw, dtype=np.uint8, count=stride, offset=y * (stride + 1) + 1)
        row = row.astype(np.int64)
        if ft == 0:
            cur = row
        elif ft == 1:
            cur = np.cumsum(row.reshape(w, bpp), axis=0).reshape(stride) & 255
        elif ft == 2:
            cur = (row + prev) & 255
        else:
            cur = row.copy()
            for i in range(stride):
                a = cur[i - bpp] if i >= bpp else 0
                c = prev[i - bpp] if i >= bpp else 0
                pred = (a + prev[i]) // 2 if ft == 3 else _paeth(a, prev[i], c)
                cur[i] = (cur[i] + pred) & 255
        out[y] = cur
        prev = cur
    v = out.reshape(h, w, ch, 2)
    return (v[..., 0] * 256 + v[..., 1]).astype(np.uint16)


def read_texture(path):
    """The texture's texels as 8-bit values (H, W, C) with C 1 (grey), 2 (grey + alpha), 3 (RGB)
    or 4 (RGBA): palettes expanded (RGBA when they have tRNS), grey below 8 bits scaled to 8 bits,
    16-bit samples converted to round(v * 255 / 65535): a layer with a 16-bit texture keeps 16
    bits (docs/atlas-build.md), and read_store_image reduces its texels the same way."""
    head = _png_header(path)
    if head and head[2] == 16:
        v = _read_png16(path).astype(np.int64)
        return ((v * 255 + 32767) // 65535).astype(np.uint8)
    im = Image.open(path)
    if im.mode == "P":
        im = im.convert("RGBA" if "transparency" in im.info else "RGB")
    elif im.mode == "1":
        im = im.convert("L")
    elif im.mode in ("I;16", "I;16B", "I"):
        a = np.asarray(im).astype(np.int64)
        return ((a * 255 + 32767) // 65535).astype(np.uint8)[:, :, None]
    elif im.mode not in ("L", "LA", "RGB", "RGBA"):
        raise ValueError("%s: image mode %s not handled" % (path, im.mode))
    a = np.asarray(im)
    return a[:, :, None] if a.ndim == 2 else a


def to_store_layout(tex, store_channels):
    """tex (H, W, C) 8-bit as read_texture gives it, in the channels of the store layer: colour
    channels 1 (a grey store) or 3 (grey replicated), then alpha (the texture's, or 255)."""
    h, w, c = tex.shape
    colour = 1 if store_channels in (1, 2) else 3
    alpha = store_channels in (2, 4)
    if c in (1, 2):
        col = np.repeat(tex[:, :, :1], colour, axis=2)
    else:
        col = tex[:, :, :colour]
    if not alpha:
        return np.ascontiguousarray(col)
    a = tex[:, :, c - 1:c] if c in (2, 4) else np.full((h, w, 1), 255, dtype=np.uint8)
    return np.ascontiguousarray(np.concatenate([col, a], axis=2))


def fill_texel(kd, store_channels):
    """The constant vt-atlas fills a diffuse layer with for a material without a usable texture
    (docs/cli/vt-atlas.md, 'Constant fills': Kd, 0.8 grey without Kd; alpha 1), as 8-bit values
    (docs/atlas-build.md: floor(v * 255 + 0.5))."""
    k = kd if kd is not None else [0.8, 0.8, 0.8]
    vals = [int(min(1.0, max(0.0, x)) * 255.0 + 0.5) for x in k]
    colour = vals[:1] if store_channels in (1, 2) else vals[:3]
    return np.array(colour + ([255] if store_channels in (2, 4) else []), dtype=np.uint8)


def read_store_image(path):
    """The extracted store level (vt-info --extract) as uint8 (H, W, C). A layer with a 16-bit
    texture is a u16 layer (docs/atlas-build.md: 8-bit textures in it are v * 257) and extracts
    as a 16-bit PNG: reduced here as read_texture reduces 16-bit textures, round(v * 255 / 65535),
    which gives back v for the 8-bit textures' v * 257 (PIL would truncate)."""
    head = _png_header(path)
    if head and head[2] == 16:
        v = _read_png16(path).astype(np.int64)
        return ((v * 255 + 32767) // 65535).astype(np.uint8)
    im = Image.open(path)
    if im.mode not in ("L", "LA", "RGB", "RGBA"):
        raise ValueError("%s: image mode %s not handled" % (path, im.mode))
    a = np.asarray(im)
    return a[:, :, None] if a.ndim == 2 else a


def scene_diagonal(positions):
    if len(positions) == 0:
        return 1.0
    d = float(np.linalg.norm(positions.max(axis=0) - positions.min(axis=0)))
    return d if d > 0 else 1.0


def fan(face_v):
    """Fan triangles of a polygon's corners (corner 0 with each consecutive pair)."""
    return [(0, i, i + 1) for i in range(1, len(face_v) - 1)]


def floor_frac(x):
    f = math.floor(x)
    return f, x - f
