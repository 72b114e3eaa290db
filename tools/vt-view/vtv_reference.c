/* vt-view --reference-scene: the original OBJ with one plain GL texture per material. */
#include "vtv_reference.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "tool_common.h"
#include "vt_atlas_alpha.h"
#include "vt_error.h"
#include "vt_image.h"
#include "vt_image_input.h"
#include "vt_obj.h"
#include "vtv_mipmap.h"
#include "vtv_tangent.h"

/* Triangles of one material, in order of first use: per vertex its position (3 floats) and its
 * texcoord as read (2 doubles, v flipped); per triangle the shift of its face (2 doubles). */
struct mat_geo {
    char *name;
    float *pos, *normal; /* 3 floats per vertex (normal 0 0 0: none) */
    uint32_t *keys;      /* v, vt, vn per vertex (vtv_tangents) */
    double *uv, *shift;
    size_t n, cap; /* vertices (3 per triangle) */
    uint64_t faces;
};

struct load_ctx {
    const char *path;
    struct vt_mtl *mtls;
    size_t mtl_count;
    struct mat_geo *mats;
    uint32_t mat_count, cur;
    char **tex_paths;     /* parallel to s->textures */
    uint32_t *tex_colour; /* parallel: the colour it was loaded as (enum vts_colour) */
    bool *tex_cutout;     /* parallel: its alpha is a cut-out (lib/atlas's rule) */
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
    float *nrm = realloc(m->normal, nc * 3 * sizeof(float));
    if (nrm)
        m->normal = nrm;
    uint32_t *keys = realloc(m->keys, nc * 3 * sizeof(uint32_t));
    if (keys)
        m->keys = keys;
    if (!p || !uv || !sh || !nrm || !keys)
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
        for (int i = 0; i < 3; i++)
            m->normal[m->n * 3 + i] =
                k[j]->vn != VT_OBJ_NONE ? (float)vt_obj_normals(obj)[(size_t)k[j]->vn * 3 + i] : 0;
        m->keys[m->n * 3] = k[j]->v;
        m->keys[m->n * 3 + 1] = k[j]->vt;
        m->keys[m->n * 3 + 2] = k[j]->vn;
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
    if (st == 0)
        c->mats[c->cur].faces++;
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

/* Whether the alpha of rgba (n texels) is a cut-out, by vt-atlas's rule (lib/atlas: clear at most
 * 1/8, solid at least 7/8, few texels in between). */
static bool alpha_cutout(const uint8_t *rgba, size_t n)
{
    struct vt_atlas_alpha_counts c = {.texels = n, .read = n};
    for (size_t i = 0; i < n; i++) {
        uint8_t a = rgba[i * 4 + 3];
        c.clear += a <= 31;             /* 31/255 <= 1/8 < 32/255 */
        c.partial += a > 31 && a < 224; /* 224/255 >= 7/8 > 223/255 */
    }
    return vt_atlas_alpha_is_cutout(&c);
}

/* Loads path as a texture of kind colour (sRGB: decoded to linear when the file is sRGB and the
 * frame is; normal; data), its mips made like the store's. *cutout: its alpha is a cut-out. */
static int load_texture(const char *path, bool srgb, uint32_t colour, GLuint *out, bool *cutout,
                        struct vts_error *err)
{
    struct vt_source src;
    struct vt_image img = {0};
    uint8_t *rgba = NULL;
    *cutout = false;
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
    *cutout = in->has_alpha && alpha_cutout(rgba, (size_t)in->width * in->height);
    glGenTextures(1, out);
    glBindTexture(GL_TEXTURE_2D, *out);
    /* mips as the store's: box in linear light for an sRGB texture in an sRGB frame */
    if (colour == VTS_COLOUR_SRGB && !(srgb && in->colour == VTS_COLOUR_SRGB))
        colour = VTS_COLOUR_LINEAR;
    st = vtv_mipmap_upload(rgba, in->width, in->height, colour,
                           in->has_alpha && colour != VTS_COLOUR_DATA, path, err);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
cleanup:
    free(rgba);
    vt_image_release(&img);
    vt_source_close(&src);
    return st;
}

/* The texture of map file path loaded as colour (shared by the materials that use it so). */
static int texture_of(struct vtv_reference_scene *s, struct load_ctx *c, const char *path,
                      bool srgb, uint32_t colour, GLuint *tex, bool *cutout, struct vts_error *err)
{
    for (uint32_t i = 0; i < s->texture_count; i++)
        if (c->tex_colour[i] == colour && strcmp(c->tex_paths[i], path) == 0) {
            *tex = s->textures[i];
            *cutout = c->tex_cutout[i];
            return 0;
        }
    uint32_t n = s->texture_count;
    GLuint *t = realloc(s->textures, (n + 1) * sizeof(*t));
    if (t)
        s->textures = t;
    char **p = realloc(c->tex_paths, (n + 1) * sizeof(*p));
    if (p)
        c->tex_paths = p;
    uint32_t *col = realloc(c->tex_colour, (n + 1) * sizeof(*col));
    if (col)
        c->tex_colour = col;
    bool *cut = realloc(c->tex_cutout, (n + 1) * sizeof(*cut));
    if (cut)
        c->tex_cutout = cut;
    if (!t || !p || !col || !cut || !(p[n] = strdup(path)))
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
    t[n] = 0;
    col[n] = colour;
    cut[n] = false;
    s->texture_count++;
    int st = load_texture(path, srgb, colour, &t[n], &cut[n], err);
    *tex = t[n];
    *cutout = cut[n];
    return st;
}

/* The maps, constants and features of the part drawing g (the first MTL file that defines its
 * material, as vt-atlas reads). A map whose file does not exist is left out with a warning (as
 * vt-atlas warns and uses the constant). */
static int setup_part(struct vtv_reference_scene *s, struct load_ctx *c, const struct mat_geo *g,
                      bool srgb, struct vtv_reference_part *part, struct vts_error *err)
{
    static const unsigned kinds[][2] = {{VT_MTL_MAP_KD, VTV_MAP_DIFFUSE},
                                        {VT_MTL_MAP_NORM, VTV_MAP_NORMAL},
                                        {VT_MTL_MAP_BUMP, VTV_MAP_NORMAL},
                                        {VT_MTL_MAP_KS, VTV_MAP_SPECULAR},
                                        {VT_MTL_MAP_D, VTV_MAP_ALPHA}};
    static const uint32_t colour[VTV_MAP_COUNT] = {VTS_COLOUR_SRGB, VTS_COLOUR_NORMAL,
                                                   VTS_COLOUR_SRGB, VTS_COLOUR_DATA};
    const struct vt_mtl_material *mat = NULL;
    for (size_t i = 0; i < c->mtl_count && !mat; i++)
        mat = vt_mtl_find(&c->mtls[i], g->name);
    unsigned maps = 0;
    bool cutout = false, moved = false;
    for (size_t i = 0; mat && i < sizeof(kinds) / sizeof(kinds[0]); i++) {
        const struct vt_mtl_map *m = &mat->maps[kinds[i][0]];
        unsigned k = kinds[i][1];
        struct stat file;
        if (!m->path || (maps & (1u << k)))
            continue;
        if (stat(m->path, &file) != 0 && errno == ENOENT) { /* as vt-atlas: the constant */
            vt_log(VT_LOG_WARN, "'%s': %s: the material's constant", m->path, strerror(errno));
            continue;
        }
        struct vtv_reference_map *rm = &part->maps[k];
        bool cut = false;
        int st = texture_of(s, c, m->path, srgb, colour[k], &rm->tex, &cut, err);
        if (st != 0)
            return st;
        maps |= 1u << k;
        cutout |= k == VTV_MAP_DIFFUSE && cut;
        rm->clamp = m->clamp;
        /* (u s + o, 1 - ((1 - v') s + o)) on the drawn (u, v' = 1 - v) */
        rm->st[0] = (float)m->s[0];
        rm->st[1] = (float)m->s[1];
        rm->st[2] = (float)m->o[0];
        rm->st[3] = (float)(1.0 - m->s[1] - m->o[1]);
        moved |= (m->options & (VT_MTL_OPT_S | VT_MTL_OPT_O)) != 0;
    }
    part->clamp = (maps & (1u << VTV_MAP_DIFFUSE)) ? part->maps[VTV_MAP_DIFFUSE].clamp : false;
    /* the per-face shift is whole repeats only without -s/-o */
    part->clamp |= moved;
    vtv_material_from_mtl(mat, maps, cutout, &part->mat);
    part->features = vtv_material_features(&part->mat);
    return 0;
}

/* The vertices of g as drawn (x y z u v floats) into out. A repeating material's texcoords get
 * their face's shift subtracted in double before the conversion to float: u = 2600.3 has a float
 * step of 1/4096 (a sixteenth of a texel of a 256-texel texture, and interpolation adds more),
 * 0.3 one of 1/2^25; repeat addressing shows the same texels either way, and the shift is the same
 * over a face, so the derivatives (the level of detail) do not change. A clamped material keeps
 * its texcoords. */
static void write_vertices(const struct mat_geo *g, bool repeat, float *out)
{
    for (size_t j = 0; j < g->n; j++, out += VTV_VERTEX_FLOATS) {
        const double *sh = g->shift + j / 3 * 2;
        memset(out, 0, VTV_VERTEX_FLOATS * sizeof(float));
        memcpy(out, g->pos + j * 3, 3 * sizeof(float));
        out[3] = (float)(g->uv[j * 2] - (repeat ? sh[0] : 0.0));
        out[4] = (float)(g->uv[j * 2 + 1] - (repeat ? sh[1] : 0.0));
        memcpy(out + 5, g->normal + j * 3, 3 * sizeof(float));
    }
}

static void upload_geometry(struct vtv_reference_scene *s, const float *all, size_t total)
{
    glGenVertexArrays(1, &s->vao);
    glGenBuffers(1, &s->vbo);
    glBindVertexArray(s->vao);
    glBindBuffer(GL_ARRAY_BUFFER, s->vbo);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(total * VTV_VERTEX_FLOATS * sizeof(float)), all,
                 GL_STATIC_DRAW);
    vtv_render_vertex_layout();
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
        free(c->mats[i].normal);
        free(c->mats[i].keys);
    }
    free(c->mats);
    for (uint32_t i = 0; i < texture_count; i++)
        free(c->tex_paths ? c->tex_paths[i] : NULL);
    free(c->tex_paths);
    free(c->tex_colour);
    free(c->tex_cutout);
}

static int cmp_part(const void *a, const void *b)
{
    const struct vtv_reference_part *x = a, *y = b;
    bool bx = x->features & VTV_F_ALPHA_BLEND, by = y->features & VTV_F_ALPHA_BLEND;
    if (bx != by)
        return bx ? 1 : -1;
    if (x->features != y->features)
        return x->features < y->features ? -1 : 1;
    return x->first < y->first ? -1 : x->first > y->first; /* order of first use */
}

/* The vertex buffer in part order (first: the material's index until then), with tangents. */
static int lay_out(struct vtv_reference_scene *s, const struct load_ctx *c, float *all,
                   uint32_t *keys, struct vts_error *err)
{
    size_t at = 0;
    for (uint32_t i = 0; i < s->part_count; i++) {
        struct vtv_reference_part *part = &s->parts[i];
        const struct mat_geo *g = &c->mats[part->first];
        write_vertices(g, !part->clamp, all + at * VTV_VERTEX_FLOATS);
        memcpy(keys + at * 3, g->keys, g->n * 3 * sizeof(uint32_t));
        part->first = (uint32_t)at;
        at += g->n;
    }
    return vtv_tangents(all, keys, at) != 0 ? vt_error_set(err, VTS_ERR_NOMEM, "out of memory") : 0;
}

int vtv_reference_scene_load(struct vtv_reference_scene *s, struct vtv_render *r,
                             const char *obj_path, bool srgb, struct vts_error *err)
{
    memset(s, 0, sizeof(*s));
    struct load_ctx c = {.path = obj_path, .cur = UINT32_MAX};
    for (int k = 0; k < 3; k++) {
        c.lo[k] = 1e300;
        c.hi[k] = -1e300;
    }
    float *all = NULL;
    uint32_t *keys = NULL;
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
    all = malloc(total * VTV_VERTEX_FLOATS * sizeof(float)); /* total < mat_count * 3 * 2^27 */
    keys = malloc(total * 3 * sizeof(uint32_t));
    if (!s->parts || !all || !keys) {
        st = vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
        goto cleanup;
    }
    for (uint32_t i = 0; i < c.mat_count && st == 0; i++) {
        struct vtv_reference_part *part = &s->parts[s->part_count++];
        part->first = i;
        part->count = (uint32_t)c.mats[i].n;
        st = setup_part(s, &c, &c.mats[i], srgb, part, err);
        struct vtv_variant *v =
            st == 0 ? vtv_render_variant(r, part->features, 1u << VTV_PROG_REFERENCE, err) : NULL;
        if (st == 0 && !v)
            st = err->status;
        if (v)
            v->faces += c.mats[i].faces;
    }
    if (st != 0)
        goto cleanup;
    qsort(s->parts, s->part_count, sizeof(*s->parts), cmp_part);
    st = lay_out(s, &c, all, keys, err);
    if (st != 0)
        goto cleanup;
    memcpy(s->lo, c.lo, sizeof(s->lo));
    memcpy(s->hi, c.hi, sizeof(s->hi));
    upload_geometry(s, all, total);
cleanup:
    free(all);
    free(keys);
    release_ctx(&c, s->texture_count);
    if (st != 0)
        vtv_reference_scene_free(s);
    return st;
}

void vtv_reference_scene_draw(struct vtv_render *r, const struct vtv_reference_scene *s,
                              const struct vtv_view *v)
{
    vtv_render_reference_begin(r);
    glBindVertexArray(s->vao);
    for (uint32_t i = 0; i < s->part_count; i++) {
        const struct vtv_reference_part *part = &s->parts[i];
        struct vtv_variant *var = vtv_render_variant(r, part->features, 0, NULL);
        GLuint p = var ? var->prog[VTV_PROG_REFERENCE] : 0;
        if (!p)
            continue;
        glUseProgram(p);
        float st[VTV_MAP_COUNT][4];
        for (int k = 0; k < VTV_MAP_COUNT; k++) {
            const struct vtv_reference_map *m = &part->maps[k];
            memcpy(st[k], m->tex ? m->st : (const float[4]){1, 1, 0, 0}, sizeof(st[k]));
            glActiveTexture(GL_TEXTURE0 + k);
            glBindTexture(GL_TEXTURE_2D, m->tex);
            if (!m->tex)
                continue;
            GLint wrap = m->clamp ? GL_CLAMP_TO_EDGE : GL_REPEAT;
            glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, wrap);
            glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, wrap);
            glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER,
                            v->trilinear ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR_MIPMAP_NEAREST);
            glTexParameterf(GL_TEXTURE_2D, GL_TEXTURE_MAX_ANISOTROPY,
                            (float)(v->aniso > 1 ? v->aniso : 1));
        }
        glActiveTexture(GL_TEXTURE0);
        vtv_render_reference_uniforms(r, p, &part->mat, v, (const float(*)[4])st);
        bool blend = part->features & VTV_F_ALPHA_BLEND;
        if (blend) {
            glEnablei(GL_BLEND, 0);
            glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
            glDepthMask(GL_FALSE);
        }
        glDrawArrays(GL_TRIANGLES, (GLint)part->first, (GLsizei)part->count);
        if (blend) {
            glDisablei(GL_BLEND, 0);
            glDepthMask(GL_TRUE);
        }
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
