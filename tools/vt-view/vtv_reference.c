/* vt-view --reference-scene: the original OBJ with one plain GL texture per material. */
#include "vtv_reference.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "tool_common.h"
#include "vt_error.h"
#include "vt_image.h"
#include "vt_image_input.h"
#include "vt_obj.h"
#include "vtv_mipmap.h"

/* Triangles of one material, in order of first use: per vertex its position (3 floats) and its
 * texcoord as read (2 doubles, v flipped); per triangle the shift of its face (2 doubles). */
struct mat_geo {
    char *name;
    float *pos;
    double *uv, *shift;
    size_t n, cap; /* vertices (3 per triangle) */
};

struct load_ctx {
    const char *path;
    struct vt_mtl *mtls;
    size_t mtl_count;
    struct mat_geo *mats;
    uint32_t mat_count, cur;
    char **tex_paths; /* parallel to s->textures */
    double lo[3], hi[3];
};

static int on_mtllib(void *user, const struct vt_obj *obj, const char *mtl_path, uint64_t line,
                     struct vts_error *err)
{
    (void)obj;
    (void)line;
    struct load_ctx *c = user;
    struct vt_mtl *m = realloc(c->mtls, (c->mtl_count + 1) * sizeof(*m));
    if (!m)
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
    c->mtls = m;
    memset(&m[c->mtl_count], 0, sizeof(*m));
    int st = vt_mtl_read(mtl_path, NULL, &m[c->mtl_count], err);
    c->mtl_count++; /* released either way */
    return st;
}

static int material_index(struct load_ctx *c, const char *name, struct vts_error *err)
{
    if (c->cur < c->mat_count && strcmp(c->mats[c->cur].name, name) == 0)
        return 0;
    for (c->cur = 0; c->cur < c->mat_count; c->cur++)
        if (strcmp(c->mats[c->cur].name, name) == 0)
            return 0;
    struct mat_geo *m = realloc(c->mats, (c->mat_count + 1) * sizeof(*m));
    if (!m)
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
    c->mats = m;
    memset(&m[c->mat_count], 0, sizeof(*m));
    m[c->mat_count].name = strdup(name);
    if (!m[c->mat_count].name)
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
    c->cur = c->mat_count++;
    return 0;
}

/* Room for one more triangle. */
static int grow(struct mat_geo *m)
{
    if (m->n + 3 <= m->cap)
        return 0;
    if (m->cap >= ((size_t)3 << 27))
        return VTS_ERR_LIMIT;
    size_t nc = m->cap ? m->cap * 2 : 768; /* a multiple of 3 */
    float *p = realloc(m->pos, nc * 3 * sizeof(float));
    if (p)
        m->pos = p;
    double *uv = realloc(m->uv, nc * 2 * sizeof(double));
    if (uv)
        m->uv = uv;
    double *sh = realloc(m->shift, nc / 3 * 2 * sizeof(double));
    if (sh)
        m->shift = sh;
    if (!p || !uv || !sh)
        return VTS_ERR_NOMEM;
    m->cap = nc;
    return 0;
}

/* Corner k's texcoord as drawn: (u, 1 - v), v flipped as in vtv_mesh.c (v = 1 is the first row);
 * (0, 0) without one. */
static void corner_uv(const struct vt_obj *obj, const struct vt_obj_corner *k, double uv[2])
{
    uv[0] = uv[1] = 0.0;
    if (k->vt != VT_OBJ_NONE) {
        const double *t = vt_obj_texcoords(obj) + (size_t)k->vt * 3;
        uv[0] = t[0];
        uv[1] = 1.0 - t[1];
    }
}

/* Appends the triangle of corners k[0..2] of a face whose shift is shift[0..1]. */
static int push_triangle(struct load_ctx *c, const struct vt_obj *obj,
                         const struct vt_obj_corner *const k[3], const double shift[2])
{
    struct mat_geo *m = &c->mats[c->cur];
    int st = grow(m);
    if (st != 0)
        return st;
    memcpy(m->shift + m->n / 3 * 2, shift, 2 * sizeof(double));
    for (int j = 0; j < 3; j++, m->n++) {
        const double *p = vt_obj_positions(obj) + (size_t)k[j]->v * 3;
        for (int i = 0; i < 3; i++) {
            m->pos[m->n * 3 + i] = (float)p[i];
            c->lo[i] = fmin(c->lo[i], p[i]);
            c->hi[i] = fmax(c->hi[i], p[i]);
        }
        corner_uv(obj, k[j], m->uv + m->n * 2);
    }
    return 0;
}

/* The shift of a face: the floor of its smallest u and (flipped) v over the corners that have a
 * texcoord (0 without any). */
static void face_shift(const struct vt_obj *obj, const struct vt_obj_face *f, double shift[2])
{
    double lo[2] = {INFINITY, INFINITY};
    for (uint32_t i = 0; i < f->corner_count; i++)
        if (f->corners[i].vt != VT_OBJ_NONE) {
            double uv[2];
            corner_uv(obj, &f->corners[i], uv);
            lo[0] = fmin(lo[0], uv[0]);
            lo[1] = fmin(lo[1], uv[1]);
        }
    for (int i = 0; i < 2; i++)
        shift[i] = isfinite(lo[i]) ? floor(lo[i]) : 0.0;
}

static int on_face(void *user, const struct vt_obj *obj, const struct vt_obj_face *f,
                   struct vts_error *err)
{
    struct load_ctx *c = user;
    int st = material_index(c, f->material, err);
    double shift[2];
    face_shift(obj, f, shift);
    for (uint32_t i = 1; st == 0 && i + 1 < f->corner_count; i++) { /* fanned as in vtv_mesh.c */
        const struct vt_obj_corner *k[3] = {&f->corners[0], &f->corners[i], &f->corners[i + 1]};
        st = push_triangle(c, obj, k, shift);
        if (st != 0 && st != VTS_ERR_NOMEM)
            return vt_error_set(err, st, "'%s':%llu: too many triangles", c->path,
                                (unsigned long long)f->line);
        if (st != 0)
            return vt_error_set(err, st, "out of memory");
    }
    return st;
}

static void to_rgba8(const struct vt_image *img, uint8_t *out)
{
    uint32_t ch = img->channels;
    for (uint32_t y = 0; y < img->height; y++)
        for (uint32_t x = 0; x < img->width; x++) {
            const void *px = vt_image_at(img, x, y);
            uint8_t s[4] = {0, 0, 0, 255};
            for (uint32_t k = 0; k < ch; k++)
                s[k] = img->sample == VTS_SAMPLE_U8
                           ? ((const uint8_t *)px)[k]
                           : (uint8_t)((((const uint16_t *)px)[k] * 255u + 32767u) / 65535u);
            uint8_t *o = out + ((size_t)y * img->width + x) * 4;
            bool grey = ch <= 2;
            o[0] = s[0];
            o[1] = grey ? s[0] : s[1];
            o[2] = grey ? s[0] : s[2];
            o[3] = ch == 2 ? s[1] : ch == 4 ? s[3] : 255;
        }
}

static int load_texture(const char *path, bool srgb, GLuint *out, struct vts_error *err)
{
    struct vt_source src;
    struct vt_image img = {0};
    uint8_t *rgba = NULL;
    int st = vt_image_input_open(path, NULL, &src, err);
    if (st != 0)
        return st;
    const struct vt_source_info *in = &src.info;
    GLint max_size = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
    if (in->sample != VTS_SAMPLE_U8 && in->sample != VTS_SAMPLE_U16) {
        st = vt_error_set(err, VTS_ERR_UNSUPPORTED,
                          "'%s': --reference-scene shows 8- and 16-bit textures only", path);
        goto cleanup;
    }
    if (in->width > (uint32_t)max_size || in->height > (uint32_t)max_size) {
        st = vt_error_set(err, VTS_ERR_LIMIT, "'%s': %ux%u is larger than GL_MAX_TEXTURE_SIZE %d",
                          path, in->width, in->height, max_size);
        goto cleanup;
    }
    st = vt_image_alloc(&img, in->width, in->height, in->channels, in->sample, err);
    if (st == 0)
        st = vt_source_read(&src, 0, 0, &img, err);
    if (st != 0)
        goto cleanup;
    rgba = malloc((size_t)in->width * in->height * 4); /* each edge <= GL_MAX_TEXTURE_SIZE */
    if (!rgba) {
        st = vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
        goto cleanup;
    }
    to_rgba8(&img, rgba);
    glGenTextures(1, out);
    glBindTexture(GL_TEXTURE_2D, *out);
    /* mips as the store's: box in linear light for an sRGB texture in an sRGB frame */
    st = vtv_mipmap_upload(rgba, in->width, in->height, srgb && in->colour == VTS_COLOUR_SRGB,
                           in->has_alpha, path, err);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
cleanup:
    free(rgba);
    vt_image_release(&img);
    vt_source_close(&src);
    return st;
}

static float srgb_to_linear(double c)
{
    c = c < 0 ? 0 : c > 1 ? 1 : c;
    return (float)(c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4));
}

/* The texture or colour of material m (first MTL file that defines it, as vt-atlas does) and its
 * addressing: repeat, unless its map_Kd statement says -clamp on. */
static int setup_part(struct vtv_reference_scene *s, struct load_ctx *c, const struct mat_geo *g,
                      bool srgb, struct vtv_reference_part *part, struct vts_error *err)
{
    const char *name = g->name;
    const struct vt_mtl_material *mat = NULL;
    for (size_t i = 0; i < c->mtl_count && !mat; i++)
        mat = vt_mtl_find(&c->mtls[i], name);
    double kd[3] = {0.8, 0.8, 0.8};
    if (mat && (mat->flags & VT_MTL_HAS_KD))
        memcpy(kd, mat->kd, sizeof(kd));
    for (int k = 0; k < 3; k++)
        part->kd[k] = srgb ? srgb_to_linear(kd[k]) : (float)kd[k];
    part->kd[3] = 1.0f;
    const char *path = mat ? mat->maps[VT_MTL_MAP_KD].path : NULL;
    part->clamp = path && mat->maps[VT_MTL_MAP_KD].clamp;
    struct stat file;
    if (path && stat(path, &file) != 0 && errno == ENOENT) { /* as vt-atlas: the constant */
        vt_log(VT_LOG_WARN, "'%s': %s: the material's constant", path, strerror(errno));
        path = NULL;
    }
    if (!path)
        return 0;
    for (uint32_t i = 0; i < s->texture_count; i++)
        if (strcmp(c->tex_paths[i], path) == 0) {
            part->tex = s->textures[i];
            return 0;
        }
    GLuint *t = realloc(s->textures, (s->texture_count + 1) * sizeof(*t));
    if (t)
        s->textures = t;
    char **p = realloc(c->tex_paths, (s->texture_count + 1) * sizeof(*p));
    if (p)
        c->tex_paths = p;
    if (!t || !p || !(p[s->texture_count] = strdup(path)))
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
    t[s->texture_count] = 0;
    s->texture_count++;
    int st = load_texture(path, srgb, &t[s->texture_count - 1], err);
    part->tex = t[s->texture_count - 1];
    return st;
}

/* The vertices of g as drawn (x y z u v floats) into out. A repeating material's texcoords get
 * their face's shift subtracted in double before the conversion to float: u = 2600.3 has a float
 * step of 1/4096 (a sixteenth of a texel of a 256-texel texture, and interpolation adds more),
 * 0.3 one of 1/2^25; repeat addressing shows the same texels either way, and the shift is the same
 * over a face, so the derivatives (the level of detail) do not change. A clamped material keeps
 * its texcoords. */
static void write_vertices(const struct mat_geo *g, bool repeat, float *out)
{
    for (size_t j = 0; j < g->n; j++, out += 5) {
        const double *sh = g->shift + j / 3 * 2;
        memcpy(out, g->pos + j * 3, 3 * sizeof(float));
        out[3] = (float)(g->uv[j * 2] - (repeat ? sh[0] : 0.0));
        out[4] = (float)(g->uv[j * 2 + 1] - (repeat ? sh[1] : 0.0));
    }
}

static void upload_geometry(struct vtv_reference_scene *s, const float *all, size_t total)
{
    glGenVertexArrays(1, &s->vao);
    glGenBuffers(1, &s->vbo);
    glBindVertexArray(s->vao);
    glBindBuffer(GL_ARRAY_BUFFER, s->vbo);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(total * 5 * sizeof(float)), all, GL_STATIC_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 5 * sizeof(float), (void *)0);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 2, GL_FLOAT, GL_FALSE, 5 * sizeof(float), (void *)(3 * sizeof(float)));
    glBindVertexArray(0);
}

static void release_ctx(struct load_ctx *c, uint32_t texture_count)
{
    for (size_t i = 0; i < c->mtl_count; i++)
        vt_mtl_release(&c->mtls[i]);
    free(c->mtls);
    for (uint32_t i = 0; i < c->mat_count; i++) {
        free(c->mats[i].name);
        free(c->mats[i].pos);
        free(c->mats[i].uv);
        free(c->mats[i].shift);
    }
    free(c->mats);
    for (uint32_t i = 0; i < texture_count; i++)
        free(c->tex_paths ? c->tex_paths[i] : NULL);
    free(c->tex_paths);
}

int vtv_reference_scene_load(struct vtv_reference_scene *s, const char *obj_path, bool srgb,
                             struct vts_error *err)
{
    memset(s, 0, sizeof(*s));
    struct load_ctx c = {.path = obj_path, .cur = UINT32_MAX};
    for (int k = 0; k < 3; k++) {
        c.lo[k] = 1e300;
        c.hi[k] = -1e300;
    }
    float *all = NULL;
    struct vt_obj *obj = vt_obj_create(NULL, err);
    if (!obj)
        return err->status;
    struct vt_obj_callbacks cb = {.mtllib = on_mtllib, .face = on_face, .user = &c};
    int st = vt_obj_read(obj, obj_path, &cb, err);
    vt_obj_destroy(obj);
    size_t total = 0;
    for (uint32_t i = 0; i < c.mat_count; i++)
        total += c.mats[i].n;
    if (st == 0 && total == 0)
        st = vt_error_set(err, VTS_ERR_BAD_INPUT, "'%s': no faces", obj_path);
    if (st != 0)
        goto cleanup;
    s->parts = calloc(c.mat_count, sizeof(*s->parts));
    all = malloc(total * 5 * sizeof(float)); /* total < mat_count * 3 * 2^27 */
    if (!s->parts || !all) {
        st = vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
        goto cleanup;
    }
    size_t first = 0;
    for (uint32_t i = 0; i < c.mat_count && st == 0; i++) {
        struct vtv_reference_part *part = &s->parts[s->part_count++];
        part->first = (uint32_t)first;
        part->count = (uint32_t)c.mats[i].n;
        st = setup_part(s, &c, &c.mats[i], srgb, part, err);
        write_vertices(&c.mats[i], !part->clamp, all + first * 5);
        first += c.mats[i].n;
    }
    if (st != 0)
        goto cleanup;
    memcpy(s->lo, c.lo, sizeof(s->lo));
    memcpy(s->hi, c.hi, sizeof(s->hi));
    upload_geometry(s, all, total);
cleanup:
    free(all);
    release_ctx(&c, s->texture_count);
    if (st != 0)
        vtv_reference_scene_free(s);
    return st;
}

void vtv_reference_scene_draw(struct vtv_render *r, const struct vtv_reference_scene *s,
                              const struct vtv_view *v)
{
    GLuint p = vtv_render_reference_begin(r, v);
    GLint mode = glGetUniformLocation(p, "u_mode"), kd = glGetUniformLocation(p, "u_kd");
    glBindVertexArray(s->vao);
    for (uint32_t i = 0; i < s->part_count; i++) {
        const struct vtv_reference_part *part = &s->parts[i];
        glUniform1i(mode, part->tex ? 1 : 0);
        glUniform4fv(kd, 1, part->kd);
        if (part->tex) {
            GLint wrap = part->clamp ? GL_CLAMP_TO_EDGE : GL_REPEAT;
            glBindTexture(GL_TEXTURE_2D, part->tex);
            glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, wrap);
            glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, wrap);
            glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER,
                            v->trilinear ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR_MIPMAP_NEAREST);
        }
        glDrawArrays(GL_TRIANGLES, (GLint)part->first, (GLsizei)part->count);
    }
    glBindVertexArray(0);
    vtv_render_reference_end();
}

void vtv_reference_scene_free(struct vtv_reference_scene *s)
{
    if (s->texture_count)
        glDeleteTextures((GLsizei)s->texture_count, s->textures);
    if (s->vbo)
        glDeleteBuffers(1, &s->vbo);
    if (s->vao)
        glDeleteVertexArrays(1, &s->vao);
    free(s->textures);
    free(s->parts);
    memset(s, 0, sizeof(*s));
}
