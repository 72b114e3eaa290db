/* vt-view renderer: programs, framebuffers, textures and passes. */
#include "vtv_render.h"
#include "vtv_ramp.h"

#include <assert.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vt_error.h"
#include "vtv_program.h"
#include "vtv_shaders.h"
#include "vtv_wang_scene.h"

static GLuint program(enum vtv_program_kind kind, unsigned features, struct vts_error *err)
{
    static const char *const names[VTV_PROG_KINDS] = {"virtual-texture", "feedback", "reference"};
    const char *vsrc = vtv_vs_source;
    char defines[512];
    const char *pieces[VTV_SHADER_PIECES];
    int n = vtv_shader_fragment(kind, features, defines, sizeof(defines), pieces);
    return vtv_program_build(&vsrc, 1, pieces, n, names[kind], err);
}

/* The tile determination depends only on the coverage features and on whether any map is
 * sampled: variants that differ in shading share its program (fewer programs for LLVM to
 * compile on the first frame). */
static GLuint feedback_program(struct vtv_render *r, unsigned features, struct vts_error *err)
{
    const unsigned maps =
        VTV_F_DIFFUSE_MAP | VTV_F_NORMAL_MAP | VTV_F_SPECULAR_MAP | VTV_F_ALPHA_MAP;
    unsigned key = features & (VTV_F_ALPHA_TEST | VTV_F_ALPHA_MAP | VTV_F_ALPHA_BLEND);
    if (features & maps)
        key |= VTV_F_DIFFUSE_MAP;
    for (uint32_t i = 0; i < r->feedback_count; i++)
        if (r->feedback_keys[i] == key)
            return r->feedback_progs[i];
    if (r->feedback_count == VTV_MAX_VARIANTS) {
        vt_error_set(err, VTS_ERR_LIMIT, "more than %d shader variants", VTV_MAX_VARIANTS);
        return 0;
    }
    GLuint p = program(VTV_PROG_FEEDBACK, key, err);
    if (p) {
        r->feedback_keys[r->feedback_count] = key;
        r->feedback_progs[r->feedback_count++] = p;
    }
    return p;
}

struct vtv_variant *vtv_render_variant(struct vtv_render *r, unsigned features, unsigned kinds,
                                       struct vts_error *err)
{
    struct vtv_variant *v = NULL;
    features |= r->display.features; /* range and ramp: only when the view uses them */
    for (uint32_t i = 0; i < r->variant_count && !v; i++)
        if (r->variants[i].features == features)
            v = &r->variants[i];
    if (!v) {
        if (r->variant_count == VTV_MAX_VARIANTS) {
            vt_error_set(err, VTS_ERR_LIMIT, "more than %d shader variants", VTV_MAX_VARIANTS);
            return NULL;
        }
        v = &r->variants[r->variant_count++];
        memset(v, 0, sizeof(*v));
        v->features = features;
    }
    for (int k = 0; k < VTV_PROG_KINDS; k++)
        if ((kinds & (1u << k)) && !v->prog[k] &&
            !(v->prog[k] = k == VTV_PROG_FEEDBACK
                               ? feedback_program(r, features, err)
                               : program((enum vtv_program_kind)k, features, err)))
            return NULL;
    return v;
}

static GLuint renderbuffer(GLenum format, uint32_t w, uint32_t h)
{
    GLuint rb;
    glGenRenderbuffers(1, &rb);
    glBindRenderbuffer(GL_RENDERBUFFER, rb);
    glRenderbufferStorage(GL_RENDERBUFFER, format, (GLsizei)w, (GLsizei)h);
    return rb;
}

int vtv_render_init(struct vtv_render *r, uint32_t width, uint32_t height, uint32_t fb_width,
                    uint32_t fb_height, struct vts_error *err)
{
    memset(r, 0, sizeof(*r));
    r->width = width;
    r->height = height;
    r->fb_width = fb_width;
    r->fb_height = fb_height;
    for (int k = 0; k < VTV_MAP_COUNT; k++)
        r->phys_slice[k] = -1;
    r->fallback_pixels = malloc((size_t)width * height);
    if (!r->fallback_pixels)
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
    r->has_s3tc = epoxy_has_gl_extension("GL_EXT_texture_compression_s3tc");
    r->has_srgb_s3tc =
        r->has_s3tc && (epoxy_gl_version() >= 21 || epoxy_has_gl_extension("GL_EXT_texture_sRGB"));
    r->has_rgtc =
        epoxy_gl_version() >= 30 || epoxy_has_gl_extension("GL_ARB_texture_compression_rgtc");
    glGenVertexArrays(1, &r->vao);
    glGenBuffers(1, &r->vbo);

    r->rb_color = renderbuffer(GL_SRGB8_ALPHA8, width, height); /* encodes only if enabled */
    r->rb_fallback = renderbuffer(GL_R8UI, width, height);
    r->rb_depth = renderbuffer(GL_DEPTH_COMPONENT24, width, height);
    glGenFramebuffers(1, &r->fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, r->fbo);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, r->rb_color);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_RENDERBUFFER,
                              r->rb_fallback);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, r->rb_depth);
    GLenum bufs[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    glDrawBuffers(2, bufs);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        return vt_error_set(err, VTS_ERR_UNSUPPORTED, "the main framebuffer is incomplete");

    r->rb_request = renderbuffer(GL_RGBA16UI, fb_width, fb_height);
    r->rb_fb_depth = renderbuffer(GL_DEPTH_COMPONENT24, fb_width, fb_height);
    glGenFramebuffers(1, &r->fb_fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, r->fb_fbo);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, r->rb_request);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, r->rb_fb_depth);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        return vt_error_set(err, VTS_ERR_UNSUPPORTED, "the feedback framebuffer is incomplete");
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    return 0;
}

void vtv_render_free(struct vtv_render *r)
{
    for (uint32_t i = 0; i < r->variant_count; i++)
        for (int k = 0; k < VTV_PROG_KINDS; k++)
            if (r->variants[i].prog[k] && k != VTV_PROG_FEEDBACK)
                glDeleteProgram(r->variants[i].prog[k]);
    for (uint32_t i = 0; i < r->feedback_count; i++)
        glDeleteProgram(r->feedback_progs[i]);
    glDeleteTextures(VTV_MAP_COUNT, r->tex_phys);
    GLuint tex[2] = {r->tex_pt, r->tex_reference};
    glDeleteTextures(2, tex);
    GLuint rbs[5] = {r->rb_color, r->rb_fallback, r->rb_depth, r->rb_request, r->rb_fb_depth};
    glDeleteRenderbuffers(5, rbs);
    GLuint fbos[2] = {r->fbo, r->fb_fbo};
    glDeleteFramebuffers(2, fbos);
    glDeleteBuffers(1, &r->vbo);
    if (r->ebo)
        glDeleteBuffers(1, &r->ebo);
    glDeleteVertexArrays(1, &r->vao);
    free(r->fallback_pixels);
    memset(r, 0, sizeof(*r));
}

/* Attribute pointers of a VTV_VERTEX_FLOATS buffer bound to GL_ARRAY_BUFFER (vtv_tangent.h). */
void vtv_render_vertex_layout(void)
{
    static const int size[4] = {3, 2, 3, 4}, offset[4] = {0, 3, 5, 8};
    for (GLuint k = 0; k < 4; k++) {
        glEnableVertexAttribArray(k);
        glVertexAttribPointer(k, size[k], GL_FLOAT, GL_FALSE, VTV_VERTEX_FLOATS * sizeof(float),
                              (void *)(offset[k] * sizeof(float)));
    }
}

void vtv_render_update_vertices(struct vtv_render *r, const struct vtv_mesh *mesh)
{
    glBindBuffer(GL_ARRAY_BUFFER, r->vbo);
    glBufferSubData(GL_ARRAY_BUFFER, 0,
                    (GLsizeiptr)mesh->vertex_count * VTV_VERTEX_FLOATS * sizeof(float),
                    mesh->vertices);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
}

int vtv_render_set_mesh(struct vtv_render *r, const struct vtv_mesh *mesh, unsigned kinds,
                        struct vts_error *err)
{
    glBindVertexArray(r->vao);
    glBindBuffer(GL_ARRAY_BUFFER, r->vbo);
    glBufferData(GL_ARRAY_BUFFER,
                 (GLsizeiptr)mesh->vertex_count * VTV_VERTEX_FLOATS * sizeof(float), mesh->vertices,
                 GL_STATIC_DRAW);
    vtv_render_vertex_layout();
    r->indexed = mesh->indices != NULL;
    if (r->indexed) { /* the element buffer binding is the vertex array's state */
        if (!r->ebo)
            glGenBuffers(1, &r->ebo);
        glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, r->ebo);
        glBufferData(GL_ELEMENT_ARRAY_BUFFER, (GLsizeiptr)mesh->index_count * sizeof(uint32_t),
                     mesh->indices, GL_STATIC_DRAW);
    }
    glBindVertexArray(0);
    r->groups = mesh->groups;
    r->group_count = mesh->group_count;
    for (uint32_t i = 0; i < mesh->group_count; i++) {
        struct vtv_variant *v = vtv_render_variant(r, mesh->groups[i].features, kinds, err);
        if (!v)
            return err->status;
        v->faces += mesh->groups[i].faces;
    }
    return 0;
}

void vtv_render_draw_group(const struct vtv_render *r, const struct vtv_mesh_group *g)
{
    if (r->indexed)
        glDrawElements(GL_TRIANGLES, (GLsizei)g->count, GL_UNSIGNED_INT,
                       (const void *)((size_t)g->first * sizeof(uint32_t)));
    else
        glDrawArrays(GL_TRIANGLES, (GLint)g->first, (GLsizei)g->count);
}

static float to_linear(float c)
{
    if (c <= 0.04045f)
        return c / 12.92f;
    return powf((c + 0.055f) / 1.055f, 2.4f);
}

void vtv_render_material_uniforms(const struct vtv_render *r, GLuint p,
                                  const struct vtv_material *m, const struct vtv_view *v)
{
    float kd[3], ks[3], ke[3];
    bool ks_black = m->ks[0] <= 0 && m->ks[1] <= 0 && m->ks[2] <= 0;
    for (int k = 0; k < 3; k++) {
        kd[k] = r->srgb ? to_linear(m->kd[k]) : m->kd[k];
        /* map_Ks with a black Ks (the statement missing): the map alone */
        ks[k] = (m->maps & (1u << VTV_MAP_SPECULAR)) && ks_black ? 1.0f
                : r->srgb                                        ? to_linear(m->ks[k])
                                                                 : m->ks[k];
        ke[k] = r->srgb ? to_linear(m->ke[k]) : m->ke[k];
    }
    glUniform3fv(glGetUniformLocation(p, "u_kd"), 1, kd);
    glUniform3fv(glGetUniformLocation(p, "u_ks"), 1, ks);
    glUniform3fv(glGetUniformLocation(p, "u_ke"), 1, ke);
    glUniform1f(glGetUniformLocation(p, "u_ns"), m->ns);
    glUniform1f(glGetUniformLocation(p, "u_d"), m->d);
    glUniform3fv(glGetUniformLocation(p, "u_light_dir"), 1, r->light.dir);
    glUniform3fv(glGetUniformLocation(p, "u_light_colour"), 1, r->light.colour);
    glUniform3fv(glGetUniformLocation(p, "u_ambient"), 1, r->light.ambient);
    glUniform3fv(glGetUniformLocation(p, "u_eye"), 1, v->eye);
    const struct vtv_display *d = &r->display;
    if (d->features & VTV_F_RANGE) {
        float span = d->max - d->min;
        glUniform2f(glGetUniformLocation(p, "u_range"), d->min, span != 0.0f ? 1.0f / span : 0.0f);
    }
    if (d->features & VTV_F_INDEX)
        glUniform1f(glGetUniformLocation(p, "u_index_scale"), d->index_scale);
    const float(*tab)[3] = vtv_ramp_table((enum vtv_ramp_kind)d->ramp);
    if ((d->features & VTV_F_RAMP) && tab) {
        float ramp[VTV_RAMP_POINTS][3]; /* sRGB-encoded colours: linear when the frame encodes */
        for (int i = 0; i < VTV_RAMP_POINTS; i++)
            for (int c = 0; c < 3; c++)
                ramp[i][c] = r->srgb ? to_linear(tab[i][c]) : tab[i][c];
        glUniform3fv(glGetUniformLocation(p, "u_ramp"), VTV_RAMP_POINTS, &ramp[0][0]);
    }
}

void vtv_render_wide_formats(const struct vtv_texel_format *f, GLenum out[3])
{
    static const GLenum formats[4] = {GL_RED, GL_RG, GL_RGB, GL_RGBA};
    static const GLenum u16[4] = {GL_R16, GL_RG16, GL_RGB16, GL_RGBA16};
    static const GLenum f16[4] = {GL_R16F, GL_RG16F, GL_RGB16F, GL_RGBA16F};
    static const GLenum f32[4] = {GL_R32F, GL_RG32F, GL_RGB32F, GL_RGBA32F};
    uint32_t c = f->channels - 1;
    out[1] = formats[c];
    if (f->sample == VTS_SAMPLE_U16) {
        out[0] = u16[c];
        out[2] = GL_UNSIGNED_SHORT;
    } else if (f->sample == VTS_SAMPLE_F16) {
        out[0] = f16[c];
        out[2] = GL_HALF_FLOAT;
    } else {
        out[0] = f32[c];
        out[2] = GL_FLOAT;
    }
}

static GLuint make_phys(GLenum fmt, uint32_t pw, uint32_t ph)
{
    GLuint t;
    glGenTextures(1, &t);
    glBindTexture(GL_TEXTURE_2D, t);
    glTexStorage2D(GL_TEXTURE_2D, 1, fmt, (GLsizei)pw, (GLsizei)ph);
    /* one or two channels read as grey (and alpha), as RGBA8 tiles show them */
    if (fmt == GL_R16 || fmt == GL_R16F || fmt == GL_R32F) {
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_SWIZZLE_G, GL_RED);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_SWIZZLE_B, GL_RED);
    } else if (fmt == GL_RG16 || fmt == GL_RG16F || fmt == GL_RG32F) {
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_SWIZZLE_G, GL_RED);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_SWIZZLE_B, GL_RED);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_SWIZZLE_A, GL_GREEN);
    }
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return t;
}

/* One- and two-channel RGTC layers sample as the CPU path expands them (vtv_loader's to_rgba8):
 * grey (R, R, R, 1), or grey and alpha (R, R, R, G). */
static void swizzle_grey(GLuint tex, bool alpha_in_g)
{
    const GLint swizzle[4] = {GL_RED, GL_RED, GL_RED, alpha_in_g ? GL_GREEN : GL_ONE};
    glBindTexture(GL_TEXTURE_2D, tex);
    glTexParameteriv(GL_TEXTURE_2D, GL_TEXTURE_SWIZZLE_RGBA, swizzle);
}

int vtv_render_set_cache(struct vtv_render *r, const struct vtv_cache *c,
                         const struct vts_geometry *g, const struct vtv_phys_layer *layers,
                         struct vts_error *err)
{
    GLint max_size = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
    uint64_t pw = (uint64_t)c->slots_x * g->tile_payload_px;
    uint64_t ph = (uint64_t)c->slots_y * g->tile_payload_px;
    if (pw > (uint64_t)max_size || ph > (uint64_t)max_size)
        return vt_error_set(
            err, VTS_ERR_LIMIT,
            "a cache of %u tiles of %u px needs a %llux%llu texture; this GL allows %d: use a smaller --cache",
            c->slots, g->tile_payload_px, (unsigned long long)pw, (unsigned long long)ph, max_size);
    r->phys_w = (uint32_t)pw;
    r->phys_h = (uint32_t)ph;
    r->payload_px = g->tile_payload_px;
    r->virt_w = (float)g->width;
    r->virt_h = (float)g->height;
    r->content = (float)g->tile_content_px;
    r->border = (float)g->border_px;
    r->payload = (float)g->tile_payload_px;
    r->max_level = (int)c->level_count - 1;
    for (uint32_t l = 0; l < c->level_count; l++) {
        r->pt_tiles[2 * l] = (int)c->levels[l].tiles_x;
        r->pt_tiles[2 * l + 1] = (int)c->levels[l].tiles_y;
        r->pt_row[l] = (int)c->pt_row[l];
    }
    r->phys_count = 0;
    r->rebuild_z_mask = 0;
    for (int k = 0; k < VTV_MAP_COUNT; k++) {
        if (!layers[k].used)
            continue;
        GLenum bc = layers[k].bc_codec ? vtv_render_bc_format(r, layers[k].bc_codec, layers[k].srgb,
                                                              g->tile_payload_px)
                                       : 0;
        r->phys_format[k] = bc ? bc : layers[k].srgb ? GL_SRGB8_ALPHA8 : GL_RGBA8;
        r->phys_upload[k][0] = GL_RGBA;
        r->phys_upload[k][1] = bc ? 0 : GL_UNSIGNED_BYTE;
        uint32_t sample = layers[k].texels.sample;
        if (!bc && sample && sample != VTS_SAMPLE_U8) {
            GLenum f[3];
            vtv_render_wide_formats(&layers[k].texels, f);
            r->phys_format[k] = f[0];
            r->phys_upload[k][0] = f[1];
            r->phys_upload[k][1] = f[2];
        }
        r->tex_phys[k] = make_phys(r->phys_format[k], r->phys_w, r->phys_h);
        r->phys_slice[k] = (int)r->phys_count++;
        if (bc && layers[k].rebuild_z)
            r->rebuild_z_mask |= 1 << k;
        else if (bc == GL_COMPRESSED_RED_RGTC1 || bc == GL_COMPRESSED_RG_RGTC2)
            swizzle_grey(r->tex_phys[k], bc == GL_COMPRESSED_RG_RGTC2);
        if (k == VTV_MAP_DIFFUSE) {
            r->srgb = layers[k].srgb;
            r->bc_format = bc;
        }
    }
    glGenTextures(1, &r->tex_pt);
    glBindTexture(GL_TEXTURE_2D, r->tex_pt);
    glTexStorage2D(GL_TEXTURE_2D, 1, GL_RGBA8UI, (GLsizei)c->pt_width, (GLsizei)c->pt_height);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    return 0;
}

GLenum vtv_render_bc_format(const struct vtv_render *r, uint32_t codec, bool srgb,
                            uint32_t payload_px)
{
    if (payload_px % 4 != 0)
        return 0;
    if (codec == VTS_CODEC_BC4 || codec == VTS_CODEC_BC5) {
        if (!r->has_rgtc || srgb) /* RGTC has no sRGB formats: decoded on the CPU */
            return 0;
        return codec == VTS_CODEC_BC4 ? GL_COMPRESSED_RED_RGTC1 : GL_COMPRESSED_RG_RGTC2;
    }
    if (!r->has_s3tc || (srgb && !r->has_srgb_s3tc))
        return 0;
    if (codec == VTS_CODEC_BC1)
        return srgb ? GL_COMPRESSED_SRGB_ALPHA_S3TC_DXT1_EXT : GL_COMPRESSED_RGBA_S3TC_DXT1_EXT;
    if (codec == VTS_CODEC_BC3)
        return srgb ? GL_COMPRESSED_SRGB_ALPHA_S3TC_DXT5_EXT : GL_COMPRESSED_RGBA_S3TC_DXT5_EXT;
    return 0;
}

void vtv_render_upload_tile(struct vtv_render *r, const struct vtv_cache *c, uint32_t slot,
                            const uint8_t *data, size_t bytes)
{
    GLint x = (GLint)((slot % c->slots_x) * r->payload_px);
    GLint y = (GLint)((slot / c->slots_x) * r->payload_px);
    size_t stride = r->slice_bytes ? r->slice_bytes : (size_t)r->payload_px * r->payload_px * 4;
    assert(bytes >= stride * r->phys_count);
    (void)bytes;
    for (int k = 0; k < VTV_MAP_COUNT; k++) {
        if (r->phys_slice[k] < 0)
            continue;
        const uint8_t *p = data + (size_t)r->phys_slice[k] * stride;
        glBindTexture(GL_TEXTURE_2D, r->tex_phys[k]);
        if (r->phys_upload[k][1] == 0) { /* compressed */
            size_t block = r->phys_format[k] == GL_COMPRESSED_RGBA_S3TC_DXT1_EXT ||
                                   r->phys_format[k] == GL_COMPRESSED_SRGB_ALPHA_S3TC_DXT1_EXT ||
                                   r->phys_format[k] == GL_COMPRESSED_RED_RGTC1
                               ? 8
                               : 16;
            size_t n = (size_t)(r->payload_px / 4) * (r->payload_px / 4) * block;
            glCompressedTexSubImage2D(GL_TEXTURE_2D, 0, x, y, (GLsizei)r->payload_px,
                                      (GLsizei)r->payload_px, r->phys_format[k], (GLsizei)n, p);
        } else {
            glPixelStorei(GL_UNPACK_ALIGNMENT, 1); /* rows of 1..4 16-bit samples: any length */
            glTexSubImage2D(GL_TEXTURE_2D, 0, x, y, (GLsizei)r->payload_px, (GLsizei)r->payload_px,
                            r->phys_upload[k][0], r->phys_upload[k][1], p);
            glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
        }
    }
}

size_t vtv_render_upload_bytes(const struct vtv_render *r)
{
    size_t n = 0, px = (size_t)r->payload_px * r->payload_px;
    for (int k = 0; k < VTV_MAP_COUNT; k++) {
        if (r->phys_slice[k] < 0)
            continue;
        GLenum f = r->phys_upload[k][0], t = r->phys_upload[k][1];
        if (t == 0) { /* BC blocks of 8 (BC1, BC4) or 16 bytes */
            GLenum c = r->phys_format[k];
            bool eight = c == GL_COMPRESSED_RGBA_S3TC_DXT1_EXT ||
                         c == GL_COMPRESSED_SRGB_ALPHA_S3TC_DXT1_EXT ||
                         c == GL_COMPRESSED_RED_RGTC1;
            n += px / 16 * (eight ? 8 : 16);
            continue;
        }
        size_t ch = f == GL_RED ? 1 : f == GL_RG ? 2 : f == GL_RGB ? 3 : 4;
        size_t b = t == GL_UNSIGNED_BYTE ? 1 : t == GL_FLOAT ? 4 : 2;
        n += px * ch * b;
    }
    return n;
}

void vtv_render_upload_page_table(struct vtv_render *r, const struct vtv_cache *c)
{
    glBindTexture(GL_TEXTURE_2D, r->tex_pt);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, (GLint)c->pt_width);
    for (uint32_t l = 0; l < c->level_count; l++) {
        if (c->dirty_x0[l] >= c->dirty_x1[l])
            continue;
        uint32_t x0 = c->dirty_x0[l], y0 = c->dirty_y0[l];
        glTexSubImage2D(GL_TEXTURE_2D, 0, (GLint)x0, (GLint)(c->pt_row[l] + y0),
                        (GLsizei)(c->dirty_x1[l] - x0), (GLsizei)(c->dirty_y1[l] - y0),
                        GL_RGBA_INTEGER, GL_UNSIGNED_BYTE,
                        c->pt + ((size_t)(c->pt_row[l] + y0) * c->pt_width + x0) * 4);
    }
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
}

static void common_uniforms(const struct vtv_render *r, GLuint p, const struct vtv_view *v,
                            float lod_bias)
{
    static const char *const phys[VTV_MAP_COUNT] = {"u_phys_kd", "u_phys_norm", "u_phys_ks",
                                                    "u_phys_d"};
    glUniformMatrix4fv(glGetUniformLocation(p, "u_mvp"), 1, GL_FALSE, v->mvp);
    glUniform1i(glGetUniformLocation(p, "u_pt"), 0);
    glUniform2f(glGetUniformLocation(p, "u_virt"), r->virt_w, r->virt_h);
    glUniform1f(glGetUniformLocation(p, "u_content"), r->content);
    glUniform1i(glGetUniformLocation(p, "u_max_level"), r->max_level);
    glUniform2iv(glGetUniformLocation(p, "u_pt_tiles"), r->max_level + 1, r->pt_tiles);
    glUniform1iv(glGetUniformLocation(p, "u_pt_row"), r->max_level + 1, r->pt_row);
    glUniform1i(glGetUniformLocation(p, "u_trilinear"), v->trilinear && !v->nearest ? 1 : 0);
    glUniform1i(glGetUniformLocation(p, "u_aniso"), v->aniso > 1 && !v->nearest ? v->aniso : 1);
    glUniform1i(glGetUniformLocation(p, "u_rel"), v->rel ? 1 : 0);
    glUniform2i(glGetUniformLocation(p, "u_origin"), v->rel ? v->origin[0] : 0,
                v->rel ? v->origin[1] : 0);
    glUniform1f(glGetUniformLocation(p, "u_lod_bias"), lod_bias);
    glUniform2f(glGetUniformLocation(p, "u_phys_size"), (float)r->phys_w, (float)r->phys_h);
    glUniform1f(glGetUniformLocation(p, "u_border"), r->border);
    glUniform1f(glGetUniformLocation(p, "u_payload"), r->payload);
    glUniform1i(glGetUniformLocation(p, "u_rebuild_z"), r->rebuild_z_mask);
    for (int k = 0; k < VTV_MAP_COUNT; k++)
        glUniform1i(glGetUniformLocation(p, phys[k]), 1 + k);
}

static void bind_textures(const struct vtv_render *r)
{
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, r->tex_pt);
    for (int k = 0; k < VTV_MAP_COUNT; k++) {
        glActiveTexture(GL_TEXTURE1 + k);
        glBindTexture(GL_TEXTURE_2D, r->tex_phys[k]);
    }
    glActiveTexture(GL_TEXTURE0);
}

/* The physical textures' sampling: GL_NEAREST for a view without filtering (docs/viewer.md,
 * "Categorical and min/max layers"), GL_LINEAR otherwise. */
static void phys_filter(const struct vtv_render *r, bool nearest)
{
    GLint f = nearest ? GL_NEAREST : GL_LINEAR;
    for (int k = 0; k < VTV_MAP_COUNT; k++) {
        if (!r->tex_phys[k])
            continue;
        glBindTexture(GL_TEXTURE_2D, r->tex_phys[k]);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, f);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, f);
    }
}

/* Blended groups: over what is drawn, without writing depth (not sorted among themselves). */
static void set_blend(bool on, bool colour)
{
    if (on && colour) {
        glEnablei(GL_BLEND, 0);
        glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    } else if (colour) {
        glDisablei(GL_BLEND, 0);
    }
    glDepthMask(on ? GL_FALSE : GL_TRUE);
}

/* Draws every group with its variant's program of kind (uniforms set by setup for each program
 * used). */
static void draw_groups(struct vtv_render *r, enum vtv_program_kind kind, const struct vtv_view *v,
                        void (*setup)(struct vtv_render *, GLuint, const struct vtv_view *, void *),
                        void *user)
{
    glBindVertexArray(r->vao);
    GLuint cur = 0;
    for (uint32_t i = 0; i < r->group_count; i++) {
        const struct vtv_mesh_group *g = &r->groups[i];
        struct vtv_variant *var = vtv_render_variant(r, g->features, 0, NULL);
        GLuint p = var ? var->prog[kind] : 0;
        if (!p)
            continue;
        if (p != cur) {
            glUseProgram(p);
            setup(r, p, v, user);
            cur = p;
        }
        if (kind == VTV_PROG_VT)
            vtv_render_material_uniforms(r, p, &g->mat, v);
        if (kind == VTV_PROG_VT && (g->features & VTV_F_WANG))
            vtv_wang_scene_bind(r->wang, p, &g->mat);
        /* blended groups come last; they write no depth (the tile-determination pass: their
           requests replace those of what is behind them, a constant one asks for nothing) */
        bool blend = g->features & VTV_F_ALPHA_BLEND;
        if (blend)
            set_blend(true, kind == VTV_PROG_VT);
        vtv_render_draw_group(r, g);
        if (blend)
            set_blend(false, kind == VTV_PROG_VT);
    }
    glBindVertexArray(0);
    glUseProgram(0);
}

void vtv_render_begin_main(const struct vtv_render *r)
{
    static const GLfloat bg[4] = {0.1f, 0.1f, 0.1f, 1.0f};
    static const GLuint zero[4] = {0, 0, 0, 0};
    glBindFramebuffer(GL_FRAMEBUFFER, r->fbo);
    glViewport(0, 0, (GLsizei)r->width, (GLsizei)r->height);
    glEnable(GL_DEPTH_TEST);
    glDepthMask(GL_TRUE);
    glClearBufferfv(GL_COLOR, 0, bg);
    glClearBufferuiv(GL_COLOR, 1, zero);
    glClear(GL_DEPTH_BUFFER_BIT);
    (r->srgb ? glEnable : glDisable)(GL_FRAMEBUFFER_SRGB);
}

static void setup_vt(struct vtv_render *r, GLuint p, const struct vtv_view *v, void *user)
{
    (void)user;
    common_uniforms(r, p, v, r->lod_bias);
    glUniform2f(glGetUniformLocation(p, "u_jitter"), 0.0f, 0.0f);
    glUniform1i(glGetUniformLocation(p, "u_debug"), v->debug);
}

uint64_t vtv_render_end_main(struct vtv_render *r)
{
    glDisable(GL_FRAMEBUFFER_SRGB);
    glReadBuffer(GL_COLOR_ATTACHMENT1);
    glReadPixels(0, 0, (GLsizei)r->width, (GLsizei)r->height, GL_RED_INTEGER, GL_UNSIGNED_BYTE,
                 r->fallback_pixels);
    uint64_t n = 0;
    for (size_t i = 0; i < (size_t)r->width * r->height; i++)
        n += r->fallback_pixels[i] != 0;
    return n;
}

uint64_t vtv_render_vt(struct vtv_render *r, const struct vtv_view *v)
{
    vtv_render_begin_main(r);
    phys_filter(r, v->nearest);
    bind_textures(r);
    draw_groups(r, VTV_PROG_VT, v, setup_vt, NULL);
    return vtv_render_end_main(r);
}

static void setup_feedback(struct vtv_render *r, GLuint p, const struct vtv_view *v, void *user)
{
    const float *jitter = user;
    /* At 1/k of the resolution the gradients are k times larger: bias back to full resolution. */
    common_uniforms(r, p, v, log2f((float)r->fb_width / (float)r->width) + r->lod_bias);
    glUniform2f(glGetUniformLocation(p, "u_jitter"), jitter[0], jitter[1]);
}

void vtv_render_feedback(struct vtv_render *r, const struct vtv_view *v, float jx, float jy,
                         uint16_t *out)
{
    static const GLuint zero[4] = {0, 0, 0, 0};
    glBindFramebuffer(GL_FRAMEBUFFER, r->fb_fbo);
    glViewport(0, 0, (GLsizei)r->fb_width, (GLsizei)r->fb_height);
    glEnable(GL_DEPTH_TEST);
    glDepthMask(GL_TRUE);
    glClearBufferuiv(GL_COLOR, 0, zero);
    glClear(GL_DEPTH_BUFFER_BIT);
    float jitter[2] = {jx, jy};
    bind_textures(r);
    draw_groups(r, VTV_PROG_FEEDBACK, v, setup_feedback, jitter);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glReadPixels(0, 0, (GLsizei)r->fb_width, (GLsizei)r->fb_height, GL_RGBA_INTEGER,
                 GL_UNSIGNED_SHORT, out);
}

int vtv_render_set_reference(struct vtv_render *r, const uint8_t *rgba, uint32_t w, uint32_t h,
                             bool srgb, struct vts_error *err)
{
    GLint max_size = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
    if (w > (uint32_t)max_size || h > (uint32_t)max_size)
        return vt_error_set(err, VTS_ERR_LIMIT,
                            "--reference: level 0 is %ux%u, larger than GL_MAX_TEXTURE_SIZE %d", w,
                            h, max_size);
    glGenTextures(1, &r->tex_reference);
    glBindTexture(GL_TEXTURE_2D, r->tex_reference);
    r->srgb = srgb;
    glTexImage2D(GL_TEXTURE_2D, 0, srgb ? GL_SRGB8_ALPHA8 : GL_RGBA8, (GLsizei)w, (GLsizei)h, 0,
                 GL_RGBA, GL_UNSIGNED_BYTE, rgba);
    glGenerateMipmap(GL_TEXTURE_2D);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return 0;
}

void vtv_render_reference_begin(struct vtv_render *r)
{
    vtv_render_begin_main(r);
}

void vtv_render_reference_end(void)
{
    glDisable(GL_FRAMEBUFFER_SRGB);
    glUseProgram(0);
}

/* The reference program's uniforms: camera, material, maps on units 0..3 with -s/-o transforms
 * (identity here). */
void vtv_render_reference_uniforms(const struct vtv_render *r, GLuint p,
                                   const struct vtv_material *m, const struct vtv_view *v,
                                   const float st[VTV_MAP_COUNT][4])
{
    static const char *const tex[VTV_MAP_COUNT] = {"u_tex_kd", "u_tex_norm", "u_tex_ks", "u_tex_d"};
    static const float identity[VTV_MAP_COUNT][4] = {
        {1, 1, 0, 0}, {1, 1, 0, 0}, {1, 1, 0, 0}, {1, 1, 0, 0}};
    glUniformMatrix4fv(glGetUniformLocation(p, "u_mvp"), 1, GL_FALSE, v->mvp);
    glUniform2f(glGetUniformLocation(p, "u_jitter"), 0.0f, 0.0f);
    for (int k = 0; k < VTV_MAP_COUNT; k++)
        glUniform1i(glGetUniformLocation(p, tex[k]), k);
    glUniform4fv(glGetUniformLocation(p, "u_st"), VTV_MAP_COUNT, &(st ? st : identity)[0][0]);
    vtv_render_material_uniforms(r, p, m, v);
}

void vtv_render_reference(struct vtv_render *r, const struct vtv_view *v)
{
    vtv_render_reference_begin(r);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, r->tex_reference);
    /* without filtering: level 0 only (GL's mip levels are averages, not the store's selections) */
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER,
                    v->nearest     ? GL_NEAREST
                    : v->trilinear ? GL_LINEAR_MIPMAP_LINEAR
                                   : GL_LINEAR_MIPMAP_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, v->nearest ? GL_NEAREST : GL_LINEAR);
    glTexParameterf(GL_TEXTURE_2D, GL_TEXTURE_MAX_ANISOTROPY,
                    (float)(v->aniso > 1 && !v->nearest ? v->aniso : 1));
    glBindVertexArray(r->vao);
    for (uint32_t i = 0; i < r->group_count; i++) {
        const struct vtv_mesh_group *g = &r->groups[i];
        struct vtv_variant *var = vtv_render_variant(r, g->features, 0, NULL);
        if (!var || !var->prog[VTV_PROG_REFERENCE])
            continue;
        glUseProgram(var->prog[VTV_PROG_REFERENCE]);
        vtv_render_reference_uniforms(r, var->prog[VTV_PROG_REFERENCE], &g->mat, v, NULL);
        vtv_render_draw_group(r, g);
    }
    glBindVertexArray(0);
    vtv_render_reference_end();
}

void vtv_render_read_color(struct vtv_render *r, uint8_t *rgba)
{
    size_t row = (size_t)r->width * 4;
    glBindFramebuffer(GL_FRAMEBUFFER, r->fbo);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glReadPixels(0, 0, (GLsizei)r->width, (GLsizei)r->height, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
    for (uint32_t y = 0; y < r->height / 2; y++) { /* GL rows are bottom-up */
        uint8_t *a = rgba + y * row, *b = rgba + (r->height - 1 - y) * row;
        for (size_t i = 0; i < row; i++) {
            uint8_t t = a[i];
            a[i] = b[i];
            b[i] = t;
        }
    }
}

void vtv_render_present(struct vtv_render *r, uint32_t w, uint32_t h)
{
    glBindFramebuffer(GL_READ_FRAMEBUFFER, r->fbo);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    glBlitFramebuffer(0, 0, (GLint)r->width, (GLint)r->height, 0, 0, (GLint)w, (GLint)h,
                      GL_COLOR_BUFFER_BIT, GL_LINEAR);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}
