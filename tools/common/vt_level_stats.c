/* Texel statistics of a store's level (see vt_level_stats.h). */
#include "vt_level_stats.h"

#include <math.h>
#include <string.h>

#include "vt_filter.h"
#include "vts.h"

/* Running moments of one channel (Welford's update: stable for millions of samples). */
struct moments {
    uint64_t n, nan;
    double mean, m2, min, max;
};

static void add(struct moments *m, double v)
{
    if (isnan(v)) {
        m->nan++;
        return;
    }
    if (m->n == 0 || v < m->min)
        m->min = v;
    if (m->n == 0 || v > m->max)
        m->max = v;
    m->n++;
    double d = v - m->mean;
    m->mean += d / (double)m->n;
    m->m2 += d * (v - m->mean);
}

/* Sample c of texel x of row y of the reader's last tile, as a double. */
static double sample_at(const struct vt_tile_reader *r, uint32_t x, uint32_t y, uint32_t c)
{
    const unsigned char *p = (const unsigned char *)vt_image_at(&r->img, x, y);
    switch (r->img.sample) {
    case VTS_SAMPLE_U8:
        return p[c];
    case VTS_SAMPLE_U16: {
        uint16_t v;
        memcpy(&v, p + 2 * c, 2);
        return v;
    }
    case VTS_SAMPLE_F16: { /* the working conversion of data samples is the half's value */
        struct vt_pixel_mode mode = {1, VTS_COLOUR_DATA, false};
        float f;
        vt_filter_to_working(&mode, VTS_SAMPLE_F16, p + 2 * c, &f, 1);
        return f;
    }
    default: {
        float f;
        memcpy(&f, p + 4 * c, 4);
        return f;
    }
    }
}

int vt_level_stats_compute(struct vt_tile_reader *r, uint32_t level, struct vt_level_stats *out,
                           struct vts_error *err)
{
    const struct vts_geometry *g = vts_store_geometry(r->store);
    struct vts_level L;
    vts_store_level(r->store, level, &L);
    struct moments m[4];
    memset(m, 0, sizeof m);
    *out = (struct vt_level_stats){.texels = (uint64_t)L.width * L.height,
                                   .channels = r->img.channels};
    uint32_t c = g->tile_content_px, b = g->border_px;
    for (uint32_t ty = 0; ty < L.tiles_y; ty++)
        for (uint32_t tx = 0; tx < L.tiles_x; tx++) {
            bool stored = false;
            int rc = vt_tile_reader_read(r, level, tx, ty, &stored, err);
            if (rc)
                return rc;
            out->empty_tiles += !stored;
            uint32_t w = L.width - tx * c < c ? L.width - tx * c : c;
            uint32_t h = L.height - ty * c < c ? L.height - ty * c : c;
            for (uint32_t y = 0; y < h; y++)
                for (uint32_t x = 0; x < w; x++)
                    for (uint32_t ch = 0; ch < out->channels && ch < 4; ch++)
                        add(&m[ch], sample_at(r, b + x, b + y, ch));
        }
    for (uint32_t ch = 0; ch < out->channels && ch < 4; ch++) {
        struct vt_channel_stats *s = &out->ch[ch];
        s->nan = m[ch].nan;
        if (m[ch].n) {
            s->min = m[ch].min;
            s->max = m[ch].max;
            s->mean = m[ch].mean;
            s->stddev = sqrt(m[ch].m2 / (double)m[ch].n); /* of the population, as gdalinfo */
        }
    }
    return 0;
}
