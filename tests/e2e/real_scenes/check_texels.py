#!/usr/bin/env python3
"""Checker A of tests/e2e/real_scenes: the store shows, at every sampled surface point, the texel
that the original scene shows there.

  check_texels.py ORIGINAL.obj OUTPUT.obj LEVEL0.png [--points N] [--seed S] [--no-corners]

ORIGINAL.obj is the scene as vt-atlas read it (its MTL and textures), OUTPUT.obj what vt-offset
wrote (scene.vt.obj), LEVEL0.png the store's level 0 (vt-info --extract 0 -o LEVEL0.png
scene.vts). Uses no vtpipe code: OBJ, MTL and PNG are read here (scene_io.py).

For each sample point: an output face with texture coordinates (uniformly), a fan triangle of it
(by area) and a uniform point P in it; P's atlas coordinate (U, V) by barycentric interpolation;
the original textured face containing P (a grid of original fan triangles' boxes, then
barycentrics in each candidate's plane with tolerance 1e-7 relative to the scene's size; among
several, the one containing P deepest); the original (u, v) at P; the original texel at column
floor(frac(u) W), row floor((1 - frac(v)) H) in the store's channel layout; the store texel at
column floor(U AW), row floor((1 - V) AH). They must be equal in every channel. Besides the N
random points, unless --no-corners, three points per output fan triangle near its corners
(weights 0.765, 0.136, 0.099): a texture coordinate moved by a texel moves those by 0.77 texel.

Points within 1e-3 texel of a texel edge in either image are skipped and counted. Faces whose
material has no texture (no map_Kd, or a map_Kd file that does not exist) are compared with the
constant vt-atlas fills them with (Kd; 0.8 grey without Kd): every store texel within 1e-3 texel
of the point (vt-offset may map a constant's coordinates to a texel corner). Exit 0 when every compared point
matches and at least half of the points were compared; 1 with the first mismatches otherwise;
2 on bad usage or unreadable input.
"""

import argparse
import math
import os
import sys

import numpy as np

import scene_io

EDGE = 1e-3  # texels


class Textures:
    """Per original material: its texels in the store's layout, or its constant fill."""

    def __init__(self, obj, store_channels):
        paths = [os.path.join(os.path.dirname(obj.path), m) for m in obj.mtllibs]
        self.mats = scene_io.read_mtl(paths)
        self.store_channels = store_channels
        self.cache = {}
        self.fills = 0

    def get(self, name):
        """(array H x W x C, None) for a texture, (None, texel) for a constant."""
        if name in self.cache:
            return self.cache[name]
        m = self.mats.get(name)
        path = m["map_kd"] if m else None
        if path and os.path.exists(path):
            tex = scene_io.to_store_layout(scene_io.read_texture(path), self.store_channels)
            r = (tex, None)
        else:
            r = (None, scene_io.fill_texel(m["kd"] if m else None, self.store_channels))
        self.cache[name] = r
        return r


class TriangleGrid:
    """The original textured faces' fan triangles, bucketed by their bounding boxes."""

    def __init__(self, obj, tol):
        tris, owner = [], []
        for fi, f in enumerate(obj.faces):
            if f.vt is None:
                continue
            for a, b, c in scene_io.fan(f.v):
                tris.append((a, b, c))
                owner.append(fi)
        self.obj = obj
        self.owner = np.array(owner, dtype=np.int64)
        idx = np.array(tris, dtype=np.int64).reshape(-1, 3)
        self.corners = idx  # indices into the face's corner list
        p = obj.positions
        fv = [obj.faces[o].v for o in owner]
        self.A = np.array([p[v[i[0]]] for v, i in zip(fv, tris)]).reshape(-1, 3)
        self.B = np.array([p[v[i[1]]] for v, i in zip(fv, tris)]).reshape(-1, 3)
        self.C = np.array([p[v[i[2]]] for v, i in zip(fv, tris)]).reshape(-1, 3)
        self.tol = tol
        lo = np.minimum(np.minimum(self.A, self.B), self.C) - tol
        hi = np.maximum(np.maximum(self.A, self.B), self.C) + tol
        self.origin = lo.min(axis=0) if len(lo) else np.zeros(3)
        ext = (hi.max(axis=0) - self.origin) if len(hi) else np.ones(3)
        # about one triangle per cell along the scene's largest extent
        n = max(1, len(tris))
        self.cell = max(float(ext.max()) / max(1.0, n ** (1 / 2)), 1e-12)
        self.cells = {}
        a = np.floor((lo - self.origin) / self.cell).astype(np.int64)
        b = np.floor((hi - self.origin) / self.cell).astype(np.int64)
        for t in range(len(tris)):
            for x in range(a[t, 0], b[t, 0] + 1):
                for y in range(a[t, 1], b[t, 1] + 1):
                    for z in range(a[t, 2], b[t, 2] + 1):
                        self.cells.setdefault((x, y, z), []).append(t)
        self.lists = {k: np.array(v, dtype=np.int64) for k, v in self.cells.items()}

    def locate(self, P):
        """(triangle, barycentrics) of the triangle containing P deepest, or (None, None)."""
        key = tuple(int(k) for k in np.floor((P - self.origin) / self.cell))
        cand = self.lists.get(key)
        if cand is None:
            return None, None
        A, B, C = self.A[cand], self.B[cand], self.C[cand]
        v0, v1, v2 = B - A, C - A, P - A
        n = np.cross(v0, v1)
        nn = np.linalg.norm(n, axis=1)
        ok = nn > 0
        dist = np.abs(np.einsum("ij,ij->i", v2, n)) / np.where(ok, nn, 1)
        d00 = np.einsum("ij,ij->i", v0, v0)
        d01 = np.einsum("ij,ij->i", v0, v1)
        d11 = np.einsum("ij,ij->i", v1, v1)
        d20 = np.einsum("ij,ij->i", v2, v0)
        d21 = np.einsum("ij,ij->i", v2, v1)
        den = d00 * d11 - d01 * d01
        den = np.where(den != 0, den, 1)
        bv = (d11 * d20 - d01 * d21) / den
        bw = (d00 * d21 - d01 * d20) / den
        bu = 1 - bv - bw
        depth = np.minimum(np.minimum(bu, bv), bw)
        good = ok & (dist <= self.tol) & (depth >= -1e-7)
        if not good.any():
            return None, None
        k = int(np.argmax(np.where(good, depth, -np.inf)))
        return int(cand[k]), (bu[k], bv[k], bw[k])


def near_edge(x):
    f = x - math.floor(x)
    return f < EDGE or f > 1 - EDGE


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[1])
    ap.add_argument("original")
    ap.add_argument("output")
    ap.add_argument("level0")
    ap.add_argument("--points", type=int, default=2000)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--no-corners", action="store_true")
    ap.add_argument("--show", type=int, default=10, help="mismatches printed")
    a = ap.parse_args()
    try:
        orig = scene_io.Obj(a.original)
        out = scene_io.Obj(a.output)
        store = scene_io.read_store_image(a.level0)
    except (OSError, ValueError, scene_io.ObjError) as e:
        print("check_texels: %s" % e, file=sys.stderr)
        return 2
    AH, AW, SC = store.shape
    tex = Textures(orig, SC)
    tol = 1e-7 * scene_io.scene_diagonal(orig.positions)
    grid = TriangleGrid(orig, tol)

    # the output's fan triangles with texcoords, with their areas
    otris, oarea = [], []
    P, T = out.positions, out.texcoords
    for fi, f in enumerate(out.faces):
        if f.vt is None:
            continue
        for tri in scene_io.fan(f.v):
            p = [P[f.v[i]] for i in tri]
            otris.append((fi, tri))
            oarea.append(0.5 * np.linalg.norm(np.cross(p[1] - p[0], p[2] - p[0])))
    faces_with_vt = sorted({fi for fi, _ in otris})
    if not faces_with_vt:
        print("check_texels: '%s' has no face with texture coordinates" % a.output, file=sys.stderr)
        return 1
    by_face = {}
    for k, (fi, _) in enumerate(otris):
        by_face.setdefault(fi, []).append(k)

    rng = np.random.default_rng(a.seed)
    samples = []  # (output triangle, barycentric weights, kind)
    for _ in range(a.points):
        fi = faces_with_vt[int(rng.integers(len(faces_with_vt)))]
        ks = by_face[fi]
        w = np.array([oarea[k] for k in ks])
        k = ks[int(rng.choice(len(ks), p=w / w.sum()))] if w.sum() > 0 else ks[0]
        r1, r2 = rng.random(), rng.random()
        s1 = math.sqrt(r1)
        samples.append((k, (1 - s1, s1 * (1 - r2), s1 * r2), "random"))
    if not a.no_corners:
        for k in range(len(otris)):
            # weights away from simple fractions: corners often sit on texel edges
            w0, w1 = 0.7654321, 0.1357913  # no pair of them sums to a simple fraction
            w2 = 1 - w0 - w1
            for wts in ((w0, w1, w2), (w2, w0, w1), (w1, w2, w0)):
                samples.append((k, wts, "corner"))

    compared = skipped = against_fill = 0
    mismatches = []
    for k, wts, kind in samples:
        fi, tri = otris[k]
        f = out.faces[fi]
        pts = [P[f.v[i]] for i in tri]
        uvs = [T[f.vt[i]] for i in tri]
        p = wts[0] * pts[0] + wts[1] * pts[1] + wts[2] * pts[2]
        U, V = wts[0] * uvs[0] + wts[1] * uvs[1] + wts[2] * uvs[2]
        t, bary = grid.locate(p)
        where = "%s point (%.9g %.9g %.9g) of output face line %d" % (kind, *p, f.line)
        if t is None:
            mismatches.append("%s: no original textured face contains it" % where)
            continue
        of = orig.faces[int(grid.owner[t])]
        c = grid.corners[t]
        ouv = sum(bary[i] * orig.texcoords[of.vt[c[i]]] for i in range(3))
        ax, ay = U * AW, (1 - V) * AH
        img, fill = tex.get(of.mtl)
        if img is None:
            # a constant: every store texel the point touches (1, 2 or 4 of them: vt-offset may
            # put a constant's coordinates on a texel corner) must hold it
            texels = {(int(math.floor(x)), int(math.floor(y)))
                      for x in (ax - EDGE, ax + EDGE) for y in (ay - EDGE, ay + EDGE)}
            want, src = fill, "the constant of material '%s'" % of.mtl
            against_fill += 1
        else:
            if near_edge(ax) or near_edge(ay):
                skipped += 1
                continue
            H, W = img.shape[:2]
            _, fu = scene_io.floor_frac(ouv[0])
            _, fv = scene_io.floor_frac(ouv[1])
            tx, ty = fu * W, (1 - fv) * H
            if near_edge(tx) or near_edge(ty):
                skipped += 1
                continue
            col, row = min(int(tx), W - 1), min(int(ty), H - 1)
            want = img[row, col]
            src = "texel %d,%d of material '%s'" % (col, row, of.mtl)
            texels = {(int(math.floor(ax)), int(math.floor(ay)))}
        compared += 1
        for acol, arow in sorted(texels):
            if not (0 <= acol < AW and 0 <= arow < AH):
                mismatches.append("%s: atlas uv (%.9g %.9g) is outside the %dx%d atlas"
                                  % (where, U, V, AW, AH))
                break
            got = store[arow, acol]
            if not np.array_equal(got, want):
                mismatches.append(
                    "%s in original face line %d: original uv (%.9g %.9g) -> %s = %s, atlas uv "
                    "(%.9g %.9g) -> store texel %d,%d = %s"
                    % (where, of.line, ouv[0], ouv[1], src, list(int(x) for x in want), U, V,
                       acol, arow, list(int(x) for x in got)))
                break
    total = len(samples)
    print("check_texels: %s: %d points (%d random, %d near corners); compared %d (%d against "
          "constant fills), skipped %d within %g texel of a texel edge; %d mismatches"
          % (a.output, total, a.points, total - a.points, compared, against_fill, skipped,
             EDGE, len(mismatches)))
    for m in mismatches[:a.show]:
        print("  mismatch: " + m)
    if mismatches:
        return 1
    if compared * 2 < total:
        print("check_texels: fewer than half of the points were compared", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
