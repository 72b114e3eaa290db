/* Mip chain of one atlas entry in one layer (see vt_mip_chain.h). */
#include "internal/vt_mip_chain.h"

#include <assert.h>
#include <stdlib.h>
#include <string.h>

#include "vt_checked.h"
#include "vt_error.h"
#include "vts.h"

static uint32_t ceil_shift(uint32_t v, uint32_t k)
{
    return k >= 32 ? 1 : (uint32_t)(((uint64_t)v + (1ull << k) - 1) >> k);
}

void vt_mip_chain_mode(const struct vt_mip_chain_spec *s, struct vt_pixel_mode *out)
{
    *out = (struct vt_pixel_mode){s->colour_channels + (s->alpha ? 1u : 0u), s->colour,
                                  s->alpha && s->colour != VTS_COLOUR_DATA};
}

uint32_t vt_mip_chain_sample(const struct vt_mip_chain_spec *s)
{
    return s->sample ? s->sample : VTS_SAMPLE_U8;
}

void vt_mip_chain_release(struct vt_mip_chain *c)
{
    if (!c)
        return;
    for (uint32_t l = 0; l < VTS_MAX_LEVELS; l++)
        vt_image_release(&c->levels[l]);
    memset(c, 0, sizeof *c);
}

static int alloc_floats(float **out, uint64_t texels, uint32_t channels, struct vts_error *err)
{
    size_t n;
    if (!vt_size_mul3((size_t)texels, channels, sizeof(float), &n) || n == 0)
        return vt_error_set(err, VTS_ERR_LIMIT, "a mip level of %llu texels is too large",
                            (unsigned long long)texels);
    *out = malloc(n);
    return *out ? 0 : vt_error_set(err, VTS_ERR_NOMEM, "out of memory for a mip level");
}

static uint32_t wrap_index(int64_t v, uint32_t n)
{
    int64_t r = v % (int64_t)n;
    return (uint32_t)(r < 0 ? r + n : r);
}

/* The finer texels a wrapped reduction of a whole w x h level reads: positions 2X + first + t for
 * every coarser X and tap t (some before 0 or past the end), each read modulo the level's size.
 * out->px is allocated. */
static int wrap_region(const struct vt_kernel *k, uint32_t ch, const float *src, uint32_t w,
                       uint32_t h, struct vt_fregion *out, struct vts_error *err)
{
    int64_t x1 = 2 * ((int64_t)ceil_shift(w, 1) - 1) + k->first + k->count;
    int64_t y1 = 2 * ((int64_t)ceil_shift(h, 1) - 1) + k->first + k->count;
    *out = (struct vt_fregion){
        k->first, k->first, (uint32_t)(x1 - k->first), (uint32_t)(y1 - k->first), ch, NULL};
    int rc = alloc_floats(&out->px, (uint64_t)out->width * out->height, ch, err);
    if (rc)
        return rc;
    size_t tf = ch * sizeof(float);
    for (uint32_t j = 0; j < out->height; j++) {
        const float *row = src + (size_t)wrap_index(out->y0 + j, h) * w * ch;
        float *o = out->px + (size_t)j * out->width * ch;
        for (uint32_t i = 0; i < out->width; i++)
            memcpy(o + (size_t)i * ch, row + (size_t)wrap_index(out->x0 + i, w) * ch, tf);
    }
    return 0;
}

/* One 2:1 reduction of a whole w x h working image with edges clamped, or read modulo the size
 * (wrap: the last texel of an odd size then averages the edge with the opposite edge); *dst is
 * allocated. */
static int reduce_once(const struct vt_kernel *k, const struct vt_pixel_mode *m, const float *src,
                       uint32_t w, uint32_t h, bool wrap, float **dst, struct vts_error *err)
{
    uint32_t dw = ceil_shift(w, 1), dh = ceil_shift(h, 1), ch = m->channels;
    struct vt_fregion s = {0, 0, w, h, ch, (float *)(uintptr_t)src};
    struct vt_fregion d = {0, 0, dw, dh, ch, NULL};
    struct vt_edges edges = {w, h, wrap, wrap};
    int rc = wrap ? wrap_region(k, ch, src, w, h, &s, err) : 0;
    if (rc)
        return rc;
    float *padded = wrap ? s.px : NULL, *scratch = NULL;
    if ((rc = alloc_floats(&d.px, (uint64_t)dw * dh, ch, err)) != 0)
        goto out;
    size_t scratch_n = vt_filter_reduce_scratch(k, &s, &d);
    if ((rc = alloc_floats(&scratch, scratch_n ? scratch_n : 1, 1, err)) == 0)
        rc = vt_filter_reduce(k, &edges, &s, &d, scratch, scratch_n, err);
    if (rc == 0 && m->colour == VTS_COLOUR_NORMAL)
        vt_filter_renormalize(&d);
    if (rc) {
        free(d.px);
        goto out;
    }
    *dst = d.px;
out:
    free(scratch);
    free(padded);
    return rc;
}

/* Converts rows of another sample type into the layer's: through floats, one row at a time (see
 * vt_mip_chain_convert). */
static int to_layer_wide(const struct vt_mip_chain_spec *s, const struct vt_source_info *in,
                         const struct vt_image *raw, struct vt_image *out, struct vts_error *err)
{
    uint32_t och = s->colour_channels + (s->alpha ? 1u : 0u), ich = raw->channels;
    uint32_t sample = vt_mip_chain_sample(s);
    bool is_int = raw->sample == VTS_SAMPLE_U8 || raw->sample == VTS_SAMPLE_U16;
    bool linearise = s->srgb_source && is_int;
    struct vt_pixel_mode plain = {ich, VTS_COLOUR_DATA, false};
    struct vt_pixel_mode srgb = {ich, VTS_COLOUR_SRGB, false};
    struct vt_pixel_mode outm = {och, VTS_COLOUR_DATA, false};
    float *rowf = malloc((size_t)raw->width * ich * sizeof(float));
    float *rowl = malloc((size_t)raw->width * ich * sizeof(float));
    float *rowo = malloc((size_t)raw->width * och * sizeof(float));
    int rc = rowf && rowl && rowo
                 ? vt_image_alloc(out, raw->width, raw->height, och, sample, err)
                 : vt_error_set(err, VTS_ERR_NOMEM, "out of memory converting a texture");
    bool grey = ich <= 2;
    for (uint32_t y = 0; rc == 0 && y < raw->height; y++) {
        const void *src = vt_image_at(raw, 0, y);
        vt_filter_to_working(&plain, raw->sample, src, rowf, raw->width);
        if (linearise) /* every channel decoded; alpha is taken from rowf */
            vt_filter_to_working(&srgb, raw->sample, src, rowl, raw->width);
        const float *colour = linearise ? rowl : rowf;
        for (uint32_t x = 0; x < raw->width; x++) {
            const float *p = colour + (size_t)x * ich;
            float *o = rowo + (size_t)x * och;
            for (uint32_t c = 0; c < s->colour_channels; c++)
                o[c] = p[grey ? 0 : c];
            if (s->alpha)
                o[och - 1] = in->has_alpha ? rowf[(size_t)x * ich + ich - 1] : 1.0f;
        }
        vt_filter_from_working(&outm, sample, rowo, vt_image_at(out, 0, y), raw->width);
    }
    free(rowf);
    free(rowl);
    free(rowo);
    if (rc)
        vt_image_release(out);
    return rc;
}

/* Copies rows of the layer's own sample type, picking the layer's channels. */
static int to_layer_same(const struct vt_mip_chain_spec *s, const struct vt_source_info *in,
                         const struct vt_image *raw, struct vt_image *out, struct vts_error *err)
{
    uint32_t och = s->colour_channels + (s->alpha ? 1u : 0u);
    size_t sb = vts_sample_bytes(raw->sample);
    int rc = vt_image_alloc(out, raw->width, raw->height, och, raw->sample, err);
    if (rc)
        return rc;
    /* an opaque alpha: the sample type's one */
    uint8_t one[4];
    if (raw->sample == VTS_SAMPLE_U16)
        memcpy(one, &(uint16_t){65535}, 2);
    else if (raw->sample == VTS_SAMPLE_F16)
        memcpy(one, &(uint16_t){0x3c00}, 2);
    else
        memcpy(one, &(float){1.0f}, 4);
    for (uint32_t y = 0; y < raw->height; y++) {
        const uint8_t *src = vt_image_at(raw, 0, y);
        uint8_t *dst = vt_image_at(out, 0, y);
        if (raw->channels == och) {
            memcpy(dst, src, (size_t)raw->width * och * sb);
            continue;
        }
        bool grey = raw->channels <= 2;
        for (uint32_t x = 0; x < raw->width; x++) {
            const uint8_t *p = src + (size_t)x * raw->channels * sb;
            uint8_t *o = dst + (size_t)x * och * sb;
            for (uint32_t c = 0; c < s->colour_channels; c++)
                memcpy(o + c * sb, p + (grey ? 0 : c) * sb, sb);
            if (s->alpha)
                memcpy(o + (och - 1) * sb, in->has_alpha ? p + (raw->channels - 1) * sb : one, sb);
        }
    }
    return 0;
}

/* Copies 8-bit rows into an 8-bit layer, picking the layer's channels (grey -> RGB, alpha added
 * as 255 or dropped). */
static int to_layer_u8(const struct vt_mip_chain_spec *s, const struct vt_source_info *in,
                       const struct vt_image *raw, struct vt_image *out, struct vts_error *err)
{
    uint32_t och = s->colour_channels + (s->alpha ? 1u : 0u);
    assert(raw->sample == VTS_SAMPLE_U8);
    int rc = vt_image_alloc(out, raw->width, raw->height, och, VTS_SAMPLE_U8, err);
    if (rc)
        return rc;
    for (uint32_t y = 0; y < raw->height; y++) {
        const uint8_t *src = vt_image_at(raw, 0, y);
        uint8_t *dst = vt_image_at(out, 0, y);
        if (raw->channels == och) {
            memcpy(dst, src, (size_t)raw->width * och);
            continue;
        }
        bool grey = raw->channels <= 2;
        for (uint32_t x = 0; x < raw->width; x++) {
            const uint8_t *p = src + (size_t)x * raw->channels;
            uint8_t *o = dst + (size_t)x * och;
            for (uint32_t c = 0; c < s->colour_channels; c++)
                o[c] = p[grey ? 0 : c];
            if (s->alpha)
                o[och - 1] = in->has_alpha ? p[raw->channels - 1] : 255;
        }
    }
    return 0;
}

/* The texel of a texture n texels wide that texel x of its nearest-neighbour resampling to
 * n_out texels samples (at texel centres). */
static uint32_t nearest_texel(uint32_t x, uint32_t n, uint32_t n_out)
{
    return (uint32_t)(((2 * (uint64_t)x + 1) * n) / (2 * (uint64_t)n_out));
}

/* Reduces a layer-format image k times in the working space (the texture's own mip level k). */
static int reduce_stored(const struct vt_mip_chain_spec *s, const struct vt_image *src, uint32_t k,
                         struct vt_image *dst, struct vts_error *err)
{
    struct vt_pixel_mode m;
    vt_mip_chain_mode(s, &m);
    struct vt_kernel kern;
    vt_kernel_init(&kern, s->filter);
    float *cur = NULL;
    uint32_t w = src->width, h = src->height;
    int rc = alloc_floats(&cur, (uint64_t)w * h, m.channels, err);
    if (rc)
        return rc;
    for (uint32_t y = 0; y < h; y++)
        vt_filter_to_working(&m, src->sample, vt_image_at(src, 0, y),
                             cur + (size_t)y * w * m.channels, w);
    for (uint32_t i = 0; i < k && rc == 0; i++) {
        float *next = NULL;
        rc = reduce_once(&kern, &m, cur, w, h, s->wrap, &next, err);
        free(cur);
        cur = next;
        w = ceil_shift(w, 1);
        h = ceil_shift(h, 1);
    }
    if (rc == 0)
        rc = vt_image_alloc(dst, w, h, m.channels, src->sample, err);
    for (uint32_t y = 0; rc == 0 && y < h; y++)
        vt_filter_from_working(&m, src->sample, cur + (size_t)y * w * m.channels,
                               vt_image_at(dst, 0, y), w);
    free(cur);
    return rc;
}

/* Brings a layer-format image of the texture's size to the entry's size W x H: unchanged, or the
 * texture's own mip level k. Other sizes (a power-of-two enlargement: exact replication) are left
 * to crop_copies, which samples them nearest-neighbour (*nearest), so that the enlarged texture
 * is never held whole. */
static int resample(const struct vt_mip_chain_spec *s, struct vt_image *img, bool *nearest,
                    struct vts_error *err)
{
    uint32_t tw = img->width, th = img->height, W = s->width, H = s->height;
    *nearest = false;
    if (tw == W && th == H)
        return 0;
    uint32_t k = 1;
    while (k < 32 && (ceil_shift(tw, k) != W || ceil_shift(th, k) != H) && ceil_shift(tw, k) > W)
        k++;
    if (!(tw > W && k < 32 && ceil_shift(tw, k) == W && ceil_shift(th, k) == H)) {
        *nearest = true;
        return 0;
    }
    struct vt_image out = {0};
    int rc = reduce_stored(s, img, k, &out, err);
    if (rc)
        return rc;
    vt_image_release(img);
    *img = out;
    return 0;
}

/* Replaces img by level 0 of the chain: the crop of the block of copies, texel (a, b) = texel
 * ((crop_x + a) mod W, (crop_y + b) mod H) of the texture at the entry's size W x H. img holds the
 * texture at that size, or (nearest) at its own size, sampled at the centres of the W x H texels.
 */
static int crop_copies(const struct vt_mip_chain_spec *s, struct vt_image *img, bool nearest,
                       struct vts_error *err)
{
    uint32_t W = s->width, H = s->height;
    if (!nearest && s->crop_x == 0 && s->crop_y == 0 && s->crop_width == W && s->crop_height == H)
        return 0; /* one whole copy: img is level 0 */
    struct vt_image out;
    int rc = vt_image_alloc(&out, s->crop_width, s->crop_height, img->channels, img->sample, err);
    if (rc)
        return rc;
    size_t tb = vt_image_texel_bytes(img);
    for (uint32_t b = 0; b < out.height; b++) {
        uint32_t y = (uint32_t)(((uint64_t)s->crop_y + b) % H);
        const uint8_t *row = vt_image_at(img, 0, nearest ? nearest_texel(y, img->height, H) : y);
        uint8_t *o = vt_image_at(&out, 0, b);
        uint32_t x = s->crop_x % W;
        for (uint32_t a = 0; a < out.width;) {
            if (nearest) {
                memcpy(o + (size_t)a * tb, row + (size_t)nearest_texel(x, img->width, W) * tb, tb);
                a++;
                x = x + 1 == W ? 0 : x + 1;
                continue;
            }
            uint32_t run = W - x < out.width - a ? W - x : out.width - a;
            memcpy(o + (size_t)a * tb, row + (size_t)x * tb, (size_t)run * tb);
            a += run;
            x = 0;
        }
    }
    vt_image_release(img);
    *img = out;
    return 0;
}

/* Levels 1.. of the chain from level 0. */
static int build_levels(struct vt_mip_chain *c, const struct vt_mip_chain_spec *s,
                        struct vts_error *err)
{
    struct vt_pixel_mode m;
    vt_mip_chain_mode(s, &m);
    struct vt_kernel kern;
    vt_kernel_init(&kern, s->filter);
    const struct vt_image *l0 = &c->levels[0];
    uint32_t w = l0->width, h = l0->height, sample = l0->sample;
    size_t tb = vt_image_texel_bytes(l0);
    c->bytes = (size_t)w * h * tb;
    c->level_count = 1;
    if (s->level_count <= 1)
        return 0;
    float *cur = NULL;
    int rc = alloc_floats(&cur, (uint64_t)w * h, m.channels, err);
    if (rc)
        return rc;
    for (uint32_t y = 0; y < h; y++)
        vt_filter_to_working(&m, sample, vt_image_at(l0, 0, y), cur + (size_t)y * w * m.channels,
                             w);
    for (uint32_t l = 1; l < s->level_count && rc == 0; l++) {
        float *next = NULL;
        if ((rc = reduce_once(&kern, &m, cur, w, h, s->wrap, &next, err)) != 0)
            break;
        free(cur);
        cur = next;
        w = ceil_shift(w, 1);
        h = ceil_shift(h, 1);
        struct vt_image *lv = &c->levels[l];
        if ((rc = vt_image_alloc(lv, w, h, m.channels, sample, err)) != 0)
            break;
        for (uint32_t y = 0; y < h; y++)
            vt_filter_from_working(&m, sample, cur + (size_t)y * w * m.channels,
                                   vt_image_at(lv, 0, y), w);
        c->bytes += (size_t)w * h * tb;
        c->level_count = l + 1;
    }
    free(cur);
    return rc;
}

int vt_mip_chain_from_source(struct vt_mip_chain *c, const struct vt_mip_chain_spec *s,
                             struct vt_source *src, struct vts_error *err)
{
    memset(c, 0, sizeof *c);
    assert(s->crop_width >= 1 && s->crop_height >= 1 && s->width >= 1 && s->height >= 1);
    /* the chain holds the crop, never the whole block of copies */
    uint64_t texels = (uint64_t)s->crop_width * s->crop_height;
    if (texels > s->max_pixels)
        return vt_error_set(
            err, VTS_ERR_LIMIT,
            "'%s': the entry's crop of %ux%u texels (copies of %ux%u) exceeds the limit of %llu texels",
            src->name, s->crop_width, s->crop_height, s->width, s->height,
            (unsigned long long)s->max_pixels);
    struct vt_image raw = {0};
    const struct vt_source_info *in = &src->info;
    int rc = vt_image_alloc(&raw, in->width, in->height, in->channels, in->sample, err);
    if (rc == 0)
        rc = vt_source_read(src, 0, 0, &raw, err);
    if (rc == 0)
        rc = vt_mip_chain_from_image(c, s, in, &raw, err);
    vt_image_release(&raw);
    return rc;
}

int vt_mip_chain_convert(const struct vt_mip_chain_spec *s, const struct vt_source_info *in,
                         const struct vt_image *raw, struct vt_image *out, struct vts_error *err)
{
    uint32_t sample = vt_mip_chain_sample(s);
    if (sample == VTS_SAMPLE_U8 && raw->sample == VTS_SAMPLE_U8)
        return to_layer_u8(s, in, raw, out, err);
    if (raw->sample == sample)
        return to_layer_same(s, in, raw, out, err);
    return to_layer_wide(s, in, raw, out, err);
}

int vt_mip_chain_from_image(struct vt_mip_chain *c, const struct vt_mip_chain_spec *s,
                            const struct vt_source_info *in, const struct vt_image *raw,
                            struct vts_error *err)
{
    memset(c, 0, sizeof *c);
    int rc = vt_mip_chain_convert(s, in, raw, &c->levels[0], err);
    bool nearest = false;
    if (rc == 0)
        rc = resample(s, &c->levels[0], &nearest, err);
    if (rc == 0)
        rc = crop_copies(s, &c->levels[0], nearest, err);
    if (rc == 0)
        rc = build_levels(c, s, err);
    if (rc)
        vt_mip_chain_release(c);
    return rc;
}

int vt_mip_chain_from_fill(struct vt_mip_chain *c, const struct vt_mip_chain_spec *s,
                           const double fill[4], struct vts_error *err)
{
    memset(c, 0, sizeof *c);
    uint32_t ch = s->colour_channels + (s->alpha ? 1u : 0u), sample = vt_mip_chain_sample(s);
    double d[4];
    float v[4];
    for (uint32_t i = 0; i < s->colour_channels; i++)
        d[i] = fill[i] < 0 ? 0 : fill[i] > 1 ? 1 : fill[i];
    if (s->alpha)
        d[ch - 1] = fill[3] < 0 ? 0 : fill[3] > 1 ? 1 : fill[3];
    for (uint32_t i = 0; i < ch; i++)
        v[i] = (float)d[i];
    uint8_t px[16];
    if (sample == VTS_SAMPLE_U8) {
        for (uint32_t i = 0; i < ch; i++)
            px[i] = (uint8_t)(d[i] * 255.0 + 0.5);
    } else {
        if (s->srgb_source) { /* stored (sRGB) values into a float layer: linear light */
            struct vt_pixel_mode srgb = {s->colour_channels, VTS_COLOUR_SRGB, false};
            float lin[4];
            vt_filter_to_working(&srgb, VTS_SAMPLE_F32, v, lin, 1);
            memcpy(v, lin, s->colour_channels * sizeof(float));
        }
        struct vt_pixel_mode plain = {ch, VTS_COLOUR_DATA, false};
        vt_filter_from_working(&plain, sample, v, px, 1);
    }
    size_t tb = ch * vts_sample_bytes(sample);
    uint32_t n = s->level_count ? s->level_count : 1;
    for (uint32_t l = 0; l < n; l++) {
        int rc = vt_image_alloc(&c->levels[l], 1, 1, ch, sample, err);
        if (rc) {
            vt_mip_chain_release(c);
            return rc;
        }
        memcpy(c->levels[l].pixels, px, tb);
        c->bytes += tb;
    }
    c->level_count = n;
    return 0;
}
