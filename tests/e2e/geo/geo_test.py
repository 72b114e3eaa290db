#!/usr/bin/env python3
"""GDAL input end to end (docs/geospatial.md), inputs made with GDAL's own tools.

geo_test.py TOOLS_DIR WORK_DIR bands|vrt-rss [sanitized]

bands:   a 6-band u16 GeoTIFF (333x211, band descriptions, nodata 0 over a corner) becomes layers
         4+2 (and 6 with --band-layers) that round-trip exactly through vt-info --extract; the
         store's georeferencing in vt-info --json equals gdalinfo -json's; the nodata corner tile
         is empty; a JPEG 2000 input; the missing-module error. Negative controls: a shifted band,
         a wrong geotransform and another CRS fail the comparisons.
vrt-rss: a VRT mosaic of 16 GeoTIFF tiles, 2048^2 and 4096^2: peak RSS of vt-tiles flat in the
         mosaic's area and within the bound of a single GeoTIFF of the same size; with GDAL's
         block cache unbounded the same check fails (the check can see growth).
"sanitized" (an ASan build): the RSS figures are printed, not checked (ASan's shadow memory and
quarantine grow with what the process allocates). Exit 77 (skipped) when GDAL's command-line
tools are missing."""
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

import numpy as np

TOOLS, WORK, WHAT = sys.argv[1], sys.argv[2], sys.argv[3]
SANITIZED = sys.argv[4:] == ["sanitized"]
failures = []


def check(ok, what):
    print(("ok:   " if ok else "FAIL: ") + what)
    if not ok:
        failures.append(what)


def run(*args, env=None, expect=0):
    p = subprocess.run(args, capture_output=True, text=True, env=env)
    if p.returncode != expect:
        sys.exit("%s: exit %d, expected %d\n%s" % (" ".join(args), p.returncode, expect,
                                                   p.stderr))
    return p


def tool(name):
    return os.path.join(TOOLS, name)


def write_envi(path, bands, names=None):
    """bands: (n, h, w) array of uint8/uint16/float32, as an ENVI file GDAL reads."""
    n, h, w = bands.shape
    types = {np.dtype(np.uint8): 1, np.dtype(np.uint16): 12, np.dtype(np.float32): 4}
    bands.astype(bands.dtype.newbyteorder("<")).tofile(path)
    with open(path + ".hdr", "w") as f:
        f.write("ENVI\nsamples = %d\nlines = %d\nbands = %d\nheader offset = 0\n"
                "file type = ENVI Standard\ndata type = %d\ninterleave = bsq\nbyte order = 0\n"
                % (w, h, n, types[bands.dtype]))
        if names:
            f.write("band names = {%s}\n" % ", ".join(names))


def read_raster(path):
    """Any raster GDAL reads, as an (n, h, w) array, through gdal_translate to ENVI."""
    out = path + ".envi"
    run("gdal_translate", "-q", "-of", "ENVI", "-co", "INTERLEAVE=BSQ", path, out)
    info = json.loads(run("gdalinfo", "-json", out).stdout)
    w, h = info["size"]
    dtype = {"Byte": np.uint8, "UInt16": np.uint16, "Float32": np.float32}[info["bands"][0]["type"]]
    return np.fromfile(out, dtype=dtype).reshape(len(info["bands"]), h, w)


def content(n, h, w, seed):
    """Hard content for exactness: noise over the full u16 range plus gradients and edges."""
    rng = np.random.default_rng(seed)
    y, x = np.mgrid[0:h, 0:w]
    a = rng.integers(1, 65536, size=(n, h, w), dtype=np.uint32)
    for b in range(n):
        a[b] = np.where((x // 7 + y // 5 + b) % 3 == 0, (x * 197 + y * 31 * (b + 1)) % 65535 + 1,
                        a[b])
    return a.astype(np.uint16)


def same_wkt(gdal_wkt, ours):
    return re.sub(r"\n\s*", "", gdal_wkt) == ours


def same_transform(ours, gdal):
    """gdalinfo -json prints 15 significant digits (0.01 for 0.010000000000000002, which the
    store keeps exactly): equal to 1e-13 of the value."""
    return (ours is not None and len(ours) == 6 and
            all(abs(a - b) <= 1e-13 * max(1.0, abs(b)) for a, b in zip(ours, gdal)))


def georef_matches(store_json, gdal_json):
    return (same_transform(store_json.get("geoTransform"), gdal_json["geoTransform"])
            and same_wkt(gdal_json["coordinateSystem"]["wkt"],
                         store_json.get("coordinateSystem", {}).get("wkt")))


def layer_of(store, layer, out, level=0):
    run(tool("vt-info"), "-q", "--extract", str(level), "--layer", str(layer), "-o", out, store)
    return read_raster(out)


def test_bands():
    names = ["coastal", "blue", "green", "red", "nir", "swir"]
    src = content(6, 211, 333, 18)
    src[:, :80, :80] = 0  # nodata over the first tile and its border
    write_envi(os.path.join(WORK, "six.bin"), src, names)
    six = os.path.join(WORK, "six.tif")
    run("gdal_translate", "-q", "-co", "TILED=YES", "-co", "BLOCKXSIZE=64", "-co", "BLOCKYSIZE=64",
        "-co", "COMPRESS=DEFLATE", "-a_srs", "EPSG:32633", "-a_ullr", "500000", "4000000",
        "503330", "3997890", "-a_nodata", "0", os.path.join(WORK, "six.bin"), six)
    gdal = json.loads(run("gdalinfo", "-json", six).stdout)
    check([b.get("description") for b in gdal["bands"]] == names, "GDAL kept the band names")

    store = os.path.join(WORK, "six.vts")
    run(tool("vt-tiles"), "-q", "--tile-size", "64", "--codec", "png", six, "-o", store)
    js = json.loads(run(tool("vt-info"), "--json", store).stdout)
    check([l["name"] for l in js["layers"]] == ["coastal+blue+green+red", "nir+swir"],
          "6 bands -> 2 layers named from the band descriptions: %s"
          % [l["name"] for l in js["layers"]])
    check([(l["channels"], l["sample"], l["colour"]) for l in js["layers"]]
          == [(4, "u16", "data"), (2, "u16", "data")], "layers are u16 data of 4 and 2 channels")
    back = np.concatenate([layer_of(store, 0, os.path.join(WORK, "l0.tif")),
                           layer_of(store, 1, os.path.join(WORK, "l1.tif"))])
    check(back.shape == src.shape and np.array_equal(back, src),
          "the 6 bands round-trip exactly across the 2 layers")
    shifted = back.copy()
    shifted[4] = np.roll(shifted[4], 1, axis=1)
    check(not np.array_equal(shifted, src), "control: a band shifted by one texel fails")
    check(georef_matches(js, gdal), "vt-info --json: geoTransform and CRS equal gdalinfo -json's")
    check(js.get("noDataValue") == 0.0, "vt-info --json: noDataValue 0")
    level0 = js["layers"][0]["levels"][0]
    check(level0["empty"] == 1, "the tile of the nodata corner is empty (%d empty)"
          % level0["empty"])
    text = run(tool("vt-info"), store).stdout
    check("crs:               WGS 84 / UTM zone 33N" in text and
          "georef:            origin 500000, 4000000; texel 10 x -10" in text,
          "vt-info shows the georeferencing")

    # written back: an extract gets .aux.xml and a world file that GDAL reads
    x1 = os.path.join(WORK, "x1.tif")
    run(tool("vt-info"), "-q", "--extract", "1", "--layer", "1", "-o", x1, store)
    got = json.loads(run("gdalinfo", "-json", x1).stdout)
    level1 = [500000.0, 20.0, 0.0, 4000000.0, 0.0, -20.0]
    check(same_transform(got.get("geoTransform"), level1) and
          same_wkt(got["coordinateSystem"]["wkt"], js["coordinateSystem"]["wkt"]) and
          [b.get("noDataValue") for b in got["bands"]] == [0.0, 0.0],
          "extract of level 1: GDAL reads its geotransform (20 m texels), CRS and nodata")
    check(not same_transform(got.get("geoTransform"), gdal["geoTransform"]),
          "control: level 0's geotransform is not level 1's")
    check(open(os.path.join(WORK, "x1.tfw")).read().split() ==
          ["20", "0", "0", "-20", "500010", "3999990"], "the world file holds texel centres")
    t11 = os.path.join(WORK, "t11.png")
    run(tool("vt-info"), "-q", "--extract", "0", "--tile", "1,1", "-o", t11, store)
    got = json.loads(run("gdalinfo", "-json", t11).stdout)
    check(same_transform(got.get("geoTransform"), [500620.0, 10.0, 0.0, 3999380.0, 0.0, -10.0]),
          "extract of tile 1,1 (payload from texel 62,62): its origin")

    # controls: another geotransform, another CRS
    moved = os.path.join(WORK, "moved.tif")
    run("gdal_translate", "-q", "-a_ullr", "500010", "4000000", "503340", "3997890", six, moved)
    check(not georef_matches(js, json.loads(run("gdalinfo", "-json", moved).stdout)),
          "control: a geotransform moved by one texel fails the comparison")
    other = os.path.join(WORK, "other.tif")
    run("gdal_translate", "-q", "-a_srs", "EPSG:32632", six, other)
    check(not georef_matches(js, json.loads(run("gdalinfo", "-json", other).stdout)),
          "control: another CRS fails the comparison")

    # --band-layers: one layer per band
    per = os.path.join(WORK, "per.vts")
    run(tool("vt-tiles"), "-q", "--tile-size", "64", "--codec", "raw", "--band-layers", six,
        "-o", per)
    js = json.loads(run(tool("vt-info"), "--json", per).stdout)
    check([l["name"] for l in js["layers"]] == names, "--band-layers: 6 layers, one per band")
    ok = all(np.array_equal(layer_of(per, b, os.path.join(WORK, "b%d.tif" % b))[0], src[b])
             for b in range(6))
    check(ok, "--band-layers: every band round-trips exactly")
    check(js["metadata"].get("layer.4.bands") == "5", "layer.4.bands = 5")

    # nodata 65535: the corner tile is empty and extracts as 65535 again
    dem = content(1, 211, 333, 21)
    dem[:, :80, :80] = 65535
    write_envi(os.path.join(WORK, "dem.bin"), dem)
    dem_tif = os.path.join(WORK, "dem.tif")
    run("gdal_translate", "-q", "-a_srs", "EPSG:32633", "-a_ullr", "500000", "4000000", "503330",
        "3997890", "-a_nodata", "65535", os.path.join(WORK, "dem.bin"), dem_tif)
    dstore = os.path.join(WORK, "dem.vts")
    run(tool("vt-tiles"), "-q", "--tile-size", "64", "--codec", "png", dem_tif, "-o", dstore)
    js = json.loads(run(tool("vt-info"), "--json", dstore).stdout)
    back = layer_of(dstore, 0, os.path.join(WORK, "dem_x.tif"))
    zero_filled = back.copy()
    zero_filled[:, :62, :62] = 0  # what an extract writing zeros for the empty tile would hold
    check(js["layers"][0]["levels"][0]["empty"] == 1 and np.array_equal(back, dem) and
          not np.array_equal(zero_filled, dem),
          "nodata 65535: the corner tile is empty and extracts as 65535 (zeros would fail)")

    # without nodata: no empty tile
    plain = os.path.join(WORK, "plain.tif")
    run("gdal_translate", "-q", "-a_nodata", "none", six, plain)
    run(tool("vt-tiles"), "-q", "--tile-size", "64", "--codec", "raw", plain, "-o", per)
    js = json.loads(run(tool("vt-info"), "--json", per).stdout)
    check(js["layers"][0]["levels"][0]["empty"] == 0 and "noDataValue" not in js,
          "control: without nodata the corner tile is stored")

    rgb = (content(3, 150, 190, 7) >> 8).astype(np.uint8)
    write_envi(os.path.join(WORK, "rgb.bin"), rgb)
    jp2_or_rgb_tif = os.path.join(WORK, "rgb.tif")
    run("gdal_translate", "-q", "-a_srs", "EPSG:4326", "-a_ullr", "10", "50", "11.9", "48.5",
        os.path.join(WORK, "rgb.bin"), jp2_or_rgb_tif)

    # a 3-band RGB GeoTIFF: pixels through libtiff, georeferencing through GDAL
    rstore = os.path.join(WORK, "rgb.vts")
    run(tool("vt-tiles"), "-q", "--tile-size", "64", "--codec", "png", jp2_or_rgb_tif, "-o", rstore)
    js = json.loads(run(tool("vt-info"), "--json", rstore).stdout)
    check(georef_matches(js, json.loads(run("gdalinfo", "-json", jp2_or_rgb_tif).stdout)) and
          js["layers"][0]["colour"] == "srgb" and
          np.array_equal(layer_of(rstore, 0, os.path.join(WORK, "rgb_x.tif")), rgb),
          "RGB GeoTIFF (native pixels): exact, srgb, georeferencing equals gdalinfo -json's")
    # a 4-band GeoTIFF whose 4th band is not alpha (RGB + near infrared, 0 over a whole tile):
    # through GDAL, a data layer whose zeros are texels
    rgbn = content(4, 150, 190, 9)
    rgbn[3, :, :100] = 0
    write_envi(os.path.join(WORK, "rgbn.bin"), rgbn)
    rgbn_tif = os.path.join(WORK, "rgbn.tif")
    run("gdal_translate", "-q", "-co", "PHOTOMETRIC=RGB", "-co", "ALPHA=NO", "-a_srs",
        "EPSG:4326", "-a_ullr", "10", "50", "11.9", "48.5", os.path.join(WORK, "rgbn.bin"),
        rgbn_tif)
    nstore = os.path.join(WORK, "rgbn.vts")
    run(tool("vt-tiles"), "-q", "--tile-size", "64", "--codec", "png", rgbn_tif, "-o", nstore)
    js = json.loads(run(tool("vt-info"), "--json", nstore).stdout)
    check(js["layers"][0]["colour"] == "data" and js["layers"][0]["levels"][0]["empty"] == 0 and
          np.array_equal(layer_of(nstore, 0, os.path.join(WORK, "rgbn_x.tif")), rgbn),
          "RGBN GeoTIFF: a 4-channel data layer, exact, no tile dropped where band 4 is 0")

    # the same in 2 shards joined by vt-merge: every level equals the single build's (the
    # band-4 zeros are texels in the shards' seams too), georeferencing kept
    single = os.path.join(WORK, "rgbn1.vts")
    parts = [os.path.join(WORK, "rgbn_s%d.vts" % i) for i in (1, 2)]
    merged = os.path.join(WORK, "rgbn_m.vts")
    opts = ["-q", "--tile-size", "32", "--codec", "raw"]
    run(tool("vt-tiles"), *opts, rgbn_tif, "-o", single)
    for i, part in enumerate(parts):
        run(tool("vt-tiles"), *opts, "--shard", "%d/2" % (i + 1), rgbn_tif, "-o", part)
    run(tool("vt-merge"), "-q", *parts, "-o", merged)
    js = json.loads(run(tool("vt-info"), "--json", merged).stdout)
    levels = [(layer_of(single, 0, os.path.join(WORK, "s%d.tif" % lv), lv),
               layer_of(merged, 0, os.path.join(WORK, "m%d.tif" % lv), lv))
              for lv in range(js["level_count"])]
    check(len(levels) > 2 and all(np.array_equal(a, b) for a, b in levels) and
          georef_matches(js, json.loads(run("gdalinfo", "-json", rgbn_tif).stdout)),
          "RGBN in 2 shards + vt-merge: every level equals the single build's, georef kept")
    bad = levels[0][0].copy()
    bad[3, 0, 0] ^= 1
    check(not np.array_equal(bad, levels[0][1]),
          "control: one texel of band 4 changed fails that comparison")

    # an input without georeferencing (a PNG, native): no geo metadata, no sidecars
    png = os.path.join(WORK, "rgb.png")
    run("gdal_translate", "-q", "-of", "PNG", os.path.join(WORK, "rgb.bin"), png)
    for f in (png + ".aux.xml",):
        if os.path.exists(f):
            os.remove(f)
    pstore = os.path.join(WORK, "png.vts")
    # GDAL is loaded only when met: not for a PNG, and for a GeoTIFF (LD_DEBUG lists the loads)
    env = dict(os.environ, LD_DEBUG="files")
    loads_png = run(tool("vt-tiles"), "-q", png, "-o", pstore, env=env).stderr
    loads_geo = run(tool("vt-tiles"), "-q", jp2_or_rgb_tif, "-o", pstore, env=env).stderr
    check("libgdal" not in loads_png and "libvt_gdal" not in loads_png and
          "libgdal" in loads_geo and "libvt_gdal" in loads_geo,
          "GDAL is mapped for a GeoTIFF, not for a PNG")
    run(tool("vt-tiles"), "-q", png, "-o", pstore)
    pext = os.path.join(WORK, "png_x.png")
    run(tool("vt-info"), "-q", "--extract", "0", "-o", pext, pstore)
    js = json.loads(run(tool("vt-info"), "--json", pstore).stdout)
    check("geoTransform" not in js and not os.path.exists(pext + ".aux.xml") and
          not os.path.exists(os.path.join(WORK, "png_x.pgw")),
          "a PNG input: no georeferencing, no sidecar files")
    # --band-layers on a file the native reader takes (the PNG): GDAL reads its bands, exactly
    bstore = os.path.join(WORK, "png_bands.vts")
    run(tool("vt-tiles"), "-q", "--band-layers", "--codec", "png", "--colour", "data", png, "-o",
        bstore)
    src_png = read_raster(png)
    js = json.loads(run(tool("vt-info"), "--json", bstore).stdout)
    ok = all(np.array_equal(layer_of(bstore, b, os.path.join(WORK, "pb%d.tif" % b))[0], src_png[b])
             for b in range(src_png.shape[0]))
    check(ok and len(js["layers"]) == src_png.shape[0] == 3,
          "--band-layers on a PNG: one layer per band, each exact")

    # JPEG 2000 (lossless) through GDAL's JP2OpenJPEG driver
    drivers = run("gdalinfo", "--formats").stdout
    if "JP2OpenJPEG" in drivers:
        jp2 = os.path.join(WORK, "rgb.jp2")
        run("gdal_translate", "-q", "-of", "JP2OpenJPEG", "-co", "QUALITY=100", "-co",
            "REVERSIBLE=YES", "-a_srs", "EPSG:4326", "-a_ullr", "10", "50", "11.9", "48.5",
            os.path.join(WORK, "rgb.bin"), jp2)
        js_store = os.path.join(WORK, "jp2.vts")
        run(tool("vt-tiles"), "-q", "--tile-size", "64", "--codec", "png", jp2, "-o", js_store)
        back = layer_of(js_store, 0, os.path.join(WORK, "jp2.tif"))
        check(np.array_equal(back, read_raster(jp2)), "JPEG 2000: level 0 equals GDAL's decode")
        js = json.loads(run(tool("vt-info"), "--json", js_store).stdout)
        check(georef_matches(js, json.loads(run("gdalinfo", "-json", jp2).stdout)),
              "JPEG 2000: georeferencing equals gdalinfo -json's")
    else:
        print("skip: no JP2OpenJPEG driver in this GDAL")

    # the module missing: one clear line, exit 1 (a copy of vt-tiles outside the build tree
    # finds no module next to it nor at the install path)
    with tempfile.TemporaryDirectory() as tmp:
        bindir = os.path.join(tmp, "bin")
        os.makedirs(bindir)
        moved_tool = os.path.join(bindir, "vt-tiles")
        shutil.copy(tool("vt-tiles"), moved_tool)
        env = {k: v for k, v in os.environ.items() if k != "VT_GDAL_MODULE"}
        none = os.path.join(WORK, "none.vts")
        if os.path.exists(none):
            os.remove(none)
        p = run(moved_tool, six, "-o", none, env=env, expect=1)
        lines = p.stderr.strip().split("\n")
        check(len(lines) == 1 and "six.tif" in lines[0] and "needs GDAL" in lines[0],
              "without the module: one line naming the file (%r)" % p.stderr)
        check(not os.path.exists(none), "without the module: no output")
        # a GeoTIFF of up to 4 bands is still read (libtiff), with a warning that its
        # georeferencing is not kept
        p = run(moved_tool, jp2_or_rgb_tif, "-o", none, env=env)
        check("georeferencing is not kept" in p.stderr and "GDAL module" in p.stderr,
              "without the module: a 3-band GeoTIFF builds with a warning (%r)" % p.stderr)
        js = json.loads(run(tool("vt-info"), "--json", none).stdout)
        check("geoTransform" not in js, "without the module: no georeferencing in the store")


def peak_rss_kib(*args, env=None):
    """Runs a command, returns its peak RSS (KiB) from wait4()."""
    pid = os.spawnve(os.P_NOWAIT, args[0], list(args), env or dict(os.environ))
    _, status, usage = os.wait4(pid, 0)
    if os.waitstatus_to_exitcode(status) != 0:
        sys.exit("%s failed" % " ".join(args))
    return usage.ru_maxrss


def mosaic(name, tile):
    """A VRT of 4x4 GeoTIFF tiles of tile^2 texels (3 bands u8, tiled, deflate), and one GeoTIFF
    of the same size and content, of 3 grey bands so that GDAL reads its pixels too (an RGB one
    would go to libtiff: docs/geospatial.md, "Routing")."""
    d = os.path.join(WORK, name)
    os.makedirs(d, exist_ok=True)
    paths = []
    for ty in range(4):
        for tx in range(4):
            rng = np.random.default_rng(ty * 4 + tx)
            y, x = np.mgrid[0:tile, 0:tile]
            a = np.stack([(x + tx * tile) % 251, (y + ty * tile) % 241,
                          rng.integers(0, 256, size=(tile, tile))]).astype(np.uint8)
            raw = os.path.join(d, "t%d%d.bin" % (ty, tx))
            write_envi(raw, a)
            out = os.path.join(d, "t%d%d.tif" % (ty, tx))
            x0, y0 = 600000 + tx * tile, 5000000 - ty * tile
            run("gdal_translate", "-q", "-co", "TILED=YES", "-co", "COMPRESS=DEFLATE", "-a_srs",
                "EPSG:32632", "-a_ullr", str(x0), str(y0), str(x0 + tile), str(y0 - tile), raw,
                out)
            os.remove(raw)
            paths.append(out)
    vrt = os.path.join(d, "mosaic.vrt")
    run("gdalbuildvrt", "-q", vrt, *paths)
    single = os.path.join(d, "single.tif")
    run("gdal_translate", "-q", "-co", "TILED=YES", "-co", "COMPRESS=DEFLATE", "-co",
        "PHOTOMETRIC=MINISBLACK", vrt, single)
    return vrt, single


def test_vrt_rss():
    small_vrt, small_tif = mosaic("small", 512)
    large_vrt, large_tif = mosaic("large", 1024)
    out = os.path.join(WORK, "m.vts")
    args = [tool("vt-tiles"), "-q", "-j2", "--codec", "raw"]
    rss = {}
    for key, path in [("single", large_tif), ("small", small_vrt), ("large", large_vrt)]:
        rss[key] = peak_rss_kib(*args, path, "-o", out)
    js = json.loads(run(tool("vt-info"), "--json", out).stdout)
    check(js["width"] == 4096 and "geoTransform" in js, "the 4096^2 build is georeferenced")
    back = layer_of(out, 0, os.path.join(WORK, "m0.tif"))
    check(np.array_equal(back, read_raster(large_vrt)), "the mosaic's level 0 equals GDAL's read")
    print("peak RSS MiB: mosaic 2048^2 %.1f, mosaic 4096^2 %.1f, single GeoTIFF 4096^2 %.1f"
          % (rss["small"] / 1024, rss["large"] / 1024, rss["single"] / 1024))

    def flat(small, large):  # 4x the area, at most 1.25x the memory
        return large <= small * 1.25

    if SANITIZED:
        print("skip: the RSS bounds in a sanitizer build")
        return
    check(flat(rss["small"], rss["large"]), "RSS flat in the mosaic's area (4x area, <= 1.25x)")
    check(rss["large"] <= rss["single"] * 1.15 + 8 * 1024,
          "RSS of the mosaic within the single GeoTIFF's, both read by GDAL (+15%, +8 MiB)")
    # control: GDAL's block cache unbounded (1 GiB) holds the whole input: the check sees it
    env = dict(os.environ, GDAL_CACHEMAX="1024")
    s = peak_rss_kib(*args, small_vrt, "-o", out, env=env)
    g = peak_rss_kib(*args, large_vrt, "-o", out, env=env)
    print("control, GDAL_CACHEMAX=1024: %.1f -> %.1f MiB" % (s / 1024, g / 1024))
    check(not flat(s, g), "control: an in-core read (unbounded cache) fails the flatness check")


if shutil.which("gdal_translate") is None or shutil.which("gdalbuildvrt") is None:
    print("skip: GDAL's tools (gdal-bin) are not installed")
    sys.exit(77)
os.makedirs(WORK, exist_ok=True)
{"bands": test_bands, "vrt-rss": test_vrt_rss}[WHAT]()
if failures:
    sys.exit("%d check(s) failed" % len(failures))
print("all checks passed")
