"""The vtpipe package (python/vtpipe) against vt-info --extract: every level and some tiles of
png, raw, jpeg and 16-bit stores decoded to numpy arrays equal the PNGs vt-info writes of them
(the same codec table decodes both, so jpeg is equal too); regions equal slices of levels;
geometry, layers and metadata; errors raise with the library's message; and the comparison
itself fails on a wrong image. Run by ctest (tests/python/CMakeLists.txt), which exports the tool
paths VT_SYNTH, VT_INFO, VT_CONVERT and PYTHONPATH to the build tree's package."""
import os
import subprocess
import threading

import numpy as np
import pytest
from PIL import Image

import vtpipe


def run(*args):
    subprocess.run([str(a) for a in args], check=True, stdout=subprocess.DEVNULL)


@pytest.fixture(scope="module")
def stores(tmp_path_factory):
    d = tmp_path_factory.mktemp("stores")
    synth, convert = os.environ["VT_SYNTH"], os.environ["VT_CONVERT"]
    common = ["--size", "300x200", "--tile", "64", "--border", "2", "--empty"]
    paths = {
        "png": d / "png.vts", "raw": d / "raw.vts", "rgb": d / "rgb.vts",
        "jpeg": d / "jpeg.vts", "u16": d / "u16.vts", "u16raw": d / "u16raw.vts",
    }
    run(synth, paths["png"], *common, "--codec", "png")
    run(synth, paths["raw"], *common, "--codec", "raw", "--channels", "2", "--seed", "5")
    run(synth, paths["rgb"], *common, "--codec", "raw", "--channels", "3")
    run(convert, paths["rgb"], "-o", paths["jpeg"], "--codec", "jpeg", "-q")
    run(synth, paths["u16"], *common, "--codec", "png", "--channels", "1", "--sample", "u16")
    run(synth, paths["u16raw"], *common, "--codec", "raw", "--channels", "1", "--sample", "u16",
        "--seed", "9")
    return paths


def extract(store_path, level, tile=None):
    """vt-info --extract of level (or one tile of it) as a (h, w, channels) numpy array."""
    out = store_path.with_name(f"{store_path.stem}_{level}_{tile}.png")
    args = [os.environ["VT_INFO"], "-q", "--extract", level, "-o", out, store_path]
    if tile:
        args[4:4] = ["--tile", f"{tile[0]},{tile[1]}"]
    run(*args)
    with Image.open(out) as im:
        a = np.array(im)
    return a[:, :, None] if a.ndim == 2 else a


def assert_same_image(got, want):
    assert got.shape == want.shape, f"shape {got.shape} != {want.shape}"
    want = want.astype(got.dtype)
    diff = np.count_nonzero(got != want)
    assert diff == 0, f"{diff} samples differ"


@pytest.mark.parametrize("kind", ["png", "raw", "jpeg", "u16", "u16raw"])
def test_every_level_equals_vt_info_extract(stores, kind):
    with vtpipe.open(stores[kind]) as s:
        for level in range(s.geometry.level_count):
            assert_same_image(s.level(0, level), extract(stores[kind], level))


@pytest.mark.parametrize("kind", ["png", "jpeg", "u16"])
def test_tiles_equal_vt_info_extract(stores, kind):
    with vtpipe.open(stores[kind]) as s:
        b = s.geometry.border_px
        for level, x, y in [(0, 0, 0), (0, 4, 3), (0, 3, 0), (1, 2, 1), (3, 0, 0)]:
            want = extract(stores[kind], level, (x, y))
            assert_same_image(s.tile(0, level, x, y), want)
            assert_same_image(s.tile(0, level, x, y, border=False), want[b:-b, b:-b])


def test_dtypes_and_shapes(stores):
    with vtpipe.open(stores["png"]) as s:
        a = s.level("diffuse", 1)
        assert a.dtype == np.uint8 and a.shape == (100, 150, 4)
        assert s.tile(0, 0, 0, 0).shape == (68, 68, 4)
        assert s.tile(0, 0, 0, 0, border=False).shape == (64, 64, 4)
    with vtpipe.open(stores["u16"]) as s:
        a = s.level(0, 0)
        assert a.dtype == np.uint16 and a.shape == (200, 300, 1)
        assert a.max() > 255  # really 16 bits


def test_empty_tiles_are_zeros(stores):
    with vtpipe.open(stores["png"]) as s:
        # vt-synth --empty: tile (tx, ty) of level 0 is empty when (tx + 2 ty) % 7 == 3
        assert not s.tile(0, 0, 3, 0).any()
        assert not s.level(0, 0)[0:64, 192:256].any()
        assert s.level(0, 0)[0:64, 128:192].any()


def test_regions_are_slices_of_the_level(stores):
    with vtpipe.open(stores["raw"]) as s:
        full = s.level(0, 0)
        for x, y, w, h in [(0, 0, 300, 200), (63, 63, 2, 2), (10, 5, 250, 190), (299, 199, 1, 1)]:
            assert_same_image(s.region(0, 0, x, y, w, h), full[y:y + h, x:x + w])


def test_geometry_layers_metadata(stores):
    with vtpipe.open(stores["jpeg"]) as s:
        g = s.geometry
        assert (g.width, g.height, g.tile_content_px, g.border_px, g.tile_payload_px) == \
            (300, 200, 64, 2, 68)
        assert (g.level_count, g.layer_count) == (4, 1)
        assert s.levels[3] == vtpipe.Level(38, 25, 1, 1)
        layer = s.layers[0]
        assert (layer.name, layer.channels, layer.sample, layer.colour, layer.codec) == \
            ("diffuse", 3, "u8", "srgb", "jpeg")
        assert layer.codec_param == 85
        assert s.metadata["generator"] == "vt-synth"
        assert s.metadata["convert.1"] == "jpeg q85 from raw"
    with vtpipe.open(stores["u16raw"]) as s:
        assert s.layers[0].sample == "u16" and s.layers[0].codec == "raw"
        assert s.metadata["seed"] == "9"


def test_threads_decode_the_same(stores):
    with vtpipe.open(stores["png"]) as s:
        want = s.level(0, 0)
        got = [None] * 4

        def work(i):
            got[i] = s.level(0, 0)

        threads = [threading.Thread(target=work, args=(i,)) for i in range(4)]
        for t in threads:
            t.start()
        for t in threads:
            t.join()
        for g in got:
            assert_same_image(g, want)


def test_a_missing_file_raises_with_the_library_message(tmp_path):
    missing = tmp_path / "nope.vts"
    with pytest.raises(vtpipe.VtsError) as e:
        vtpipe.open(missing)
    assert str(missing) in str(e.value)
    assert e.value.status_name == "io"


def test_a_file_that_is_not_a_store_raises(tmp_path):
    p = tmp_path / "x.vts"
    p.write_bytes(b"not a store at all" * 10)
    with pytest.raises(vtpipe.VtsError) as e:
        vtpipe.open(p)
    assert e.value.status_name == "not-vts" and e.value.status == -3
    assert str(p) in str(e.value)


def test_out_of_range_raises(stores):
    with vtpipe.open(stores["png"]) as s:
        with pytest.raises(vtpipe.VtsRangeError, match=r"no level 4 \(the store has 4\)"):
            s.tile(0, 4, 0, 0)
        with pytest.raises(IndexError, match="no level 9"):
            s.level(0, 9)
        with pytest.raises(vtpipe.VtsRangeError, match="no tile 5,0 in level 0"):
            s.tile(0, 0, 5, 0)
        with pytest.raises(vtpipe.VtsRangeError, match="outside level 0"):
            s.region(0, 0, 290, 0, 11, 1)
        with pytest.raises(vtpipe.VtsRangeError, match="no layer 1"):
            s.level(1, 0)
        with pytest.raises(vtpipe.VtsRangeError, match="no layer named 'normal'"):
            s.level("normal", 0)
        with pytest.raises(vtpipe.VtsRangeError):
            s.tile(0, -1, 0, 0)
        with pytest.raises(vtpipe.VtsError, match="empty rectangle"):
            s.region(0, 0, 0, 0, 0, 5)
    with pytest.raises(vtpipe.VtsError, match="closed"):
        s.level(0, 0)


def test_a_wrong_comparison_fails(stores):
    """The check can fail: a level shifted by one texel, one changed sample, another level."""
    with vtpipe.open(stores["png"]) as s:
        want = extract(stores["png"], 0)
        got = s.level(0, 0)
        with pytest.raises(AssertionError, match="samples differ"):
            assert_same_image(s.region(0, 0, 1, 0, 299, 200), want[:, :299])
        got[100, 100, 0] ^= 1
        with pytest.raises(AssertionError, match="1 samples differ"):
            assert_same_image(got, want)
        with pytest.raises(AssertionError, match="shape"):
            assert_same_image(s.level(0, 1), want)
