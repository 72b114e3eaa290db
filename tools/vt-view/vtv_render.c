/* vt-view renderer: programs, framebuffers, textures and passes. */
#include "vtv_render.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vt_error.h"
#include "vtv_shaders.h"

static GLuint compile(GLenum type, const char *src, const char *what, struct vts_error *err)
{
    GLuint s = glCreateShader(type);
    glShaderSource(s, 1, &src, NULL);
    glCompileShader(s);
    GLint ok = 0;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[512] = "";
        glGetShaderInfoLog(s, sizeof(log), NULL, log);
        vt_error_set(err, VTS_ERR_UNSUPPORTED, "cannot compile the %s shader: %s", what, log);
        glDeleteShader(s);
        return 0;
    }
    return s;
}

static GLuint program(const char *fs_src, const char *what, struct vts_error *err)
{
    GLuint vs = compile(GL_VERTEX_SHADER, vtv_vs_source, "vertex", err);
    GLuint fs = vs ? compile(GL_FRAGMENT_SHADER, fs_src, what, err) : 0;
    if (!fs) {
        glDeleteShader(vs);
        return 0;
    }
    GLuint p = glCreateProgram();
    glAttachShader(p, vs);
    glAttachShader(p, fs);
    glLinkProgram(p);
    glDeleteShader(vs);
    glDeleteShader(fs);
    GLint ok = 0;
    glGetProgramiv(p, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[512] = "";
        glGetProgramInfoLog(p, sizeof(log), NULL, log);
        vt_error_set(err, VTS_ERR_UNSUPPORTED, "cannot link the %s program: %s", what, log);
        glDeleteProgram(p);
        return 0;
    }
    return p;
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
    r->prog_vt = program(vtv_fs_vt_source, "virtual-texture", err);
    r->prog_feedback = r->prog_vt ? program(vtv_fs_feedback_source, "feedback", err) : 0;
    r->prog_reference = r->prog_feedback ? program(vtv_fs_reference_source, "reference", err) : 0;
    if (!r->prog_reference)
        return err->status;
    r->fallback_pixels = malloc((size_t)width * height);
    if (!r->fallback_pixels)
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
    r->has_s3tc = epoxy_has_gl_extension("GL_EXT_texture_compression_s3tc");
    r->has_srgb_s3tc =
        r->has_s3tc && (epoxy_gl_version() >= 21 || epoxy_has_gl_extension("GL_EXT_texture_sRGB"));
    glGenVertexArrays(1, &r->vao);
    glGenBuffers(1, &r->vbo);
    glGenBuffers(1, &r->ibo);

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
    if (r->prog_vt)
        glDeleteProgram(r->prog_vt);
    if (r->prog_feedback)
        glDeleteProgram(r->prog_feedback);
    if (r->prog_reference)
        glDeleteProgram(r->prog_reference);
    GLuint tex[3] = {r->tex_pt, r->tex_phys, r->tex_reference};
    glDeleteTextures(3, tex);
    GLuint rbs[5] = {r->rb_color, r->rb_fallback, r->rb_depth, r->rb_request, r->rb_fb_depth};
    glDeleteRenderbuffers(5, rbs);
    GLuint fbos[2] = {r->fbo, r->fb_fbo};
    glDeleteFramebuffers(2, fbos);
    GLuint bufs[2] = {r->vbo, r->ibo};
    glDeleteBuffers(2, bufs);
    glDeleteVertexArrays(1, &r->vao);
    free(r->fallback_pixels);
    memset(r, 0, sizeof(*r));
}

void vtv_render_set_mesh(struct vtv_render *r, const float *vertices, uint32_t n,
                         const uint32_t *indices, uint32_t index_count)
{
    glBindVertexArray(r->vao);
    glBindBuffer(GL_ARRAY_BUFFER, r->vbo);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)n * 5 * sizeof(float), vertices, GL_STATIC_DRAW);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, r->ibo);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, (GLsizeiptr)index_count * sizeof(uint32_t), indices,
                 GL_STATIC_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 5 * sizeof(float), (void *)0);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 2, GL_FLOAT, GL_FALSE, 5 * sizeof(float), (void *)(3 * sizeof(float)));
    glBindVertexArray(0);
    r->index_count = (GLsizei)index_count;
}

int vtv_render_set_cache(struct vtv_render *r, const struct vtv_cache *c,
                         const struct vts_geometry *g, bool srgb, uint32_t bc_codec,
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
    r->srgb = srgb;
    r->bc_format = bc_codec ? vtv_render_bc_format(r, bc_codec, srgb, g->tile_payload_px) : 0;
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
    glGenTextures(1, &r->tex_phys);
    glBindTexture(GL_TEXTURE_2D, r->tex_phys);
    GLenum fmt = r->bc_format ? r->bc_format : srgb ? GL_SRGB8_ALPHA8 : GL_RGBA8;
    glTexStorage2D(GL_TEXTURE_2D, 1, fmt, (GLsizei)pw, (GLsizei)ph);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
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
    if (!r->has_s3tc || payload_px % 4 != 0 || (srgb && !r->has_srgb_s3tc))
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
    glBindTexture(GL_TEXTURE_2D, r->tex_phys);
    if (r->bc_format)
        glCompressedTexSubImage2D(GL_TEXTURE_2D, 0, x, y, (GLsizei)r->payload_px,
                                  (GLsizei)r->payload_px, r->bc_format, (GLsizei)bytes, data);
    else
        glTexSubImage2D(GL_TEXTURE_2D, 0, x, y, (GLsizei)r->payload_px, (GLsizei)r->payload_px,
                        GL_RGBA, GL_UNSIGNED_BYTE, data);
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
    glUniformMatrix4fv(glGetUniformLocation(p, "u_mvp"), 1, GL_FALSE, v->mvp);
    glUniform1i(glGetUniformLocation(p, "u_pt"), 0);
    glUniform2f(glGetUniformLocation(p, "u_virt"), r->virt_w, r->virt_h);
    glUniform1f(glGetUniformLocation(p, "u_content"), r->content);
    glUniform1i(glGetUniformLocation(p, "u_max_level"), r->max_level);
    glUniform2iv(glGetUniformLocation(p, "u_pt_tiles"), r->max_level + 1, r->pt_tiles);
    glUniform1iv(glGetUniformLocation(p, "u_pt_row"), r->max_level + 1, r->pt_row);
    glUniform1i(glGetUniformLocation(p, "u_trilinear"), v->trilinear ? 1 : 0);
    glUniform1f(glGetUniformLocation(p, "u_lod_bias"), lod_bias);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, r->tex_pt);
}

static void draw(const struct vtv_render *r)
{
    glBindVertexArray(r->vao);
    glDrawElements(GL_TRIANGLES, r->index_count, GL_UNSIGNED_INT, NULL);
    glBindVertexArray(0);
}

static void begin_main(const struct vtv_render *r)
{
    static const GLfloat bg[4] = {0.1f, 0.1f, 0.1f, 1.0f};
    static const GLuint zero[4] = {0, 0, 0, 0};
    glBindFramebuffer(GL_FRAMEBUFFER, r->fbo);
    glViewport(0, 0, (GLsizei)r->width, (GLsizei)r->height);
    glEnable(GL_DEPTH_TEST);
    glClearBufferfv(GL_COLOR, 0, bg);
    glClearBufferuiv(GL_COLOR, 1, zero);
    glClear(GL_DEPTH_BUFFER_BIT);
    (r->srgb ? glEnable : glDisable)(GL_FRAMEBUFFER_SRGB);
}

uint64_t vtv_render_vt(struct vtv_render *r, const struct vtv_view *v)
{
    begin_main(r);
    GLuint p = r->prog_vt;
    glUseProgram(p);
    common_uniforms(r, p, v, 0.0f);
    glUniform2f(glGetUniformLocation(p, "u_jitter"), 0.0f, 0.0f);
    glUniform1i(glGetUniformLocation(p, "u_phys"), 1);
    glUniform2f(glGetUniformLocation(p, "u_phys_size"), (float)r->phys_w, (float)r->phys_h);
    glUniform1f(glGetUniformLocation(p, "u_border"), r->border);
    glUniform1f(glGetUniformLocation(p, "u_payload"), r->payload);
    glUniform1i(glGetUniformLocation(p, "u_debug"), v->debug);
    glUniform1f(glGetUniformLocation(p, "u_alpha_test"), v->alpha_test);
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_2D, r->tex_phys);
    draw(r);
    glDisable(GL_FRAMEBUFFER_SRGB);
    glReadBuffer(GL_COLOR_ATTACHMENT1);
    glReadPixels(0, 0, (GLsizei)r->width, (GLsizei)r->height, GL_RED_INTEGER, GL_UNSIGNED_BYTE,
                 r->fallback_pixels);
    uint64_t n = 0;
    for (size_t i = 0; i < (size_t)r->width * r->height; i++)
        n += r->fallback_pixels[i] != 0;
    glUseProgram(0);
    return n;
}

void vtv_render_feedback(struct vtv_render *r, const struct vtv_view *v, float jx, float jy,
                         uint16_t *out)
{
    static const GLuint zero[4] = {0, 0, 0, 0};
    glBindFramebuffer(GL_FRAMEBUFFER, r->fb_fbo);
    glViewport(0, 0, (GLsizei)r->fb_width, (GLsizei)r->fb_height);
    glEnable(GL_DEPTH_TEST);
    glClearBufferuiv(GL_COLOR, 0, zero);
    glClear(GL_DEPTH_BUFFER_BIT);
    GLuint p = r->prog_feedback;
    glUseProgram(p);
    /* At 1/k of the resolution the gradients are k times larger: bias back to full resolution. */
    float bias = log2f((float)r->fb_width / (float)r->width);
    common_uniforms(r, p, v, bias);
    glUniform2f(glGetUniformLocation(p, "u_jitter"), jx, jy);
    draw(r);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glReadPixels(0, 0, (GLsizei)r->fb_width, (GLsizei)r->fb_height, GL_RGBA_INTEGER,
                 GL_UNSIGNED_SHORT, out);
    glUseProgram(0);
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

GLuint vtv_render_reference_begin(struct vtv_render *r, const struct vtv_view *v)
{
    begin_main(r);
    GLuint p = r->prog_reference;
    glUseProgram(p);
    glUniformMatrix4fv(glGetUniformLocation(p, "u_mvp"), 1, GL_FALSE, v->mvp);
    glUniform2f(glGetUniformLocation(p, "u_jitter"), 0.0f, 0.0f);
    glUniform1i(glGetUniformLocation(p, "u_tex"), 0);
    glUniform1i(glGetUniformLocation(p, "u_mode"), 1);
    glUniform1f(glGetUniformLocation(p, "u_alpha_test"), v->alpha_test);
    glActiveTexture(GL_TEXTURE0);
    return p;
}

void vtv_render_reference_end(void)
{
    glDisable(GL_FRAMEBUFFER_SRGB);
    glUseProgram(0);
}

void vtv_render_reference(struct vtv_render *r, const struct vtv_view *v)
{
    vtv_render_reference_begin(r, v);
    glBindTexture(GL_TEXTURE_2D, r->tex_reference);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER,
                    v->trilinear ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR_MIPMAP_NEAREST);
    draw(r);
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
