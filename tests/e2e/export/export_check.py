#!/usr/bin/env python3
"""Checks a vt-export folder against vt-info --extract of the same store, independently of
vt-export's code: the tile grid, file names and descriptor of each layout are computed here from
the Deep Zoom, IIIF Image API 3.0 and XYZ conventions, and every tile of each given level must
equal the same rectangle of that level's extract, texel for texel (PNG tiles), or come within a
PSNR (--psnr, JPEG tiles).

  export_check.py DIR --layout dzi|iiif|xyz --levels J:EXTRACT.png [J:EXTRACT.png ...]
                  [--name NAME] [--psnr DB] [--coarse J:EXTRACT.png]

J is the store level (the full image reduced 2^J times). --coarse (Deep Zoom, an 8-bit sRGB
RGB layer): the levels coarser than J, which the store does not have, must be within 1 code of
a reduction written here: 2x2 box means in linear light, an odd edge's last texel repeated
(clamped), kept in floats, from the extract of level J. Prints one "ok ..." line per level and
exits 0, or prints what differs first and exits 1. Every file of DIR must be one the layout
names (no missing, no extra tiles)."""
import argparse
import json
import math
import os
import re
import sys
import xml.etree.ElementTree as ET

import numpy as np
from PIL import Image


def ceil_shift(v, j):
    return max(1, -(-v // (1 << j)))


def dzi_plan(d, name):
    root = ET.parse(os.path.join(d, name + ".dzi")).getroot()
    ns = "{http://schemas.microsoft.com/deepzoom/2008}"
    size = root.find(ns + "Size")
    w, h = int(size.get("Width")), int(size.get("Height"))
    t, o, fmt = int(root.get("TileSize")), int(root.get("Overlap")), root.get("Format")
    top = math.ceil(math.log2(max(w, h))) if max(w, h) > 1 else 0
    tiles = []
    for k in range(top + 1):
        j = top - k
        lw, lh = ceil_shift(w, j), ceil_shift(h, j)
        for r in range(-(-lh // t)):
            for c in range(-(-lw // t)):
                x0, y0 = max(c * t - o, 0), max(r * t - o, 0)
                x1, y1 = min((c + 1) * t + o, lw), min((r + 1) * t + o, lh)
                tiles.append((f"{name}_files/{k}/{c}_{r}.{fmt}", j, (x0, y0, x1, y1), None))
    return tiles, [name + ".dzi"]


def iiif_plan(d):
    info = json.load(open(os.path.join(d, "info.json")))
    assert info["type"] == "ImageService3" and info["profile"] == "level0", "not IIIF 3 level 0"
    w, h = info["width"], info["height"]
    tile = info["tiles"][0]
    t, factors = tile["width"], tile["scaleFactors"]
    ext = "png" if os.path.exists(os.path.join(d, "full")) and any(
        f.endswith(".png") for _, _, fs in os.walk(d) for f in fs) else "jpg"
    tiles = []
    for s in factors:
        j = int(math.log2(s))
        lw, lh = ceil_shift(w, j), ceil_shift(h, j)
        span = t * s
        for r in range(-(-lh // t)):
            for c in range(-(-lw // t)):
                rx, ry = c * span, r * span
                rw, rh = min(span, w - rx), min(span, h - ry)
                x0, y0 = c * t, r * t
                x1, y1 = min(x0 + t, lw), min(y0 + t, lh)
                region = "full" if (rx, ry, rw, rh) == (0, 0, w, h) else f"{rx},{ry},{rw},{rh}"
                size = "max" if (x1 - x0, y1 - y0) == (w, h) else f"{x1 - x0},{y1 - y0}"
                tiles.append((f"{region}/{size}/0/default.{ext}", j, (x0, y0, x1, y1), None))
    for s in info["sizes"]:
        j = round(math.log2(w / s["width"]))
        assert (ceil_shift(w, j), ceil_shift(h, j)) == (s["width"], s["height"]), "sizes"
        assert f"full/{s['width']},{s['height']}/0/default.{ext}" in {p for p, *_ in tiles}
    return tiles, ["info.json"]


def xyz_plan(d, w, h, t, ext):
    tiles = []
    top = 0
    while ceil_shift(w, top) > t or ceil_shift(h, top) > t:
        top += 1
    for z in range(top + 1):
        j = top - z
        lw, lh = ceil_shift(w, j), ceil_shift(h, j)
        for r in range(-(-lh // t)):
            for c in range(-(-lw // t)):
                rect = (c * t, r * t, min((c + 1) * t, lw), min((r + 1) * t, lh))
                tiles.append((f"{z}/{c}/{r}.{ext}", j, rect, t))
    return tiles, []


def srgb_to_linear(c):
    c = c / 255.0
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)


def linear_to_srgb(v):
    return np.where(v <= 0.0031308, v * 12.92, 1.055 * v ** (1 / 2.4) - 0.055) * 255


def box_half(a):
    h, w = a.shape[:2]
    ys, xs = np.arange((h + 1) // 2), np.arange((w + 1) // 2)
    y0, y1 = 2 * ys, np.minimum(2 * ys + 1, h - 1)
    x0, x1 = 2 * xs, np.minimum(2 * xs + 1, w - 1)
    return (a[y0][:, x0] + a[y0][:, x1] + a[y1][:, x0] + a[y1][:, x1]) / 4


def check_coarse(tiles, spec, d):
    j, path = spec.split(":", 1)
    j = int(j)
    levels = {}
    for p, tj, rect, _ in tiles:
        levels.setdefault(tj, []).append((p, rect))
    a = srgb_to_linear(np.asarray(Image.open(path).convert("RGB")).astype(np.float64))
    for k in range(j + 1, max(levels) + 1):
        a = box_half(a)
        want = np.round(linear_to_srgb(a))
        for p, (x0, y0, x1, y1) in levels[k]:
            got = np.asarray(Image.open(os.path.join(d, p)).convert("RGB")).astype(np.float64)
            ref = want[y0:y1, x0:x1]
            if got.shape != ref.shape or np.abs(got - ref).max() > 1:
                print(f"{p}: not the reduction of level {j} "
                      f"({got.shape[1]}x{got.shape[0]}, expected {ref.shape[1]}x{ref.shape[0]})")
                return False
    print(f"ok levels {j + 1}..{max(levels)}: within 1 code of the box reduction of level {j} "
          "in linear light")
    return True


def psnr(a, b):
    mse = np.mean((a.astype(np.float64) - b.astype(np.float64)) ** 2)
    return float("inf") if mse == 0 else 10 * math.log10(255.0 ** 2 / mse)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("dir")
    ap.add_argument("--layout", required=True, choices=["dzi", "iiif", "xyz"])
    ap.add_argument("--levels", nargs="+", required=True)
    ap.add_argument("--name")
    ap.add_argument("--psnr", type=float)
    ap.add_argument("--xyz", help="W,H,TILE,EXT of an XYZ export (it has no descriptor)")
    ap.add_argument("--coarse")
    a = ap.parse_args()
    extracts = {}
    for spec in a.levels:
        j, path = spec.split(":", 1)
        extracts[int(j)] = np.asarray(Image.open(path))
    if a.layout == "dzi":
        tiles, extra = dzi_plan(a.dir, a.name)
    elif a.layout == "iiif":
        tiles, extra = iiif_plan(a.dir)
    else:
        w, h, t, ext = a.xyz.split(",")
        tiles, extra = xyz_plan(a.dir, int(w), int(h), int(t), ext)
    on_disk = {os.path.relpath(os.path.join(p, f), a.dir)
               for p, _, fs in os.walk(a.dir) for f in fs}
    on_disk -= {"index.html", "openseadragon.min.js"}
    expected = {p for p, *_ in tiles} | set(extra)
    if on_disk != expected:
        missing, surplus = sorted(expected - on_disk), sorted(on_disk - expected)
        print(f"files differ: missing {missing[:3]} ({len(missing)}), "
              f"extra {surplus[:3]} ({len(surplus)})")
        return 1
    for j, ref in sorted(extracts.items()):
        worst, count = float("inf"), 0
        for path, tj, (x0, y0, x1, y1), pad in tiles:
            if tj != j:
                continue
            got = np.asarray(Image.open(os.path.join(a.dir, path)))
            want = ref[y0:y1, x0:x1]
            if pad:
                full = np.zeros((pad, pad) + want.shape[2:], want.dtype)
                full[: y1 - y0, : x1 - x0] = want
                want = full
            if got.shape != want.shape:
                print(f"{path}: {got.shape[1]}x{got.shape[0]}, expected "
                      f"{want.shape[1]}x{want.shape[0]}")
                return 1
            if a.psnr is None and not np.array_equal(got, want):
                diff = np.argwhere(np.any(np.atleast_3d(got != want), axis=2))[0]
                print(f"{path}: texel {diff[1]},{diff[0]} differs from level {j} at "
                      f"{x0 + diff[1]},{y0 + diff[0]}")
                return 1
            if a.psnr is not None:
                p = psnr(got, want)
                worst = min(worst, p)
                if p < a.psnr:
                    print(f"{path}: PSNR {p:.1f} dB < {a.psnr} dB against level {j}")
                    return 1
            count += 1
        if count == 0:
            print(f"level {j}: no tiles")
            return 1
        how = "exact" if a.psnr is None else f"PSNR >= {a.psnr} dB"
        print(f"ok level {j}: {count} tiles equal the extract ({how})")
    print(f"ok {len(expected)} files, as the {a.layout} layout names them")
    if a.coarse and not check_coarse(tiles, a.coarse, a.dir):
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
