#!/usr/bin/env python3
"""A reference for what vt-offset's cutting must give, to show that the checkers accept a correct
cut (run.sh selftest): every textured face is clipped along every integer u and v line it crosses,
and every face sharing a cut edge gets the cut points as extra corners. Its own atlas layout
replicates each material's texture over the material's whole UV range (no move, no wrap), so
vt-tiles --layout builds the store it needs from the original textures. Uses no vtpipe code.

  ref_cut.py SCENE.obj OUT_DIR [--no-split]

writes OUT_DIR/atlas.json (paths relative to it) and OUT_DIR/cut.obj (positions first as in the
scene, new ones appended; one vt per corner on the atlas). --no-split leaves the neighbours of cut
faces as they are (T-junctions: what check_watertight must refuse).
"""

import json
import math
import os
import sys

import PIL.Image

import scene_io

EPS = 1e-9


class Builder:
    def __init__(self, obj):
        self.obj = obj
        self.pos = [tuple(p) for p in obj.positions]
        self.keyed = {}

    def vertex(self, key, p):
        if key not in self.keyed:
            self.keyed[key] = len(self.pos)
            self.pos.append(tuple(p))
        return self.keyed[key]


def lerp(a, b, s):
    return tuple(x + s * (y - x) for x, y in zip(a, b))


def crossings(x0, x1):
    """Integers strictly between x0 and x1."""
    lo, hi = min(x0, x1), max(x0, x1)
    return [k for k in range(math.floor(lo + EPS) + 1, math.ceil(hi - EPS)) if lo + EPS < k < hi - EPS]


def edge_cuts(obj, own_only):
    """{(a, b) a < b: sorted params t in (0, 1) from a}, from the textured faces' UVs."""
    T = obj.texcoords
    cuts = {}
    for fi, f in enumerate(obj.faces):
        if f.vt is None:
            continue
        n = len(f.v)
        for i in range(n):
            j = (i + 1) % n
            a, b, ua, ub = f.v[i], f.v[j], T[f.vt[i]], T[f.vt[j]]
            if a > b:
                a, b, ua, ub = b, a, ub, ua
            for ax in (0, 1):
                for k in crossings(ua[ax], ub[ax]):
                    t = (k - ua[ax]) / (ub[ax] - ua[ax])
                    key = (a, b) if not own_only else (a, b, fi)
                    cuts.setdefault(key, set()).add(t)
    out = {}
    for key, ts in cuts.items():
        merged = []
        for t in sorted(ts):
            if not merged or t - merged[-1] > 1e-9:
                merged.append(t)
        out[key] = merged
    return out


def refine(bld, fi, f, cuts, own_only):
    """The face's corners with the cut points of its edges: [(position id, uv or None)]."""
    T, P = bld.obj.texcoords, bld.obj.positions
    n, out = len(f.v), []
    for i in range(n):
        j = (i + 1) % n
        a, b = f.v[i], f.v[j]
        uvi = tuple(T[f.vt[i]]) if f.vt else None
        uvj = tuple(T[f.vt[j]]) if f.vt else None
        out.append((a, uvi))
        lo, hi = min(a, b), max(a, b)
        ts = cuts.get((lo, hi, fi) if own_only else (lo, hi), [])
        ss = [t if a == lo else 1 - t for t in ts]
        for s, t in sorted(zip(ss, ts)):
            vid = bld.vertex(("e", lo, hi, t), lerp(P[lo], P[hi], t))
            out.append((vid, lerp(uvi, uvj, s) if uvi else None))
    return out


def uv_to_pos(bld, f, uv):
    """The position at uv on face f (its UVs are an affine function of its position)."""
    T, P = bld.obj.texcoords, bld.obj.positions
    for _, i, j in scene_io.fan(f.v):
        a, b, c = T[f.vt[0]], T[f.vt[i]], T[f.vt[j]]
        den = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1])
        if abs(den) < 1e-14:
            continue
        wb = ((uv[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (uv[1] - a[1])) / den
        wc = ((b[0] - a[0]) * (uv[1] - a[1]) - (uv[0] - a[0]) * (b[1] - a[1])) / den
        return tuple((1 - wb - wc) * P[f.v[0]] + wb * P[f.v[i]] + wc * P[f.v[j]])
    raise ValueError("face line %d has no UV area" % f.line)


def clip(poly, ax, k, keep_above):
    """Sutherland-Hodgman against the line uv[ax] = k; vertices are (id or None, uv)."""
    def inside(v):
        return v[1][ax] >= k - EPS if keep_above else v[1][ax] <= k + EPS
    out = []
    for i, cur in enumerate(poly):
        prev = poly[i - 1]
        if inside(cur):
            if not inside(prev):
                out.append(intersect(prev, cur, ax, k))
            out.append(cur)
        elif inside(prev):
            out.append(intersect(prev, cur, ax, k))
    return out


def intersect(p, q, ax, k):
    s = (k - p[1][ax]) / (q[1][ax] - p[1][ax])
    uv = lerp(p[1], q[1], s)
    uv = tuple(k if a == ax else x for a, x in enumerate(uv))
    return (None, uv)


def pieces(bld, fi, f, ref):
    us = [c[1][0] for c in ref]
    vs = [c[1][1] for c in ref]
    known = {c[1]: c[0] for c in ref}
    out = []
    for a in range(math.floor(min(us) + EPS), max(math.floor(min(us) + EPS) + 1,
                                                  math.ceil(max(us) - EPS))):
        for b in range(math.floor(min(vs) + EPS), max(math.floor(min(vs) + EPS) + 1,
                                                      math.ceil(max(vs) - EPS))):
            poly = ref
            for ax, k, above in ((0, a, True), (0, a + 1, False), (1, b, True), (1, b + 1, False)):
                poly = clip(poly, ax, k, above)
                if not poly:
                    break
            corners = []
            for vid, uv in poly:
                if vid is None:
                    near = [i for u, i in known.items() if abs(u[0] - uv[0]) < 1e-7
                            and abs(u[1] - uv[1]) < 1e-7]
                    if near:
                        vid = near[0]
                    else:
                        ku, kv = round(uv[0]), round(uv[1])
                        if abs(uv[0] - ku) > 1e-7 or abs(uv[1] - kv) > 1e-7:
                            raise ValueError("face line %d: a clipped corner at uv %r is neither "
                                             "a corner nor a line crossing" % (f.line, uv))
                        vid = bld.vertex(("i", fi, ku, kv), uv_to_pos(bld, f, (ku, kv)))
                if not corners or corners[-1][0] != vid:
                    corners.append((vid, uv))
            while len(corners) > 1 and corners[0][0] == corners[-1][0]:
                corners.pop()
            area = 0.0
            for i in range(len(corners)):
                (u0, v0), (u1, v1) = corners[i - 1][1], corners[i][1]
                area += u0 * v1 - u1 * v0
            if len(corners) >= 3 and abs(area) > 1e-12:
                out.append(corners)
    return out


def layout(obj, out_dir):
    """A layout with every used material's texture replicated over its UV range."""
    mats = scene_io.read_mtl([os.path.join(os.path.dirname(obj.path), m) for m in obj.mtllibs])
    ranges = {}
    for f in obj.faces:
        if f.vt is None or f.mtl is None:
            continue
        r = ranges.setdefault(f.mtl, [math.inf, -math.inf, math.inf, -math.inf])
        for t in f.vt:
            u, v = obj.texcoords[t]
            r[0], r[1], r[2], r[3] = min(r[0], u), max(r[1], u), min(r[2], v), max(r[3], v)
    entries, x, y, row_h, width = [], 0, 0, 0, 0
    for name in ranges:  # in order of first use
        r = ranges[name]
        ou, ov = math.floor(r[0] + 1e-6), math.floor(r[2] + 1e-6)
        ru, rv = max(1, math.ceil(r[1] - 1e-6) - ou), max(1, math.ceil(r[3] - 1e-6) - ov)
        m = mats.get(name)
        path = m["map_kd"] if m else None
        if path and os.path.exists(path):
            w, h = PIL.Image.open(path).size
            tex = {"path": os.path.relpath(path, out_dir), "width": w, "height": h}
        else:
            w = h = 1
            ru, rv = math.ceil(r[1]) - ou + 1, math.ceil(r[3]) - ov + 1
            k = (m["kd"] if m and m["kd"] else [0.8] * 3)
            tex = {"fill": [min(1, max(0, c)) for c in k] + [1.0]}
        cw, ch = w * ru, h * rv
        if x > 0 and x + cw > 4096:
            x, y, row_h = 0, y + row_h, 0
        entries.append({"name": name, "x": x, "y": y, "width": w, "height": h,
                        "repeat": [ru, rv], "origin": [ou, ov], "cell_width": cw,
                        "cell_height": ch, "alignment": 1, "scale": 1.0, "textures": [tex]})
        x += cw
        width, row_h = max(width, x), max(row_h, ch)
    return {"format": "vtpipe-atlas", "version": 1, "generator": "ref_cut.py",
            "width": width, "height": y + row_h, "tile_content": 256, "border": 4,
            "layers": [{"name": "diffuse", "map": "map_Kd", "colour": "srgb"}],
            "entries": entries}


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    own_only = "--no-split" in sys.argv
    obj = scene_io.Obj(args[0])
    out_dir = args[1]
    lay = layout(obj, out_dir)
    by_name = {e["name"]: e for e in lay["entries"]}
    AW, AH = lay["width"], lay["height"]

    def atlas_uv(mtl, uv):
        e = by_name[mtl]
        U = (e["x"] + (uv[0] - e["origin"][0]) * e["width"]) / AW
        V = 1 - (e["y"] + (e["repeat"][1] - (uv[1] - e["origin"][1])) * e["height"]) / AH
        return U, V

    cuts = edge_cuts(obj, own_only)
    bld = Builder(obj)
    faces, cut = [], 0  # (usemtl ordinal, [(pos id, atlas uv or None)])
    for fi, f in enumerate(obj.faces):
        ref = refine(bld, fi, f, cuts, own_only)
        if f.vt is None:
            faces.append((f.mtl_ordinal, [(v, None) for v, _ in ref]))
            continue
        ps = pieces(bld, fi, f, ref)
        cut += len(ps) > 1
        for p in ps:
            faces.append((f.mtl_ordinal, [(v, atlas_uv(f.mtl, uv)) for v, uv in p]))
    with open(os.path.join(out_dir, "atlas.json"), "w") as fo:
        json.dump(lay, fo, indent=1)
    with open(os.path.join(out_dir, "cut.obj"), "w") as fo:
        fo.write("# ref_cut.py %s\n" % args[0])
        for p in bld.pos:
            fo.write("v %.17g %.17g %.17g\n" % p)
        cur, nvt = None, 0
        for ordinal, corners in faces:
            if ordinal != cur:
                fo.write("usemtl vt_atlas\n")
                cur = ordinal
            items = []
            for v, uv in corners:
                if uv is None:
                    items.append("%d" % (v + 1))
                    continue
                fo.write("vt %.17g %.17g\n" % uv)
                nvt += 1
                items.append("%d/%d" % (v + 1, nvt))
            fo.write("f %s\n" % " ".join(items))
    print("ref_cut.py: %d faces cut into %d faces, %d new positions%s"
          % (cut, len(faces), len(bld.pos) - len(obj.positions),
             " (neighbours not split)" if own_only else ""))
    return 0


if __name__ == "__main__":
    sys.exit(main())
