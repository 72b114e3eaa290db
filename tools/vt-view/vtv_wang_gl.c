/* vt-view: a Wang pack as GL textures (vtv_wang_gl.h), for --wang and for scene materials. */
#include "vtv_wang_gl.h"

#include <epoxy/gl.h>
#include <stdlib.h>
#include <string.h>

#include "vt_filter.h"

/* n entries as an R32UI texture of 256 columns. */
static GLuint uint_texture(const uint32_t *v, uint32_t n, struct vts_error *err)
{
    uint32_t rows = (n + 255) / 256;
    uint32_t *buf = calloc((size_t)rows * 256, sizeof *buf);
    if (!buf) {
        vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
        return 0;
    }
    memcpy(buf, v, n * sizeof *v);
    GLuint t;
    glGenTextures(1, &t);
    glBindTexture(GL_TEXTURE_2D, t);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_R32UI, 256, (GLsizei)rows, 0, GL_RED_INTEGER, GL_UNSIGNED_INT,
                 buf);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    free(buf);
    return t;
}

/* A level as an sRGB texture level: grey (and grey + alpha) expanded to RGB (RGBA). Returns 0 or
 * VTS_ERR_NOMEM. */
static int upload_level(uint32_t level, const struct vt_image *img, struct vts_error *err)
{
    uint32_t ch = img->channels, out_ch = ch < 3 ? ch + 2 : ch;
    uint8_t *buf = malloc((size_t)img->width * img->height * out_ch);
    if (!buf)
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
    for (uint32_t y = 0; y < img->height; y++) {
        const uint8_t *src = vt_image_at(img, 0, y);
        uint8_t *dst = buf + (size_t)y * img->width * out_ch;
        for (uint32_t x = 0; x < img->width; x++)
            for (uint32_t c = 0; c < out_ch; c++)
                dst[x * out_ch + c] = src[x * ch + (ch >= 3 ? c : c < 3 ? 0 : 1)];
    }
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, (GLint)level, out_ch == 4 ? GL_SRGB8_ALPHA8 : GL_SRGB8,
                 (GLsizei)img->width, (GLsizei)img->height, 0, out_ch == 4 ? GL_RGBA : GL_RGB,
                 GL_UNSIGNED_BYTE, buf);
    free(buf);
    return 0;
}

/* The next coarser level of a pack level: the store's 2:1 box in linear light (lib/filter), with
 * wrap. A level of even size (tile_px a power of two) keeps every texel inside its Wang tile. */
static int reduce_level(const struct vt_image *in, struct vt_image *out, struct vts_error *err)
{
    uint32_t ch = in->channels, w = in->width / 2 ? in->width / 2 : 1;
    uint32_t h = in->height / 2 ? in->height / 2 : 1;
    struct vt_pixel_mode mode = {ch, VTS_COLOUR_SRGB, ch % 2 == 0};
    struct vt_kernel k;
    vt_kernel_init(&k, VT_FILTER_BOX);
    struct vt_edges edges = {in->width, in->height, true, true};
    struct vt_fregion src = {0, 0, in->width, in->height, ch, NULL};
    struct vt_fregion dst = {0, 0, w, h, ch, NULL};
    size_t scratch_n = vt_filter_reduce_scratch(&k, &src, &dst);
    src.px = malloc((size_t)in->width * in->height * ch * sizeof(float));
    dst.px = malloc((size_t)w * h * ch * sizeof(float));
    float *scratch = malloc(scratch_n * sizeof(float));
    int rc = src.px && dst.px && scratch ? 0 : vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
    for (uint32_t y = 0; rc == 0 && y < in->height; y++)
        vt_filter_to_working(&mode, VTS_SAMPLE_U8, vt_image_at(in, 0, y),
                             src.px + (size_t)y * in->width * ch, in->width);
    if (rc == 0)
        rc = vt_filter_reduce(&k, &edges, &src, &dst, scratch, scratch_n, err);
    if (rc == 0)
        rc = vt_image_alloc(out, w, h, ch, VTS_SAMPLE_U8, err);
    if (rc == 0)
        vt_filter_from_working(&mode, VTS_SAMPLE_U8, dst.px, out->pixels, (size_t)w * h);
    free(src.px);
    free(dst.px);
    free(scratch);
    return rc;
}

/* The pack's levels into a repeating, mipmapped sRGB texture: those of the store, then (Wei,
 * section 5) coarser ones made here down to one texel per Wang tile, where the store stopped at
 * the level that fits in one of its tiles. Coarser than that a texel would mix tiles the hash
 * puts apart: the level of detail stops there. */
int vtv_wang_load_pack(struct vts_store *store, const struct vt_wang_info *info,
                       struct vtv_wang_gl *out, struct vts_error *err)
{
    struct vtv_wang_gl *w = out;
    const struct vts_geometry *g = vts_store_geometry(store);
    GLint max_size = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
    if (g->width > (uint32_t)max_size || g->height > (uint32_t)max_size)
        return vt_error_set(err, VTS_ERR_LIMIT,
                            "'%s': the pack (%ux%u texels) is larger than this GL's textures (%d)",
                            vts_store_name(store), g->width, g->height, max_size);
    w->levels = 0;
    glGenTextures(1, &w->pack);
    glBindTexture(GL_TEXTURE_2D, w->pack);
    struct vt_image img = {0}, next;
    for (uint32_t level = 0; (info->tile_px >> level) > 0; level++) {
        int rc = level < g->level_count ? vt_wang_pack_read_level(store, level, &next, err)
                                        : reduce_level(&img, &next, err);
        vt_image_release(&img);
        img = next;
        if (rc == 0)
            rc = upload_level(level, &img, err);
        if (rc) {
            vt_image_release(&img);
            return rc;
        }
        w->levels = level + 1;
    }
    vt_image_release(&img);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, (GLint)w->levels - 1);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
    w->perm = uint_texture(info->hash, info->hash_n, err);
    uint32_t none = 0;
    w->order = info->order ? uint_texture(info->order, info->cols * info->rows, err)
                           : uint_texture(&none, 1, err);
    return w->perm && w->order ? 0 : err->status;
}
