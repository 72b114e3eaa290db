/* Cut-out detection from the texels of a texture's alpha channel (vt_atlas_alpha.h). */
#include "vt_atlas_alpha.h"

#include <math.h>
#include <string.h>

#include "vt_image.h"
#include "vts.h"

#define BAND_ROWS 64

bool vt_atlas_alpha_is_cutout(const struct vt_atlas_alpha_counts *c)
{
    return c->texels && (double)c->partial <= VT_ATLAS_ALPHA_MAX_PARTIAL * (double)c->texels &&
           (double)c->clear >= VT_ATLAS_ALPHA_MIN_CLEAR * (double)c->texels;
}

/* IEEE half to float (subnormals, infinities and NaN included). */
static float half_to_float(uint16_t h)
{
    int e = (h >> 10) & 0x1f, m = h & 0x3ff;
    float v = e == 0    ? ldexpf((float)m, -24)
              : e == 31 ? (m ? NAN : INFINITY)
                        : ldexpf((float)(m | 0x400), e - 25);
    return (h & 0x8000) ? -v : v;
}

static float alpha_of(const unsigned char *a, uint32_t sample)
{
    uint16_t u16;
    float f;
    switch (sample) {
    case VTS_SAMPLE_U8:
        return a[0] / 255.0f;
    case VTS_SAMPLE_U16:
        memcpy(&u16, a, 2);
        return u16 / 65535.0f;
    case VTS_SAMPLE_F16:
        memcpy(&u16, a, 2);
        return half_to_float(u16);
    default:
        memcpy(&f, a, 4);
        return f;
    }
}

static void count_band(const struct vt_image *b, struct vt_atlas_alpha_counts *c)
{
    size_t sb = vt_sample_bytes(b->sample), tb = vt_image_texel_bytes(b);
    for (uint32_t y = 0; y < b->height; y++) {
        const unsigned char *row = vt_image_at(b, 0, y);
        for (uint32_t x = 0; x < b->width; x++) {
            float a = alpha_of(row + x * tb + tb - sb, b->sample);
            /* NaN counts as partial: it is no coverage a renderer can test */
            c->clear += a <= (float)VT_ATLAS_ALPHA_CLEAR;
            c->partial +=
                !(a <= (float)VT_ATLAS_ALPHA_CLEAR) && !(a >= (float)VT_ATLAS_ALPHA_SOLID);
        }
    }
    c->read += (uint64_t)b->width * b->height;
}

int vt_atlas_alpha_scan(struct vt_source *src, struct vt_atlas_alpha_counts *c,
                        struct vts_error *err)
{
    const struct vt_source_info *in = &src->info;
    memset(c, 0, sizeof *c);
    c->texels = (uint64_t)in->width * in->height;
    if (!in->has_alpha || c->texels == 0)
        return 0;
    size_t row_bytes = (size_t)in->width * in->channels * vt_sample_bytes(in->sample);
    uint32_t rows = row_bytes ? (uint32_t)(VT_ATLAS_ALPHA_BAND_BYTES / row_bytes) : BAND_ROWS;
    rows = rows < 1 ? 1 : rows > BAND_ROWS ? BAND_ROWS : rows;
    rows = rows > in->height ? in->height : rows;
    struct vt_image band;
    int rc = vt_image_alloc(&band, in->width, rows, in->channels, in->sample, err);
    double max_partial = VT_ATLAS_ALPHA_MAX_PARTIAL * (double)c->texels;
    for (uint32_t y = 0; rc == 0 && y < in->height; y += rows) {
        band.height = in->height - y < rows ? in->height - y : rows;
        rc = vt_source_read(src, 0, y, &band, err);
        if (rc == 0)
            count_band(&band, c);
        if ((double)c->partial > max_partial)
            break; /* no cut-out, whatever the rest holds */
    }
    vt_image_release(&band);
    return rc;
}
