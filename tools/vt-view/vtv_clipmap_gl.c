/* vt-view --clipmap: texture array, tile uploads and the draw (docs/viewer.md, "Clipmap mode"). */
#include "vtv_clipmap_gl.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "vt_checked.h"
#include "vtv_clipmap_glsl.h"
#include "vtv_material.h"
#include "vtv_program.h"
#include "vtv_render.h"
#include "vtv_shaders.h"

/* The fragment shader: version, the display's #defines, vt_display(), the clipmap's body. */
static GLuint build_program(unsigned display_features, struct vts_error *err)
{
    const char *vsrc = vtv_vs_source;
    char defines[512];
    vtv_feature_defines(display_features, defines, sizeof(defines));
    const char *fsrc[5] = {"#version 330 core\n", defines, vtv_display_glsl, vtv_level_colour_glsl,
                           vtv_clipmap_fs_glsl};
    return vtv_program_build(&vsrc, 1, fsrc, 5, "clipmap", err);
}

double vtv_clipmap_gl_inset(bool nearest)
{
    return nearest ? 0.5 : 1.0;
}

/* The texels' GL formats and bytes; one and two channels read as grey (and alpha), as RGBA8
 * tiles show them (as the page table's physical textures). */
static size_t texel_formats(struct vtv_clipmap_gl *g, const struct vtv_texel_format *t, bool srgb)
{
    if (!t->sample || t->sample == VTS_SAMPLE_U8) {
        g->internal = srgb ? GL_SRGB8_ALPHA8 : GL_RGBA8;
        g->format = GL_RGBA;
        g->type = GL_UNSIGNED_BYTE;
        return 4;
    }
    GLenum f[3];
    vtv_render_wide_formats(t, f);
    g->internal = f[0];
    g->format = f[1];
    g->type = f[2];
    return vtv_wide_texel_bytes(t);
}

static void swizzle(const struct vtv_clipmap_gl *g)
{
    if (g->format == GL_RED || g->format == GL_RG) {
        const GLint sw[4] = {GL_RED, GL_RED, GL_RED, g->format == GL_RG ? GL_GREEN : GL_ONE};
        glTexParameteriv(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_SWIZZLE_RGBA, sw);
    }
}

/* The texture of n x n tiles of content_px per level, levels layers, of g's internal format:
 * bytes_per_16 bytes per 4 x 4 texels (what the limits count); texel_bytes for the message. */
static int create_texture(struct vtv_clipmap_gl *g, uint32_t n, uint32_t content_px,
                          uint32_t levels, uint64_t bytes_per_16, double texel_bytes,
                          unsigned display_features, struct vts_error *err)
{
    g->debug_offset = -1;
    const char *dbg = getenv("VTV_CLIPMAP_DEBUG_OFFSET");
    if (dbg && *dbg)
        g->debug_offset = atoi(dbg);
    GLint max_size = 0, max_layers = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
    glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &max_layers);
    uint64_t size = (uint64_t)n * content_px, bytes = 0;
    bool over = !vt_u64_mul(size, size, &bytes) || !vt_u64_mul(bytes, bytes_per_16, &bytes) ||
                !vt_u64_mul(bytes / 16, levels, &bytes);
    if (size > (uint64_t)max_size)
        return vt_error_set(err, VTS_ERR_LIMIT,
                            "--clipmap %u: a level's texture of %u tiles of %u px is %llu texels "
                            "across; this GL allows %d: use a smaller --clipmap",
                            n, n, content_px, (unsigned long long)size, max_size);
    if (levels > (uint32_t)max_layers)
        return vt_error_set(err, VTS_ERR_LIMIT,
                            "--clipmap: %u levels need %u array layers; this GL allows %d", levels,
                            levels, max_layers);
    if (over || bytes > VTV_CLIPMAP_MAX_TEXTURE_BYTES)
        return vt_error_set(err, VTS_ERR_LIMIT,
                            "--clipmap %u: %u levels of %llu^2 texels of %g bytes exceed the %llu "
                            "MiB limit: use a smaller --clipmap",
                            n, levels, (unsigned long long)size, texel_bytes,
                            (unsigned long long)(VTV_CLIPMAP_MAX_TEXTURE_BYTES >> 20));
    g->size_px = (uint32_t)size;
    g->content_px = content_px;
    g->levels = levels;
    g->tile_bytes = (uint64_t)content_px * content_px * bytes_per_16 / 16;
    g->prog = build_program(display_features, err);
    if (!g->prog)
        return err->status;
    glGenTextures(1, &g->tex);
    glBindTexture(GL_TEXTURE_2D_ARRAY, g->tex);
    glTexStorage3D(GL_TEXTURE_2D_ARRAY, 1, g->internal, (GLsizei)size, (GLsizei)size,
                   (GLsizei)levels);
    swizzle(g);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_T, GL_REPEAT);
    glBindTexture(GL_TEXTURE_2D_ARRAY, 0);
    if (glGetError() != GL_NO_ERROR)
        return vt_error_set(err, VTS_ERR_LIMIT,
                            "--clipmap %u: this GL cannot allocate %u levels of %llu^2 texels", n,
                            levels, (unsigned long long)size);
    return 0;
}

int vtv_clipmap_gl_init(struct vtv_clipmap_gl *g, uint32_t n, uint32_t content_px, uint32_t levels,
                        const struct vtv_texel_format *texels, bool srgb, unsigned display_features,
                        struct vts_error *err)
{
    memset(g, 0, sizeof(*g));
    size_t texel_bytes = texel_formats(g, texels, srgb);
    return create_texture(g, n, content_px, levels, 16 * (uint64_t)texel_bytes, (double)texel_bytes,
                          display_features, err);
}

int vtv_clipmap_gl_init_bc(struct vtv_clipmap_gl *g, uint32_t n, uint32_t content_px,
                           uint32_t levels, GLenum bc_format, bool rebuild_z,
                           unsigned display_features, struct vts_error *err)
{
    memset(g, 0, sizeof(*g));
    assert(content_px % 4 == 0);
    bool eight = bc_format == GL_COMPRESSED_RGBA_S3TC_DXT1_EXT ||
                 bc_format == GL_COMPRESSED_SRGB_ALPHA_S3TC_DXT1_EXT ||
                 bc_format == GL_COMPRESSED_RED_RGTC1;
    g->internal = bc_format;
    g->bc_format = bc_format;
    g->bc_block = eight ? 8 : 16;
    g->rebuild_z = rebuild_z;
    /* RGTC reads as grey (and alpha), as the page table's physical textures show it */
    g->format = bc_format == GL_COMPRESSED_RED_RGTC1                ? GL_RED
                : bc_format == GL_COMPRESSED_RG_RGTC2 && !rebuild_z ? GL_RG
                                                                    : GL_RGBA;
    int st = create_texture(g, n, content_px, levels, g->bc_block, g->bc_block / 16.0,
                            display_features, err);
    if (st != 0)
        return st;
    g->bc_buf = malloc((size_t)g->tile_bytes);
    if (!g->bc_buf)
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
    return 0;
}

void vtv_clipmap_gl_free(struct vtv_clipmap_gl *g)
{
    if (g->tex)
        glDeleteTextures(1, &g->tex);
    if (g->prog)
        glDeleteProgram(g->prog);
    free(g->bc_buf);
    memset(g, 0, sizeof(*g));
}

/* BC: the content's block rows copied out of the payload's (payload_px / 4 blocks a row, the
 * content from block (border_px / 4, border_px / 4)) into one contiguous buffer. */
static void upload_blocks(struct vtv_clipmap_gl *g, uint32_t level, uint32_t slot_x,
                          uint32_t slot_y, const uint8_t *payload, uint32_t payload_px,
                          uint32_t border_px, const uint8_t *zero)
{
    assert(border_px % 4 == 0 && payload_px % 4 == 0);
    size_t row = (size_t)(g->content_px / 4) * g->bc_block;
    size_t src_row = (size_t)(payload_px / 4) * g->bc_block;
    const uint8_t *src = zero;
    if (payload) {
        const uint8_t *p =
            payload + (size_t)(border_px / 4) * src_row + (size_t)(border_px / 4) * g->bc_block;
        for (uint32_t by = 0; by < g->content_px / 4; by++)
            memcpy(g->bc_buf + by * row, p + by * src_row, row);
        src = g->bc_buf;
    }
    GLsizei c = (GLsizei)g->content_px;
    glBindTexture(GL_TEXTURE_2D_ARRAY, g->tex);
    glCompressedTexSubImage3D(GL_TEXTURE_2D_ARRAY, 0, (GLint)(slot_x * g->content_px),
                              (GLint)(slot_y * g->content_px), (GLint)level, c, c, 1, g->bc_format,
                              (GLsizei)g->tile_bytes, src);
    glBindTexture(GL_TEXTURE_2D_ARRAY, 0);
}

void vtv_clipmap_gl_upload(struct vtv_clipmap_gl *g, uint32_t level, uint32_t slot_x,
                           uint32_t slot_y, const uint8_t *payload, uint32_t payload_px,
                           uint32_t border_px, const uint8_t *zero)
{
    GLsizei c = (GLsizei)g->content_px;
    if (g->bc_format) {
        upload_blocks(g, level, slot_x, slot_y, payload, payload_px, border_px, zero);
        return;
    }
    glBindTexture(GL_TEXTURE_2D_ARRAY, g->tex);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    if (payload) { /* the content cut out of the payload: rows of payload_px, from (b, b) */
        glPixelStorei(GL_UNPACK_ROW_LENGTH, (GLint)payload_px);
        glPixelStorei(GL_UNPACK_SKIP_PIXELS, (GLint)border_px);
        glPixelStorei(GL_UNPACK_SKIP_ROWS, (GLint)border_px);
    }
    glTexSubImage3D(GL_TEXTURE_2D_ARRAY, 0, (GLint)(slot_x * g->content_px),
                    (GLint)(slot_y * g->content_px), (GLint)level, c, c, 1, g->format, g->type,
                    payload ? payload : zero);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
    glPixelStorei(GL_UNPACK_SKIP_PIXELS, 0);
    glPixelStorei(GL_UNPACK_SKIP_ROWS, 0);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glBindTexture(GL_TEXTURE_2D_ARRAY, 0);
}

/* The per-level uniforms relative to the base (level-0 texels) of the view's texcoords. */
static void level_uniforms(const struct vtv_clipmap_gl *g, const struct vts_clipmap *cm, GLuint p,
                           double base_x, double base_y, double inset)
{
    float off[2 * VTS_MAX_LEVELS], edge[4 * VTS_MAX_LEVELS], valid[4 * VTS_MAX_LEVELS];
    double s = g->size_px;
    for (uint32_t l = 0; l < cm->level_count; l++) {
        double k = ldexp(1.0, -(int)l), bx = base_x * k, by = base_y * k;
        double ox = fmod(bx, s), oy = fmod(by, s);
        if ((int)l == g->debug_offset)
            ox += 1.0; /* the tests' deliberately wrong render */
        off[2 * l] = (float)ox;
        off[2 * l + 1] = (float)oy;
        const struct vts_clipmap_level *lv = &cm->levels[l];
        edge[4 * l] = (float)(0.5 - bx);
        edge[4 * l + 1] = (float)(0.5 - by);
        edge[4 * l + 2] = (float)(lv->width - 0.5 - bx);
        edge[4 * l + 3] = (float)(lv->height - 0.5 - by);
        double x0, y0, x1, y1;
        vts_clipmap_valid(cm, l, inset, &x0, &y0, &x1, &y1);
        bool empty = !(x0 < x1 && y0 < y1);
        valid[4 * l] = empty ? 1.0f : (float)(x0 - bx);
        valid[4 * l + 1] = empty ? 1.0f : (float)(y0 - by);
        valid[4 * l + 2] = empty ? 0.0f : (float)(x1 - bx);
        valid[4 * l + 3] = empty ? 0.0f : (float)(y1 - by);
    }
    GLsizei n = (GLsizei)cm->level_count;
    glUniform2fv(glGetUniformLocation(p, "u_off"), n, off);
    glUniform4fv(glGetUniformLocation(p, "u_edge"), n, edge);
    glUniform4fv(glGetUniformLocation(p, "u_valid"), n, valid);
}

uint64_t vtv_clipmap_gl_draw(const struct vtv_clipmap_gl *g, const struct vts_clipmap *cm,
                             struct vtv_render *r, const struct vtv_view *v, float lod_bias)
{
    vtv_render_begin_main(r);
    GLuint p = g->prog;
    glUseProgram(p);
    glUniformMatrix4fv(glGetUniformLocation(p, "u_mvp"), 1, GL_FALSE, v->mvp);
    glUniform2f(glGetUniformLocation(p, "u_jitter"), 0.0f, 0.0f);
    glUniform1i(glGetUniformLocation(p, "u_clip"), 0);
    glUniform1i(glGetUniformLocation(p, "u_levels"), (GLint)cm->level_count);
    glUniform2f(glGetUniformLocation(p, "u_virt"), (float)cm->levels[0].width,
                (float)cm->levels[0].height);
    glUniform1i(glGetUniformLocation(p, "u_rel"), v->rel ? 1 : 0);
    glUniform1f(glGetUniformLocation(p, "u_size"), (float)g->size_px);
    glUniform1i(glGetUniformLocation(p, "u_trilinear"), v->trilinear ? 1 : 0);
    glUniform1i(glGetUniformLocation(p, "u_nearest"), v->nearest ? 1 : 0);
    glUniform1f(glGetUniformLocation(p, "u_lod_bias"), lod_bias);
    glUniform1i(glGetUniformLocation(p, "u_debug"), v->debug == 1 ? 1 : 0);
    glUniform1i(glGetUniformLocation(p, "u_rebuild_z"), g->rebuild_z ? 1 : 0);
    if (r->group_count) /* the display's range, ramp and index scale (a plain material's) */
        vtv_render_material_uniforms(r, p, &r->groups[0].mat, v);
    double bx = v->rel ? (double)v->origin[0] * g->content_px : 0.0;
    double by = v->rel ? (double)v->origin[1] * g->content_px : 0.0;
    level_uniforms(g, cm, p, bx, by, vtv_clipmap_gl_inset(v->nearest));
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D_ARRAY, g->tex);
    GLint f = v->nearest ? GL_NEAREST : GL_LINEAR;
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, f);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, f);
    glBindVertexArray(r->vao);
    for (uint32_t i = 0; i < r->group_count; i++)
        vtv_render_draw_group(r, &r->groups[i]);
    glBindVertexArray(0);
    glUseProgram(0);
    glBindTexture(GL_TEXTURE_2D_ARRAY, 0);
    return vtv_render_end_main(r);
}
