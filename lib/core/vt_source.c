#include "vt_source.h"
#include "vt_error.h"

#include <string.h>

#define SCAN_ROWS 64

int vt_source_read(struct vt_source *src, uint32_t x, uint32_t y, struct vt_image *dst,
                   struct vts_error *err)
{
    const struct vt_source_info *in = &src->info;
    if (dst->channels != in->channels || dst->sample != in->sample)
        return vt_error_set(err, VTS_ERR_ARG,
                            "'%s': region buffer has %u channels of sample %u, source has %u of %u",
                            src->name, dst->channels, dst->sample, in->channels, in->sample);
    if (x >= in->width || y >= in->height || dst->width > in->width - x ||
        dst->height > in->height - y)
        return vt_error_set(err, VTS_ERR_RANGE,
                            "'%s': region %ux%u at %u,%u is outside the %ux%u image", src->name,
                            dst->width, dst->height, x, y, in->width, in->height);
    return src->ops->read_region(src->ctx, x, y, dst, err);
}

void vt_source_close(struct vt_source *src)
{
    if (!src)
        return;
    if (src->ops && src->ops->close)
        src->ops->close(src->ctx);
    memset(src, 0, sizeof *src);
}

bool vt_image_alpha_opaque(const struct vt_image *b)
{
    size_t sb = vt_sample_bytes(b->sample), tb = vt_image_texel_bytes(b);
    for (uint32_t y = 0; y < b->height; y++) {
        const unsigned char *row = vt_image_at(b, 0, y);
        for (uint32_t x = 0; x < b->width; x++) {
            const unsigned char *a = row + x * tb + tb - sb;
            float f;
            uint16_t h;
            switch (b->sample) {
            case VTS_SAMPLE_U8:
                if (a[0] != 0xff)
                    return false;
                break;
            case VTS_SAMPLE_U16:
                if (a[0] != 0xff || a[1] != 0xff)
                    return false;
                break;
            case VTS_SAMPLE_F16:
                memcpy(&h, a, 2);
                if (h < 0x3c00 || (h & 0x8000)) /* below 1.0 (or negative) */
                    return false;
                break;
            default:
                memcpy(&f, a, 4);
                if (!(f >= 1.0f))
                    return false;
            }
        }
    }
    return true;
}

int vt_source_alpha_opaque(struct vt_source *src, bool *opaque, struct vts_error *err)
{
    *opaque = true;
    if (!src->info.has_alpha)
        return 0;
    struct vt_image band;
    uint32_t rows = src->info.height < SCAN_ROWS ? src->info.height : SCAN_ROWS;
    int rc =
        vt_image_alloc(&band, src->info.width, rows, src->info.channels, src->info.sample, err);
    for (uint32_t y = 0; rc == 0 && y < src->info.height && *opaque; y += rows) {
        band.height = src->info.height - y < rows ? src->info.height - y : rows;
        rc = vt_source_read(src, 0, y, &band, err);
        *opaque = rc == 0 && vt_image_alpha_opaque(&band);
    }
    vt_image_release(&band);
    return rc;
}
