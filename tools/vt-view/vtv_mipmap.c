/* vt-view: reference texture mip chains made like the store's (see vtv_mipmap.h). */
#include "vtv_mipmap.h"

#include <math.h>
#include <stdlib.h>

#include <epoxy/gl.h>

#include "vt_checked.h"
#include "vt_error.h"
#include "vt_filter.h"
#include "vts.h"

#define CH 4 /* RGBA */

/* The taps of coarser texel i when n finer texels reduce to m (m = n / 2, or 1 when n = 1):
 * weights into w, the first finer texel into *first; returns the count (1..4). */
static int axis_taps(uint32_t n, uint32_t m, uint32_t i, float w[4], uint32_t *first)
{
    if (n == 1) {
        *first = 0;
        w[0] = 1.0f;
        return 1;
    }
    if (n == 2 * m) { /* the store's box: exactly 1/2, 1/2 */
        *first = 2 * i;
        w[0] = w[1] = 0.5f;
        return 2;
    }
    double s = (double)n / m, a = i * s, b = (i + 1) * s, wd[4], sum = 0;
    uint32_t f = (uint32_t)floor(a), l = (uint32_t)ceil(b);
    if (l > n)
        l = n;
    int count = 0;
    for (uint32_t t = f; t < l && count < 4; t++) {
        wd[count] = fmin(b, t + 1.0) - fmax(a, (double)t);
        sum += wd[count++];
    }
    for (int k = 0; k < count; k++)
        w[k] = (float)(wd[k] / sum);
    *first = f;
    return count;
}

/* dst (m x h) from src (n x h): each row reduced horizontally. */
static void reduce_x(const float *src, uint32_t n, uint32_t h, float *dst, uint32_t m)
{
    for (uint32_t x = 0; x < m; x++) {
        float w[4];
        uint32_t first;
        int count = axis_taps(n, m, x, w, &first);
        for (uint32_t y = 0; y < h; y++) {
            const float *p = src + ((size_t)y * n + first) * CH;
            float *o = dst + ((size_t)y * m + x) * CH;
            for (int c = 0; c < CH; c++) {
                float acc = w[0] * p[c]; /* in tap order, as lib/filter sums */
                for (int t = 1; t < count; t++)
                    acc += w[t] * p[t * CH + c];
                o[c] = acc;
            }
        }
    }
}

/* dst (w x m) from src (w x n): columns reduced vertically. */
static void reduce_y(const float *src, uint32_t w_px, uint32_t n, float *dst, uint32_t m)
{
    size_t row = (size_t)w_px * CH;
    for (uint32_t y = 0; y < m; y++) {
        float w[4];
        uint32_t first;
        int count = axis_taps(n, m, y, w, &first);
        const float *p = src + (size_t)first * row;
        float *o = dst + (size_t)y * row;
        for (size_t i = 0; i < row; i++) {
            float acc = w[0] * p[i];
            for (int t = 1; t < count; t++)
                acc += w[t] * p[(size_t)t * row + i];
            o[i] = acc;
        }
    }
}

static float *alloc_level(uint32_t w, uint32_t h)
{
    size_t n;
    return vt_size_mul3((size_t)w * h, CH, sizeof(float), &n) ? malloc(n) : NULL;
}

/* Normal maps: each filtered texel's xyz back to unit length (zero: (0, 0, 1)), as the store's
 * levels are (lib/filter's vt_filter_renormalize). */
static void renormalize(float *px, size_t n)
{
    for (size_t i = 0; i < n; i++, px += CH) {
        double l = sqrt((double)px[0] * px[0] + (double)px[1] * px[1] + (double)px[2] * px[2]);
        for (int k = 0; k < 3; k++)
            px[k] = l > 0 ? (float)(px[k] / l) : k == 2 ? 1.0f : 0.0f;
    }
}

int vtv_mipmap_upload(const uint8_t *rgba, uint32_t w, uint32_t h, uint32_t colour, bool alpha,
                      const char *path, struct vts_error *err)
{
    bool srgb = colour == VTS_COLOUR_SRGB;
    const struct vt_pixel_mode mode = {CH, colour, alpha};
    GLenum internal = srgb ? GL_SRGB8_ALPHA8 : GL_RGBA8;
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, (GLint)internal, (GLsizei)w, (GLsizei)h, 0, GL_RGBA,
                 GL_UNSIGNED_BYTE, rgba);
    float *cur = alloc_level(w, h), *tmp = NULL, *next = NULL;
    uint8_t *out = malloc((size_t)(w / 2 ? w / 2 : 1) * (h / 2 ? h / 2 : 1) * CH);
    int st = 0, level = 0;
    if (!cur || !out)
        goto nomem;
    vt_filter_to_working(&mode, VTS_SAMPLE_U8, rgba, cur, (size_t)w * h);
    while (w > 1 || h > 1) {
        uint32_t nw = w > 1 ? w / 2 : 1, nh = h > 1 ? h / 2 : 1;
        tmp = alloc_level(nw, h);
        next = alloc_level(nw, nh);
        if (!tmp || !next)
            goto nomem;
        reduce_x(cur, w, h, tmp, nw); /* horizontal, then vertical, as lib/filter */
        reduce_y(tmp, nw, h, next, nh);
        free(tmp);
        free(cur);
        tmp = NULL;
        cur = next;
        next = NULL;
        w = nw;
        h = nh;
        if (colour == VTS_COLOUR_NORMAL)
            renormalize(cur, (size_t)w * h);
        vt_filter_from_working(&mode, VTS_SAMPLE_U8, cur, out, (size_t)w * h);
        glTexImage2D(GL_TEXTURE_2D, ++level, (GLint)internal, (GLsizei)w, (GLsizei)h, 0, GL_RGBA,
                     GL_UNSIGNED_BYTE, out);
    }
    goto done;
nomem:
    st = vt_error_set(err, VTS_ERR_NOMEM, "'%s': out of memory for its mip levels", path);
done:
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_BASE_LEVEL, 0);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, level);
    free(next);
    free(tmp);
    free(cur);
    free(out);
    return st;
}
