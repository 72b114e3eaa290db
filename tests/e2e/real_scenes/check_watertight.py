#!/usr/bin/env python3
"""Checker B of tests/e2e/real_scenes: rewriting the texture coordinates (and cutting faces) kept
the mesh's connectivity: no crack, no T-junction, no new boundary, nothing lost.

  check_watertight.py ORIGINAL.obj OUTPUT.obj [--tol T]

Faces are polygons; an edge is a pair of consecutive corners, undirected, keyed by position.
Positions are compared geometrically (within T times the scene's diagonal, default 1e-6): the
output's new vertices are appended `v` lines, and a cut point of an edge must be one position
shared by every face on that edge. Uses no vtpipe code (scene_io.py reads the OBJ text).

Checks, each failure printed with its edges (the first ones):
  1. every output edge that lies on an original edge (both its ends on that segment) is shared by
     as many output faces as that original edge is by original faces;
  2. an output edge on no original edge lies inside an original face (a cut through it) and is
     shared by exactly 2 output faces;
  3. the output edges on each original edge cover it exactly (the sum of their lengths is its
     length: nothing missing, nothing overlapping);
  4. the total area of the output faces is the original's (relative 1e-5: new positions are
     written rounded).
Exit 0 when all hold, 1 otherwise, 2 on bad usage or unreadable input.
"""

import argparse
import math
import sys

import numpy as np

import scene_io


def merge_positions(pos, tol):
    """Ids per position such that positions within tol get one id (a grid of cell tol)."""
    ids = np.empty(len(pos), dtype=np.int64)
    cells = {}
    reps = []
    for i, p in enumerate(pos):
        key = tuple(int(math.floor(x / tol)) for x in p)
        found = -1
        for dx in (-1, 0, 1):
            for dy in (-1, 0, 1):
                for dz in (-1, 0, 1):
                    for r in cells.get((key[0] + dx, key[1] + dy, key[2] + dz), ()):
                        if np.max(np.abs(reps[r] - p)) <= tol:
                            found = r
                            break
                    if found >= 0:
                        break
                if found >= 0:
                    break
            if found >= 0:
                break
        if found < 0:
            found = len(reps)
            reps.append(p)
            cells.setdefault(key, []).append(found)
        ids[i] = found
    return ids, np.array(reps).reshape(-1, 3)


def edges_of(obj, ids):
    """{(a, b) with a < b: [face lines]} over merged ids; degenerate edges (a == b) left out."""
    e = {}
    for f in obj.faces:
        n = len(f.v)
        for i in range(n):
            a, b = ids[f.v[i]], ids[f.v[(i + 1) % n]]
            if a != b:
                e.setdefault((min(a, b), max(a, b)), []).append(f.line)
    return e


def polygon_area(pts):
    s = np.zeros(3)
    for i in range(1, len(pts) - 1):
        s += np.cross(pts[i] - pts[0], pts[i + 1] - pts[0])
    return 0.5 * float(np.linalg.norm(s))


class SegmentGrid:
    def __init__(self, reps, edges, cell, tol):
        self.reps, self.cell = reps, cell
        self.edges = list(edges)
        self.cells = {}
        for k, (a, b) in enumerate(self.edges):
            lo = np.floor((np.minimum(reps[a], reps[b]) - tol) / cell).astype(np.int64)
            hi = np.floor((np.maximum(reps[a], reps[b]) + tol) / cell).astype(np.int64)
            for x in range(lo[0], hi[0] + 1):
                for y in range(lo[1], hi[1] + 1):
                    for z in range(lo[2], hi[2] + 1):
                        self.cells.setdefault((x, y, z), []).append(k)

    def containing(self, p, q, tol):
        """Original edges (index) whose segment holds both points p and q."""
        key = tuple(int(math.floor(x / self.cell)) for x in p)
        out = []
        for k in self.cells.get(key, ()):
            a, b = self.edges[k]
            if on_segment(p, self.reps[a], self.reps[b], tol) and on_segment(
                    q, self.reps[a], self.reps[b], tol):
                out.append(k)
        return out


def on_segment(p, a, b, tol):
    d = b - a
    L2 = float(d @ d)
    t = float((p - a) @ d) / L2 if L2 > 0 else 0.0
    if t < -tol / math.sqrt(L2) or t > 1 + tol / math.sqrt(L2):
        return False
    return float(np.linalg.norm(a + t * d - p)) <= tol


def inside_face(p, faces, pos, tol):
    """True when p lies inside (not on the boundary of) one of the original faces given."""
    for f in faces:
        pts = [pos[v] for v in f.v]
        for i in range(1, len(pts) - 1):
            a, b, c = pts[0], pts[i], pts[i + 1]
            n = np.cross(b - a, c - a)
            nn = float(np.linalg.norm(n))
            if nn == 0 or abs(float((p - a) @ n)) / nn > tol:
                continue
            v0, v1, v2 = b - a, c - a, p - a
            d00, d01, d11 = v0 @ v0, v0 @ v1, v1 @ v1
            d20, d21 = v2 @ v0, v2 @ v1
            den = d00 * d11 - d01 * d01
            bv = (d11 * d20 - d01 * d21) / den
            bw = (d00 * d21 - d01 * d20) / den
            if min(1 - bv - bw, bv, bw) >= -1e-9:
                return True
    return False


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[1])
    ap.add_argument("original")
    ap.add_argument("output")
    ap.add_argument("--tol", type=float, default=1e-6)
    ap.add_argument("--show", type=int, default=10, help="failures printed per check")
    a = ap.parse_args()
    try:
        orig = scene_io.Obj(a.original)
        out = scene_io.Obj(a.output)
    except (OSError, ValueError, scene_io.ObjError) as e:
        print("check_watertight: %s" % e, file=sys.stderr)
        return 2
    tol = a.tol * scene_io.scene_diagonal(orig.positions)
    # one id space for both meshes: a position of either that coincides is the same point
    allpos = np.concatenate([orig.positions, out.positions])
    ids, reps = merge_positions(allpos, tol)
    oid, nid = ids[:len(orig.positions)], ids[len(orig.positions):]
    oe = edges_of(orig, oid)
    ne = edges_of(out, nid)
    lengths = [float(np.linalg.norm(reps[b] - reps[a])) for a, b in oe]
    cell = max(float(np.median(lengths)) if lengths else 1.0, tol * 10)
    grid = SegmentGrid(reps, oe.keys(), cell, tol)
    okeys = grid.edges
    # original faces by the grid cell of their corners, for the inside test
    face_cells = {}
    for f in orig.faces:
        lo = np.floor((orig.positions[f.v].min(axis=0) - tol) / cell).astype(np.int64)
        hi = np.floor((orig.positions[f.v].max(axis=0) + tol) / cell).astype(np.int64)
        for x in range(lo[0], hi[0] + 1):
            for y in range(lo[1], hi[1] + 1):
                for z in range(lo[2], hi[2] + 1):
                    face_cells.setdefault((x, y, z), []).append(f)

    fails = {"count": [], "stray": [], "cover": [], "area": []}
    covered = [0.0] * len(okeys)
    interior = 0

    def where(e):
        p, q = reps[e[0]], reps[e[1]]
        return "(%.9g %.9g %.9g)-(%.9g %.9g %.9g)" % (*p, *q)

    for e, lines in ne.items():
        p, q = reps[e[0]], reps[e[1]]
        hits = grid.containing(p, q, tol)
        if hits:
            k = min(hits, key=lambda h: lengths[h])
            covered[k] += float(np.linalg.norm(q - p))
            want = len(oe[okeys[k]])
            if len(lines) != want:
                fails["count"].append(
                    "output edge %s is shared by %d faces (lines %s), the original edge it lies "
                    "on by %d (lines %s)" % (where(e), len(lines), lines[:6], want,
                                             oe[okeys[k]][:6]))
            continue
        mid = 0.5 * (p + q)
        key = tuple(int(math.floor(x / cell)) for x in mid)
        if inside_face(mid, face_cells.get(key, ()), orig.positions, tol):
            interior += 1
            if len(lines) != 2:
                fails["count"].append(
                    "output edge %s inside an original face is shared by %d faces (lines %s), "
                    "not 2" % (where(e), len(lines), lines[:6]))
        else:
            fails["stray"].append("output edge %s (face lines %s) lies on no original edge and "
                                  "inside no original face" % (where(e), lines[:6]))
    for k, e in enumerate(okeys):
        if abs(covered[k] - lengths[k]) > 1e-7 * lengths[k] + 2 * tol:
            fails["cover"].append("original edge %s (face lines %s, length %.9g): the output "
                                  "edges on it add up to %.9g" % (where(e), oe[e][:6], lengths[k],
                                                                  covered[k]))
    area_o = sum(polygon_area(orig.positions[f.v]) for f in orig.faces)
    area_n = sum(polygon_area(out.positions[f.v]) for f in out.faces)
    if abs(area_o - area_n) > 1e-5 * area_o:  # new positions are written rounded
        fails["area"].append("total face area %.12g, the original's %.12g" % (area_n, area_o))

    boundary = sum(1 for v in oe.values() if len(v) == 1)
    print("check_watertight: %s: %d faces, %d edges (%d on original edges, %d inside original "
          "faces); original %d faces, %d edges (%d boundary); %d failures"
          % (a.output, len(out.faces), len(ne), len(ne) - interior - len(fails["stray"]),
             interior, len(orig.faces), len(oe), boundary, sum(len(v) for v in fails.values())))
    names = {"count": "face count", "stray": "stray edge", "cover": "coverage", "area": "area"}
    for kind, msgs in fails.items():
        for m in msgs[:a.show]:
            print("  %s: %s" % (names[kind], m))
        if len(msgs) > a.show:
            print("  %s: ... %d more" % (names[kind], len(msgs) - a.show))
    return 1 if any(fails.values()) else 0


if __name__ == "__main__":
    sys.exit(main())
