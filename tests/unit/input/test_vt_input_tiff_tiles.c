/* formats/input's TIFF reader, whole native tiles: a region that is exactly one tile of a tiled
 * TIFF is decoded straight into the caller's image (no chunk buffer, no copy). Every tile of
 * generated files (8/16-bit and half samples, deflate/LZW/none, BigTIFF, contiguous and separate
 * planes, edge tiles cut by the image) read whole, then a part of each, holds the expected
 * texels; the comparison is shown to catch one flipped byte. Kept apart from test_vt_image_input
 * (which loads the OpenImageIO module) so that it runs alone under the sanitizers. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "vt_image_input.h"
#include "vt_synth_images.h"
#include "vt_test.h"

static char tmp_dir[256];

/* Reads [x, x + w) x [y, y + h) of src into an image with tight rows (the tile cache's layout)
 * and compares it with the pattern; `flip` flips one byte first (the comparison must see it). */
static bool region_ok(struct vt_source *src, const struct vt_synth_image_options *o, uint32_t x,
                      uint32_t y, uint32_t w, uint32_t h, bool flip)
{
    struct vt_image got, want;
    struct vts_error err = {0};
    if (vt_image_alloc(&got, w, h, src->info.channels, src->info.sample, NULL) < 0)
        return false;
    if (vt_image_alloc(&want, w, h, o->channels, o->sample, NULL) < 0) {
        vt_image_release(&got);
        return false;
    }
    int rc = vt_source_read(src, x, y, &got, &err);
    if (rc)
        fprintf(stderr, "read %ux%u at %u,%u: %s\n", w, h, x, y, err.message);
    vt_synth_image_expected(o, x, y, &want);
    if (flip)
        ((unsigned char *)got.pixels)[got.stride * (h / 2) + 1] ^= 0x10;
    bool same = rc == 0 && memcmp(got.pixels, want.pixels, got.stride * h) == 0;
    vt_image_release(&got);
    vt_image_release(&want);
    return same;
}

static void check_tiles(struct vt_synth_image_options o, const char *name)
{
    char path[512];
    snprintf(path, sizeof path, "%s/%s", tmp_dir, name);
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(vt_synth_image_write(path, &o, &err), 0);
    struct vt_source src;
    int rc = vt_image_input_open(path, NULL, &src, &err);
    VT_CHECK_INT_EQ(rc, 0);
    if (rc)
        return;
    VT_CHECK_INT_EQ(src.info.tile_w, o.tile_w);
    int bad = 0, tiles = 0;
    for (uint32_t y = 0; y < o.height; y += o.tile_h)
        for (uint32_t x = 0; x < o.width; x += o.tile_w) {
            uint32_t w = o.width - x < o.tile_w ? o.width - x : o.tile_w;
            uint32_t h = o.height - y < o.tile_h ? o.height - y : o.tile_h;
            bad += !region_ok(&src, &o, x, y, w, h, false); /* whole */
            if (w >= 2 && h >= 2)                           /* and a part of it */
                bad += !region_ok(&src, &o, x + w / 3, y + h / 4, w / 2, h / 2, false);
            tiles++;
        }
    VT_CHECK_INT_EQ(bad, 0);
    VT_CHECK(tiles >= 6);
    VT_CHECK(!region_ok(&src, &o, o.tile_w, 0, o.tile_w, o.tile_h, true));
    vt_source_close(&src);
    unlink(path);
}

static void whole_tiles_read_as_the_pattern(void)
{
    struct vt_synth_image_options o;
    vt_synth_image_defaults(&o); /* 97 x 61: edge tiles are cut by the image */
    o.format = VT_SYNTH_TIFF;
    o.channels = 3, o.sample = VTS_SAMPLE_U8, o.tile_w = 32, o.tile_h = 16;
    check_tiles(o, "rgb8_deflate.tif");
    o.compression = VT_SYNTH_TIFF_LZW;
    check_tiles(o, "rgb8_lzw.tif");
    o.channels = 1, o.sample = VTS_SAMPLE_U16, o.tile_w = 16, o.tile_h = 32, o.bigtiff = true;
    o.compression = VT_SYNTH_TIFF_NONE;
    check_tiles(o, "grey16.btf");
    o.channels = 4, o.sample = VTS_SAMPLE_F16, o.tile_w = 16, o.tile_h = 16;
    check_tiles(o, "rgbaf16.btf");
    o.channels = 3, o.sample = VTS_SAMPLE_U8, o.tile_w = 48, o.bigtiff = false;
    o.separate_planes = true; /* read plane by plane through the chunk buffers */
    check_tiles(o, "rgb8_planes.tif");
}

int main(void)
{
    snprintf(tmp_dir, sizeof tmp_dir, "/tmp/test_vt_input_tiff_tiles.XXXXXX");
    if (!mkdtemp(tmp_dir))
        return 1;
    VT_RUN(whole_tiles_read_as_the_pattern);
    rmdir(tmp_dir);
    return vt_test_main_result();
}
