/* vt-view --wang (vtv_wang.h). */
#include "vtv_wang.h"

#include <epoxy/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "tool_common.h"
#include "vt_wang_pack.h"
#include "vtv_context.h"
#include "vtv_mipmap.h"
#include "vtv_output.h"
#include "vtv_program.h"
#include "vtv_wang_gl.h"
#include "vtv_wang_glsl.h"

struct wang_view {
    const struct vtv_options *o;
    struct vts_store *store;
    struct vt_wang_info info;
    uint32_t levels;
    uint32_t origin_x, origin_y; /* the frame's first tile, mod the hash size */
    double shift_x, shift_y;     /* the position inside it, in [0, 1) tiles */
    double extent_x, extent_y;   /* tiles across and down the frame */
    GLuint program, vao, fbo, rb, pack, perm, order, image, tilemap;
};

static GLuint compile_program(bool tiletex, const char *what, struct vts_error *err)
{
    static const char version[] = "#version 330 core\n";
    const char *fragment[3] = {version, vtv_wang_hash_glsl, vtv_wang_tiletex_glsl};
    const char *vertex[1] = {vtv_wang_vertex_glsl}, *reference[1] = {vtv_wang_reference_glsl};
    return tiletex ? vtv_program_build(vertex, 1, fragment, 3, what, err)
                   : vtv_program_build(vertex, 1, reference, 1, what, err);
}

static int load_pack(struct wang_view *w, struct vts_error *err)
{
    struct vtv_wang_gl t = {0};
    int rc = vtv_wang_load_pack(w->store, &w->info, &t, err);
    w->pack = t.pack;
    w->perm = t.perm;
    w->order = t.order;
    w->levels = t.levels;
    return rc;
}

/* --tilemap (Wei's second implementation): the pack slot of every tile of one period of the hash
 * (n x n, through the C API's vt_wang_info_locate, the shuffled order included) as an RG16UI
 * texture; TileTex then reads it with one fetch instead of evaluating the hash. */
static int load_tilemap(struct wang_view *w, struct vts_error *err)
{
    uint32_t n = w->info.hash_n;
    if (n > 4096)
        return vt_error_set(err, VTS_ERR_LIMIT,
                            "--tilemap: the hash has %u entries, a map of more than 4096 x 4096 "
                            "tiles",
                            n);
    uint16_t *map = malloc((size_t)n * n * 2 * sizeof *map);
    if (!map)
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
    for (uint32_t y = 0; y < n; y++)
        for (uint32_t x = 0; x < n; x++) {
            uint32_t col, row;
            vt_wang_info_locate(&w->info, x, y, &col, &row);
            map[((size_t)y * n + x) * 2] = (uint16_t)col;
            map[((size_t)y * n + x) * 2 + 1] = (uint16_t)row;
        }
    glGenTextures(1, &w->tilemap);
    glBindTexture(GL_TEXTURE_2D, w->tilemap);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RG16UI, (GLsizei)n, (GLsizei)n, 0, GL_RG_INTEGER,
                 GL_UNSIGNED_SHORT, map);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    free(map);
    return 0;
}

/* --reference: the extent (from --origin) assembled on the CPU from level 0 (vt_wang_assemble, the
 * C API), RGBA, with the store's mip chain (vtv_mipmap_upload) cut at the pack's level count. */
static int load_reference(struct wang_view *w, struct vts_error *err)
{
    uint64_t ew = (uint64_t)w->o->extent_x * w->info.tile_px;
    uint64_t eh = (uint64_t)w->o->extent_y * w->info.tile_px;
    if (ew > 16384 || eh > 16384)
        return vt_error_set(err, VTS_ERR_LIMIT,
                            "--reference: the extent is %llux%llu texels, more than 16384 per side",
                            (unsigned long long)ew, (unsigned long long)eh);
    struct vt_image pack, out;
    int rc = vt_wang_pack_read_level(w->store, 0, &pack, err);
    if (rc)
        return rc;
    rc = vt_image_alloc(&out, (uint32_t)ew, (uint32_t)eh, pack.channels, VTS_SAMPLE_U8, err);
    uint8_t *rgba = rc ? NULL : malloc((size_t)ew * eh * 4);
    if (rc == 0 && !rgba)
        rc = vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
    if (rc == 0) {
        vt_wang_assemble(&w->info, &pack, 0, (uint64_t)w->o->origin_x * w->info.tile_px,
                         (uint64_t)w->o->origin_y * w->info.tile_px, &out);
        const uint8_t *src = out.pixels;
        for (size_t i = 0; i < (size_t)ew * eh; i++)
            for (uint32_t c = 0; c < 4; c++)
                rgba[i * 4 + c] = c < pack.channels ? src[i * pack.channels + c]
                                  : c == 3          ? 255
                                                    : src[i * pack.channels]; /* grey */
        glGenTextures(1, &w->image);
        glBindTexture(GL_TEXTURE_2D, w->image);
        rc = vtv_mipmap_upload(rgba, (uint32_t)ew, (uint32_t)eh, VTS_COLOUR_SRGB,
                               pack.channels % 2 == 0, vts_store_name(w->store), err);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, (GLint)w->levels - 1);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    }
    free(rgba);
    vt_image_release(&out);
    vt_image_release(&pack);
    return rc;
}

static int setup(struct wang_view *w, struct vts_error *err)
{
    const struct vtv_options *o = w->o;
    int rc = load_pack(w, err);
    if (rc == 0 && o->reference)
        rc = load_reference(w, err);
    else if (rc == 0 && o->wang_tilemap)
        rc = load_tilemap(w, err);
    if (rc)
        return rc;
    w->program = compile_program(!o->reference, o->reference ? "reference" : "TileTex", err);
    if (!w->program)
        return err->status;
    glGenVertexArrays(1, &w->vao);
    glGenRenderbuffers(1, &w->rb);
    glBindRenderbuffer(GL_RENDERBUFFER, w->rb);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_SRGB8_ALPHA8, (GLsizei)o->width, (GLsizei)o->height);
    glGenFramebuffers(1, &w->fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, w->fbo);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, w->rb);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        return vt_error_set(err, VTS_ERR_UNSUPPORTED, "the framebuffer is incomplete");
    GLuint p = w->program;
    glUseProgram(p);
    glUniform2f(glGetUniformLocation(p, "frame"), (float)o->width, (float)o->height);
    if (o->reference) {
        glUniform1i(glGetUniformLocation(p, "image"), 0);
        return 0;
    }
    glUniform1i(glGetUniformLocation(p, "pack"), 0);
    glUniform1i(glGetUniformLocation(p, "wang_perm"), 1);
    glUniform1i(glGetUniformLocation(p, "order"), 2);
    glUniform1i(glGetUniformLocation(p, "tilemap"), 3);
    glUniform1i(glGetUniformLocation(p, "use_map"), w->tilemap != 0);
    glUniform1ui(glGetUniformLocation(p, "wang_n"), w->info.hash_n);
    glUniform1ui(glGetUniformLocation(p, "wang_kh"), w->info.kh);
    glUniform1ui(glGetUniformLocation(p, "wang_kv"), w->info.kv);
    glUniform1ui(glGetUniformLocation(p, "cols"), w->info.cols);
    glUniform1ui(glGetUniformLocation(p, "rows"), w->info.rows);
    glUniform1i(glGetUniformLocation(p, "corners"), w->info.corners);
    glUniform1i(glGetUniformLocation(p, "shuffled"), w->info.order != NULL);
    w->origin_x = o->origin_x % w->info.hash_n;
    w->origin_y = o->origin_y % w->info.hash_n;
    w->extent_x = o->extent_x;
    w->extent_y = o->extent_y;
    return 0;
}

/* The view's uniforms (TileTex). */
static void set_view(const struct wang_view *w)
{
    GLuint p = w->program;
    glUniform2f(glGetUniformLocation(p, "extent"), (float)w->extent_x, (float)w->extent_y);
    glUniform2ui(glGetUniformLocation(p, "origin"), w->origin_x, w->origin_y);
    glUniform2f(glGetUniformLocation(p, "shift"), (float)w->shift_x, (float)w->shift_y);
}

/* Moves the origin by whole tiles of *shift (mod the hash size), keeping *shift in [0, 1). */
static void carry(uint32_t *origin, double *shift, uint32_t n)
{
    double whole = floor(*shift);
    *shift -= whole;
    int64_t k = (int64_t)fmod(whole, (double)n);
    *origin = (uint32_t)(((int64_t)*origin + k % n + n) % n);
}

/* A window's pan (pixels dragged or keyed) and zoom (around the frame's centre). */
static void move_view(struct wang_view *w, const struct vtv_input *in)
{
    double zoom = in->zoom > 0 ? in->zoom : 1;
    double ex = w->extent_x / zoom, ey = w->extent_y / zoom;
    if (ex < 1.0 / 64 || ey < 1.0 / 64 || ex > 65536 || ey > 65536)
        ex = w->extent_x, ey = w->extent_y;
    w->shift_x += (w->extent_x - ex) / 2 - in->pan_x * ex / w->o->width;
    w->shift_y += (w->extent_y - ey) / 2 - in->pan_y * ey / w->o->height;
    w->extent_x = ex;
    w->extent_y = ey;
    carry(&w->origin_x, &w->shift_x, w->info.hash_n);
    carry(&w->origin_y, &w->shift_y, w->info.hash_n);
}

static void draw(const struct wang_view *w)
{
    glBindFramebuffer(GL_FRAMEBUFFER, w->fbo);
    glViewport(0, 0, (GLsizei)w->o->width, (GLsizei)w->o->height);
    glEnable(GL_FRAMEBUFFER_SRGB);
    glUseProgram(w->program);
    if (!w->o->reference)
        set_view(w);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, w->o->reference ? w->image : w->pack);
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_2D, w->perm);
    glActiveTexture(GL_TEXTURE2);
    glBindTexture(GL_TEXTURE_2D, w->order);
    glActiveTexture(GL_TEXTURE3);
    glBindTexture(GL_TEXTURE_2D, w->tilemap);
    glBindVertexArray(w->vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glDisable(GL_FRAMEBUFFER_SRGB);
}

/* Reads the frame, rows top first. */
static int read_frame(const struct wang_view *w, uint8_t **out, struct vts_error *err)
{
    uint32_t fw = w->o->width, fh = w->o->height;
    uint8_t *rgba = malloc((size_t)fw * fh * 4), *row = malloc((size_t)fw * 4);
    if (!rgba || !row) {
        free(rgba);
        free(row);
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
    }
    glBindFramebuffer(GL_READ_FRAMEBUFFER, w->fbo);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, (GLsizei)fw, (GLsizei)fh, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
    for (uint32_t y = 0; y < fh / 2; y++) {
        memcpy(row, rgba + (size_t)y * fw * 4, fw * 4);
        memcpy(rgba + (size_t)y * fw * 4, rgba + (size_t)(fh - 1 - y) * fw * 4, fw * 4);
        memcpy(rgba + (size_t)(fh - 1 - y) * fw * 4, row, fw * 4);
    }
    free(row);
    *out = rgba;
    return 0;
}

static double now_ms(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec * 1e3 + (double)t.tv_nsec / 1e6;
}

/* Frames: headless o->frames, window until closed (or o->frames); the last one to the
 * screenshot. Logs the time per frame (glFinish after each; a first frame before is not timed). */
static int render(struct wang_view *w, struct vtv_context *ctx, struct vts_error *err)
{
    const struct vtv_options *o = w->o;
    draw(w); /* the shader's first use (compiled on first draw by some drivers): not timed */
    glFinish();
    double t0 = now_ms();
    uint32_t frames = 0;
    for (;;) {
        draw(w);
        glFinish();
        frames++;
        if (vtv_context_is_window(ctx)) {
            struct vtv_input in;
            uint32_t ww, wh;
            glBindFramebuffer(GL_READ_FRAMEBUFFER, w->fbo);
            glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
            glBlitFramebuffer(0, 0, (GLint)o->width, (GLint)o->height, 0, 0, (GLint)o->width,
                              (GLint)o->height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
            vtv_context_frame(ctx, &in, &ww, &wh);
            if (!o->reference)
                move_view(w, &in);
            if (in.quit || (o->frames && frames >= o->frames))
                break;
        } else if (frames >= o->frames) {
            break;
        }
    }
    double ms = (now_ms() - t0) / frames;
    vt_log(VT_LOG_INFO, "%s: %u frames of %ux%u, %.3f ms per frame",
           o->reference ? "reference" : "TileTex", frames, o->width, o->height, ms);
    if (!o->screenshot)
        return 0;
    uint8_t *rgba = NULL;
    int rc = read_frame(w, &rgba, err);
    if (rc == 0) {
        rc = vtv_write_screenshot(o->screenshot, rgba, o->width, o->height, err);
        free(rgba);
    }
    return rc;
}

int vtv_wang_run(const struct vtv_options *o)
{
    struct vts_error err = {0};
    struct wang_view w = {.o = o};
    struct vtv_context *ctx = NULL;
    int rc = 0;
    if (!(w.store = vts_open(o->wang_path, &err)) ||
        vt_wang_pack_open(w.store, &w.info, &err) != 0) { /* before any GL: plain errors */
        rc = err.status;
        goto out;
    }
    ctx = o->headless ? vtv_context_headless(&err)
                      : vtv_context_window(o->width, o->height, "vt-view --wang", &err);
    if (!ctx) {
        rc = err.status ? err.status : VTS_ERR_UNSUPPORTED;
        goto out;
    }
    rc = setup(&w, &err);
    if (rc == 0)
        rc = render(&w, ctx, &err);
out:
    if (rc)
        vt_log(VT_LOG_ERROR, "%s", err.message);
    if (ctx) {
        GLuint textures[5] = {w.pack, w.perm, w.order, w.image, w.tilemap};
        glDeleteTextures(5, textures);
        glDeleteFramebuffers(1, &w.fbo);
        glDeleteRenderbuffers(1, &w.rb);
        glDeleteVertexArrays(1, &w.vao);
        glDeleteProgram(w.program);
    }
    vtv_context_destroy(ctx);
    vt_wang_info_release(&w.info);
    vts_close(w.store);
    return rc ? VT_EXIT_BAD_INPUT : VT_EXIT_OK;
}
