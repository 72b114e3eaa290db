/* The placement: sizes, copies and scales per entry, sharing, then vt_atlas_pack(), then the
 * layout (vt_atlas_place.h). */
#include "vt_atlas_place.h"

#include <assert.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "vt_checked.h"
#include "vt_error.h"

#define CONSTANT_CELL 4 /* texels of an entry without any texture */

/* ---- per-entry sizes ---- */

struct sizing {
    uint32_t src_w, src_h; /* largest texture of the entry (CONSTANT_CELL without) */
    bool textured;
    double density;
    double scale;
    uint32_t w, h;               /* one copy in the atlas */
    uint32_t repeat_u, repeat_v; /* copies */
    int32_t origin_u, origin_v;
    bool split; /* the split choice: vt-offset cuts the faces */
    bool wrap;  /* one copy that wraps: split, or a fit entry holding the whole texture of a
                   material that repeats */
    uint32_t crop_x, crop_y, crop_w, crop_h; /* texels of the block of copies the entry holds */
};

static void set_choice(struct sizing *z, enum vt_atlas_choice c, uint32_t ru, uint32_t rv)
{
    z->repeat_u = ru;
    z->repeat_v = rv;
    z->origin_u = z->origin_v = 0;
    z->split = z->wrap = c == VT_ATLAS_CHOICE_SPLIT;
}

static int check_wrap(const struct vt_atlas_material *m, const struct vt_atlas_place_options *o,
                      struct sizing *z, struct vts_error *err)
{
    uint32_t ru, rv;
    bool box = z->textured && m->has_uv && m->umax >= m->umin;
    enum vt_atlas_choice c =
        vt_atlas_choose(o->wrap, o->max_repeat, box, m->umin, m->umax, m->vmin, m->vmax, &ru, &rv);
    if (c == VT_ATLAS_CHOICE_REPORT)
        return vt_error_set(err, VTS_ERR_BAD_INPUT,
                            "'%s':%llu: material '%s' (u %g..%g, v %g..%g) has charts that leave "
                            "one copy of its texture (u %g..%g, v %g..%g moved by whole "
                            "repeats): use --wrap auto, replicate or split",
                            m->obj, (unsigned long long)m->first_line, m->name, m->raw_umin,
                            m->raw_umax, m->raw_vmin, m->raw_vmax, m->umin, m->umax, m->vmin,
                            m->vmax);
    if (c == VT_ATLAS_CHOICE_TOO_MANY)
        return vt_error_set(err, VTS_ERR_LIMIT,
                            "'%s':%llu: material '%s' needs more than --max-repeat %u copies "
                            "(charts moved by whole repeats cover u %g..%g, v %g..%g): use "
                            "--wrap auto or split",
                            m->obj, (unsigned long long)m->first_line, m->name, o->max_repeat,
                            m->umin, m->umax, m->vmin, m->vmax);
    set_choice(z, c, ru, rv);
    return 0;
}

/* The crop of a sized entry whose charts cover the box (the whole block without one). */
static void set_crop(struct sizing *z, bool has_box, double umin, double umax, double vmin,
                     double vmax)
{
    z->crop_x = z->crop_y = 0;
    z->crop_w = z->w * z->repeat_u;
    z->crop_h = z->h * z->repeat_v;
    if (!has_box || z->wrap || !z->textured)
        return;
    vt_atlas_crop_axis(umin, umax, z->w, z->repeat_u, false, &z->crop_x, &z->crop_w);
    vt_atlas_crop_axis(vmin, vmax, z->h, z->repeat_v, true, &z->crop_y, &z->crop_h);
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* Target = the lower median of the textured materials' densities; each scale is the power of two
 * nearest (in log2) to sqrt(target / density), clamped to 1/max_scale..max_scale. */
static int density_scales(struct sizing *z, uint32_t n, uint32_t max_scale, double *target)
{
    double *d = malloc((n ? n : 1) * sizeof *d);
    if (!d)
        return VTS_ERR_NOMEM;
    uint32_t k = 0;
    for (uint32_t i = 0; i < n; i++)
        if (z[i].density > 0 && isfinite(z[i].density))
            d[k++] = z[i].density;
    *target = 0;
    if (k) {
        qsort(d, k, sizeof *d, cmp_double);
        *target = d[(k - 1) / 2];
        double lim = log2((double)max_scale);
        for (uint32_t i = 0; i < n; i++) {
            if (!(z[i].density > 0 && isfinite(z[i].density)))
                continue;
            double e = round(0.5 * log2(*target / z[i].density));
            e = e < -lim ? -lim : e > lim ? lim : e;
            z[i].scale = ldexp(1.0, (int)e);
        }
    }
    free(d);
    return 0;
}

static int size_entry(struct sizing *z, const char *name, struct vts_error *err)
{
    double w = (double)z->src_w * z->scale, h = (double)z->src_h * z->scale;
    if (z->scale < 1) {
        w = ceil(w);
        h = ceil(h);
    }
    if (w * z->repeat_u > UINT32_MAX || h * z->repeat_v > UINT32_MAX)
        return vt_error_set(err, VTS_ERR_LIMIT, "material '%s' needs more than 2^32 texels", name);
    z->w = (uint32_t)w;
    z->h = (uint32_t)h;
    return 0;
}

/* ---- sharing: one entry for materials with the same textures ---- */

#define NO_GROUP       UINT32_MAX
#define SHARE_ATTEMPTS 64 /* groups with the same key tried before a material opens its own */

/* The materials of one entry: the first names it, the others are its aliases. */
struct group {
    uint32_t first, last, count; /* members, linked through next_member[] */
    uint32_t next_same;          /* the next group with the same hash, or NO_GROUP */
    uint32_t tail_same;          /* in the first group of a hash: the last one */
    uint64_t hash;
    bool has_uv; /* union of the members' texcoord ranges */
    double umin, umax, vmin, vmax;
    struct sizing z; /* of the first member, with the union's copies */
};

static uint64_t mix(uint64_t h, uint64_t v)
{
    h ^= v + 0x9e3779b97f4a7c15ull + (h << 6) + (h >> 2);
    return h * 0xff51afd7ed558ccdull;
}

static uint64_t double_bits(double d)
{
    d += 0.0; /* -0 and +0 alike */
    uint64_t b;
    memcpy(&b, &d, sizeof b);
    return b;
}

/* Hash of what decides sharing: per layer the texture file or the constant, and the scale. */
static uint64_t share_hash(const struct vt_atlas_material *m, const unsigned *kinds,
                           uint32_t layer_count, double scale)
{
    uint64_t h = 1469598103934665603ull;
    for (uint32_t k = 0; k < layer_count; k++) {
        int32_t t = m->texture[kinds[k]];
        h = mix(h, (uint64_t)(int64_t)t);
        for (int c = 0; c < 4 && t < 0; c++)
            h = mix(h, double_bits(m->fill[kinds[k]][c]));
    }
    return mix(h, double_bits(scale));
}

static bool same_content(const struct vt_atlas_material *a, const struct vt_atlas_material *b,
                         const unsigned *kinds, uint32_t layer_count)
{
    for (uint32_t k = 0; k < layer_count; k++) {
        unsigned kind = kinds[k];
        if (a->texture[kind] != b->texture[kind])
            return false;
        for (int c = 0; c < 4 && a->texture[kind] < 0; c++)
            if (a->fill[kind][c] != b->fill[kind][c])
                return false;
    }
    return true;
}

/* Adds material m (sized by zm) to g when the union of their boxes costs no more atlas texels
 * than the two apart (and, replicated, stays within max_repeat copies). */
static bool try_join(struct group *g, const struct vt_atlas_material *m, const struct sizing *zm,
                     const struct vt_atlas_place_options *o)
{
    if (!zm->textured || !m->has_uv)
        return true; /* constants have one cell; no texcoords widen nothing */
    double umin = m->umin, umax = m->umax, vmin = m->vmin, vmax = m->vmax;
    if (g->has_uv) {
        umin = fmin(umin, g->umin), umax = fmax(umax, g->umax);
        vmin = fmin(vmin, g->vmin), vmax = fmax(vmax, g->vmax);
    }
    uint32_t ru, rv, gu, gv, mu, mv;
    enum vt_atlas_choice c =
        vt_atlas_choose(o->wrap, o->max_repeat, true, umin, umax, vmin, vmax, &ru, &rv);
    if (c == VT_ATLAS_CHOICE_REPORT || c == VT_ATLAS_CHOICE_TOO_MANY)
        return false;
    enum vt_atlas_choice cg = vt_atlas_choose(o->wrap, o->max_repeat, g->has_uv, g->umin, g->umax,
                                              g->vmin, g->vmax, &gu, &gv);
    enum vt_atlas_choice cm =
        vt_atlas_choose(o->wrap, o->max_repeat, true, m->umin, m->umax, m->vmin, m->vmax, &mu, &mv);
    double apart = vt_atlas_box_cost(cg, g->umin, g->umax, g->vmin, g->vmax) +
                   vt_atlas_box_cost(cm, m->umin, m->umax, m->vmin, m->vmax);
    if (g->has_uv && vt_atlas_box_cost(c, umin, umax, vmin, vmax) > apart)
        return false;
    if ((uint64_t)g->z.w * ru > UINT32_MAX || (uint64_t)g->z.h * rv > UINT32_MAX)
        return false;
    g->has_uv = true;
    g->umin = umin, g->umax = umax, g->vmin = vmin, g->vmax = vmax;
    set_choice(&g->z, c, ru, rv);
    return true;
}

static void open_group(struct group *g, uint32_t i, const struct vt_atlas_material *m,
                       const struct sizing *z, uint64_t hash, uint32_t self)
{
    *g = (struct group){.first = i,
                        .last = i,
                        .count = 1,
                        .next_same = NO_GROUP,
                        .tail_same = self,
                        .hash = hash,
                        .has_uv = z->textured && m->has_uv,
                        .umin = m->umin,
                        .umax = m->umax,
                        .vmin = m->vmin,
                        .vmax = m->vmax,
                        .z = *z};
}

/* Groups the materials into entries (in order of first use); *count gets the number. A material
 * joins the first (oldest) group with its content that takes it. Without share every material
 * is its own group. */
static int group_materials(const struct vt_atlas_scene *scene,
                           const struct vt_atlas_place_options *o, const unsigned *kinds,
                           uint32_t layer_count, const struct sizing *z, bool share,
                           struct group *groups, uint32_t *next_member, uint32_t *count)
{
    uint32_t n = scene->material_count, ng = 0;
    size_t cap = 64;
    while (cap < 2 * (size_t)n)
        cap *= 2;
    uint32_t *table = share ? malloc(cap * sizeof *table) : NULL; /* hash -> first group */
    if (share && !table)
        return VTS_ERR_NOMEM;
    if (table)
        memset(table, 0xff, cap * sizeof *table);
    for (uint32_t i = 0; i < n; i++) {
        const struct vt_atlas_material *m = &scene->materials[i];
        next_member[i] = NO_GROUP;
        if (!share) {
            open_group(&groups[ng], i, m, &z[i], 0, ng);
            ng++;
            continue;
        }
        uint64_t h = share_hash(m, kinds, layer_count, z[i].scale);
        size_t slot = h & (cap - 1);
        while (table[slot] != NO_GROUP && groups[table[slot]].hash != h)
            slot = (slot + 1) & (cap - 1);
        uint32_t g = table[slot], tries = 0;
        for (; g != NO_GROUP && tries < SHARE_ATTEMPTS; g = groups[g].next_same, tries++) {
            struct group *gr = &groups[g];
            if (gr->z.scale == z[i].scale &&
                same_content(&scene->materials[gr->first], m, kinds, layer_count) &&
                try_join(gr, m, &z[i], o)) {
                next_member[gr->last] = i;
                gr->last = i;
                gr->count++;
                break;
            }
        }
        if (g != NO_GROUP && tries < SHARE_ATTEMPTS)
            continue; /* joined */
        open_group(&groups[ng], i, m, &z[i], h, ng);
        if (table[slot] == NO_GROUP) {
            table[slot] = ng;
        } else {
            struct group *head = &groups[table[slot]];
            groups[head->tail_same].next_same = ng;
            head->tail_same = ng;
        }
        ng++;
    }
    free(table);
    *count = ng;
    return 0;
}

/* ---- the layout ---- */

static int fill_texture(struct vt_layout_texture *t, const struct vt_atlas_scene *scene,
                        const struct vt_atlas_material *m, unsigned kind, const char *output)
{
    int32_t ti = m->texture[kind];
    if (ti < 0) {
        memcpy(t->fill, m->fill[kind], sizeof t->fill);
        return 0;
    }
    const struct vt_atlas_texture *tx = &scene->textures[ti];
    t->path = vt_atlas_place_relative_path(output, tx->path);
    t->width = tx->width;
    t->height = tx->height;
    return t->path ? 0 : VTS_ERR_NOMEM;
}

static int set_aliases(struct vt_layout_entry *e, const struct vt_atlas_scene *scene,
                       const struct group *g, const uint32_t *next_member)
{
    if (g->count < 2)
        return 0;
    e->aliases = calloc(g->count - 1, sizeof *e->aliases);
    if (!e->aliases)
        return VTS_ERR_NOMEM;
    for (uint32_t i = next_member[g->first]; i != NO_GROUP; i = next_member[i]) {
        e->aliases[e->alias_count] = strdup(scene->materials[i].name);
        if (!e->aliases[e->alias_count])
            return VTS_ERR_NOMEM;
        e->alias_count++;
    }
    return 0;
}

/* One material per scene material (entry names and aliases alike): its group's entry, the layers
 * it has a texture in, its constants; sorted by name as the layout wants them. */
static int fill_materials(const struct vt_atlas_scene *scene, const unsigned *kinds,
                          uint32_t layer_count, const struct group *groups, uint32_t group_count,
                          const uint32_t *next_member, struct vt_layout *l, struct vts_error *err)
{
    int rc = vt_layout_alloc_materials(l, scene->material_count, err);
    uint32_t n = 0;
    for (uint32_t i = 0; !rc && i < group_count; i++)
        for (uint32_t mi = groups[i].first; mi != NO_GROUP; mi = next_member[mi]) {
            const struct vt_atlas_material *sm = &scene->materials[mi];
            struct vt_layout_material *m = &l->materials[n++];
            *m = sm->features;
            m->entry = i;
            m->layer_mask = 0;
            for (uint32_t k = 0; k < layer_count; k++)
                m->layer_mask |= (sm->texture[kinds[k]] >= 0 ? 1u : 0u) << k;
            m->name = strdup(sm->name);
            if (!m->name)
                rc = vt_error_set(err, VTS_ERR_NOMEM, "out of memory building the layout");
        }
    assert(rc || n == scene->material_count);
    vt_layout_sort_materials(l);
    return rc;
}

static int fill_layout(const struct vt_atlas_scene *scene, const struct vt_atlas_place_options *o,
                       const unsigned *kinds, uint32_t layer_count, const struct group *groups,
                       uint32_t group_count, const uint32_t *next_member,
                       const struct vt_atlas_rect *rects, struct vt_layout *l,
                       struct vts_error *err)
{
    int rc = vt_layout_alloc(l, layer_count, group_count, err);
    if (rc)
        return rc;
    l->tile_content = o->tile_content;
    l->border = o->border;
    l->generator = o->generator ? strdup(o->generator) : NULL;
    bool nomem = o->generator && !l->generator;
    for (uint32_t k = 0; k < layer_count; k++) {
        l->layers[k].name = strdup(vt_atlas_kind_name(kinds[k]));
        l->layers[k].map = strdup(vt_atlas_kind_map(kinds[k]));
        l->layers[k].colour = vt_atlas_kind_colour(kinds[k]);
        nomem |= !l->layers[k].name || !l->layers[k].map;
    }
    bool grid = o->grid_rows && o->grid_cols;
    for (uint32_t i = 0; i < group_count && !nomem; i++) {
        const struct sizing *z = &groups[i].z;
        const struct vt_atlas_material *m = &scene->materials[groups[i].first];
        struct vt_layout_entry *e = &l->entries[i];
        const struct vt_atlas_rect *r = &rects[grid ? 0 : i];
        e->name = strdup(m->name);
        e->width = z->w;
        e->height = z->h;
        e->repeat_u = z->repeat_u;
        e->repeat_v = z->repeat_v;
        e->crop_x = z->crop_x;
        e->crop_y = z->crop_y;
        e->crop_width = z->crop_w;
        e->crop_height = z->crop_h;
        e->wrap = z->wrap;
        e->origin_u = z->origin_u;
        e->origin_v = z->origin_v;
        e->scale = z->scale;
        e->x = r->x;
        e->y = r->y;
        e->cell_left = r->x - r->cell_x;
        e->cell_top = r->y - r->cell_y;
        e->cell_width = r->cell_width;
        e->cell_height = r->cell_height;
        e->alignment = r->alignment;
        if (grid) { /* piece (row, col) of the group, edge to edge (never shared); the pieces
                       on the group's outer edge take the gutter and padding of the group cell */
            uint32_t row = i / o->grid_cols, col = i % o->grid_cols;
            uint32_t gx0 = col ? 0 : e->cell_left, gy0 = row ? 0 : e->cell_top;
            uint32_t right = r->cell_x + r->cell_width, bottom = r->cell_y + r->cell_height;
            e->x += col * z->w;
            e->y += row * z->h;
            e->cell_left = gx0;
            e->cell_top = gy0;
            e->cell_width = col + 1 < o->grid_cols ? gx0 + z->w : right - (e->x - gx0);
            e->cell_height = row + 1 < o->grid_rows ? gy0 + z->h : bottom - (e->y - gy0);
            uint32_t a = r->alignment;
            while (a > 1 && (e->x % a || e->y % a || gx0 % a || gy0 % a || e->cell_width % a ||
                             e->cell_height % a))
                a >>= 1;
            e->alignment = a;
            e->group = 1;
        }
        nomem |= !e->name || set_aliases(e, scene, &groups[i], next_member) != 0;
        for (uint32_t k = 0; k < layer_count && !nomem; k++)
            nomem |= fill_texture(&e->textures[k], scene, m, kinds[k], o->output) != 0;
    }
    if (nomem)
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory building the layout");
    return fill_materials(scene, kinds, layer_count, groups, group_count, next_member, l, err);
}

static int check_grid(const struct vt_atlas_scene *scene, const struct vt_atlas_place_options *o,
                      struct vts_error *err)
{
    if ((uint64_t)o->grid_rows * o->grid_cols != scene->material_count)
        return vt_error_set(err, VTS_ERR_ARG, "--grid %ux%u needs %llu files, not %u", o->grid_rows,
                            o->grid_cols, (unsigned long long)o->grid_rows * o->grid_cols,
                            scene->material_count);
    const struct vt_atlas_texture *t0 = &scene->textures[scene->materials[0].texture[0]];
    for (uint32_t i = 1; i < scene->material_count; i++) {
        const struct vt_atlas_texture *t = &scene->textures[scene->materials[i].texture[0]];
        if (t->width != t0->width || t->height != t0->height)
            return vt_error_set(
                err, VTS_ERR_BAD_INPUT,
                "'%s' is %ux%u, not %ux%u like '%s': --grid pieces must have one size", t->path,
                t->width, t->height, t0->width, t0->height, t0->path);
    }
    if ((uint64_t)t0->width * o->grid_cols > UINT32_MAX ||
        (uint64_t)t0->height * o->grid_rows > UINT32_MAX)
        return vt_error_set(err, VTS_ERR_LIMIT, "the --grid is larger than 2^32 texels");
    return 0;
}

static void prepare_sizes(const struct vt_atlas_scene *scene, struct sizing *z)
{
    for (uint32_t i = 0; i < scene->material_count; i++) {
        const struct vt_atlas_material *m = &scene->materials[i];
        z[i] = (struct sizing){.src_w = CONSTANT_CELL, .src_h = CONSTANT_CELL, .scale = 1};
        uint64_t best = 0;
        for (unsigned k = 0; k < VT_ATLAS_KIND_COUNT; k++) {
            if (m->texture[k] < 0)
                continue;
            const struct vt_atlas_texture *t = &scene->textures[m->texture[k]];
            if ((uint64_t)t->width * t->height > best) {
                best = (uint64_t)t->width * t->height;
                z[i].src_w = t->width;
                z[i].src_h = t->height;
                z[i].textured = true;
            }
        }
        if (z[i].textured && m->world_area > 0 && m->uv_area > 0)
            z[i].density = m->uv_area * (double)z[i].src_w * z[i].src_h / m->world_area;
    }
}

/* Atlas texels had every entry held its whole block of copies (0 when that does not pack). */
static uint64_t whole_area(const struct group *groups, uint32_t ng,
                           const struct vt_atlas_place_options *o)
{
    struct vt_atlas_rect *r = calloc(ng, sizeof *r);
    if (!r)
        return 0;
    for (uint32_t i = 0; i < ng; i++) {
        r[i].width = groups[i].z.w * groups[i].z.repeat_u;
        r[i].height = groups[i].z.h * groups[i].z.repeat_v;
    }
    struct vt_atlas_pack_options po = {
        .tile_content = o->tile_content, .max_edge = 1u << 24, .gutter = o->gutter};
    struct vt_atlas_pack_stats st;
    struct vts_error e = {0};
    uint64_t area = vt_atlas_pack(r, ng, &po, &st, &e) ? 0 : (uint64_t)st.width * st.height;
    free(r);
    return area;
}

int vt_atlas_place(const struct vt_atlas_scene *scene, const struct vt_atlas_place_options *o,
                   struct vt_layout *layout, struct vt_atlas_place_report *report,
                   struct vts_error *err)
{
    return vt_atlas_place_choices(scene, o, layout, report, NULL, err);
}

static int place_choices(const struct vt_atlas_scene *scene, const struct vt_atlas_place_options *o,
                         struct vt_layout *layout, struct vt_atlas_place_report *report,
                         struct vt_atlas_place_choice *choices, struct vts_error *err)
{
    memset(layout, 0, sizeof *layout);
    memset(report, 0, sizeof *report);
    uint32_t n = scene->material_count;
    if (n == 0)
        return vt_error_set(err, VTS_ERR_BAD_INPUT,
                            "nothing to place: no face uses a material and no texture is listed");
    bool grid = o->grid_rows && o->grid_cols;
    /* Only the layers some entry has a texture for; diffuse alone when none has any. */
    unsigned kinds[VT_ATLAS_KIND_COUNT];
    uint32_t layer_count = 0;
    for (unsigned k = 0; k < VT_ATLAS_KIND_COUNT; k++) {
        bool used = false;
        for (uint32_t i = 0; i < n && !used; i++)
            used = scene->materials[i].texture[k] >= 0;
        if (used)
            kinds[layer_count++] = k;
    }
    if (!layer_count)
        kinds[layer_count++] = VT_ATLAS_DIFFUSE;
    struct sizing *z = calloc(n, sizeof *z);
    struct vt_atlas_rect *rects = calloc(n, sizeof *rects);
    struct group *groups = calloc(n, sizeof *groups);
    uint32_t *next_member = calloc(n, sizeof *next_member), ng = 0;
    int rc = 0;
    if (!z || !rects || !groups || !next_member) {
        rc = vt_error_set(err, VTS_ERR_NOMEM, "out of memory for %u entries", n);
        goto out;
    }
    if (grid && (rc = check_grid(scene, o, err)))
        goto out;
    prepare_sizes(scene, z);
    for (uint32_t i = 0; i < n && !rc; i++)
        rc = check_wrap(&scene->materials[i], o, &z[i], err);
    if (!rc && o->density && !grid &&
        (rc = density_scales(z, n, o->max_scale, &report->target_density)))
        vt_error_set(err, rc, "out of memory");
    for (uint32_t i = 0; i < n && !rc; i++)
        rc = size_entry(&z[i], scene->materials[i].name, err);
    if (!rc &&
        (rc = group_materials(scene, o, kinds, layer_count, z, !grid, groups, next_member, &ng)))
        vt_error_set(err, rc, "out of memory");
    if (rc)
        goto out;
    report->materials = n;
    for (uint32_t i = 0; i < n; i++) {
        report->charts += scene->materials[i].charts;
        report->moved_charts += scene->materials[i].moved_charts;
    }
    for (uint32_t i = 0; i < ng; i++) {
        struct group *gr = &groups[i];
        struct sizing *g = &gr->z;
        if (!grid)
            set_crop(g, gr->has_uv && gr->umax >= gr->umin, gr->umin, gr->umax, gr->vmin, gr->vmax);
        else
            set_crop(g, false, 0, 0, 0, 0);
        /* A fit entry that holds its whole texture wraps too, as the material's texture does
         * in an engine (MTL maps repeat unless -clamp on): filtering at the texture's edge reads
         * the opposite edge, not a copy of the edge itself. */
        bool clamp = false;
        for (uint32_t mi = gr->first; mi != NO_GROUP; mi = next_member[mi])
            clamp |= scene->materials[mi].clamp;
        if (!grid && g->textured && gr->has_uv && !g->wrap && !clamp && g->repeat_u == 1 &&
            g->repeat_v == 1 && g->crop_w == g->w && g->crop_h == g->h)
            g->wrap = true;
        rects[i].width = g->crop_w;
        rects[i].height = g->crop_h;
        report->scaled += g->scale != 1;
        report->replicated += g->repeat_u * g->repeat_v > 1;
        report->constant += !g->textured;
        report->split += g->split;
        report->fit += g->textured && !g->split && g->repeat_u * g->repeat_v == 1;
        report->cropped +=
            (uint64_t)g->crop_w * g->crop_h < (uint64_t)g->w * g->repeat_u * g->h * g->repeat_v;
        if (gr->count > 1) {
            report->shared += gr->count;
            report->shared_cells++;
        }
        if (choices)
            for (uint32_t mi = gr->first; mi != NO_GROUP; mi = next_member[mi])
                choices[mi] = (struct vt_atlas_place_choice){.how = !g->textured ? "constant"
                                                                    : g->split   ? "split"
                                                                    : g->repeat_u * g->repeat_v > 1
                                                                        ? "replicate"
                                                                        : "fit",
                                                             .entry = i,
                                                             .repeat_u = g->repeat_u,
                                                             .repeat_v = g->repeat_v,
                                                             .crop_width = g->crop_w,
                                                             .crop_height = g->crop_h};
    }
    if (!grid && report->cropped)
        report->whole_area = whole_area(groups, ng, o);
    if (grid) {
        rects[0].width = z[0].w * o->grid_cols;
        rects[0].height = z[0].h * o->grid_rows;
    }
    struct vt_atlas_pack_options po = {
        .tile_content = o->tile_content, .max_edge = o->max_edge, .gutter = o->gutter};
    rc = vt_atlas_pack(rects, grid ? 1 : ng, &po, &report->pack, err);
    if (!rc)
        rc = fill_layout(scene, o, kinds, layer_count, groups, ng, next_member, rects, layout, err);
    if (!rc) {
        layout->width = report->pack.width;
        layout->height = report->pack.height;
    }
out:
    free(z);
    free(rects);
    free(groups);
    free(next_member);
    return rc;
}

/* The pack materials of scene (material indices in order) as layout->wangs, sorted by name. */
static int fill_wangs(const struct vt_atlas_scene *scene, const uint32_t *idx, uint32_t count,
                      const struct vt_atlas_place_options *o, struct vt_layout *l,
                      struct vts_error *err)
{
    int rc = vt_layout_alloc_wangs(l, count, err);
    for (uint32_t i = 0; !rc && i < count; i++) {
        const struct vt_atlas_material *sm = &scene->materials[idx[i]];
        struct vt_layout_wang *w = &l->wangs[i];
        w->m = sm->features;
        w->m.entry = 0;
        w->m.layer_mask = 0;
        w->scale = sm->wang_scale;
        w->m.name = strdup(sm->name);
        w->pack = vt_atlas_place_relative_path(o->output, sm->wang);
        if (!w->m.name || !w->pack)
            rc = vt_error_set(err, VTS_ERR_NOMEM, "out of memory building the layout");
    }
    if (!rc) {
        vt_layout_sort_materials(l);
        rc = vt_layout_index(l, err);
    }
    return rc;
}

/* Materials that name a Wang pack (docs/wang.md) get no entry: the others are placed as a scene
 * of their own, the pack materials recorded in layout->wangs (choices: "wang", entry UINT32_MAX).
 */
int vt_atlas_place_choices(const struct vt_atlas_scene *scene,
                           const struct vt_atlas_place_options *o, struct vt_layout *layout,
                           struct vt_atlas_place_report *report,
                           struct vt_atlas_place_choice *choices, struct vts_error *err)
{
    uint32_t n = scene->material_count, nw = 0;
    for (uint32_t i = 0; i < n; i++)
        nw += scene->materials[i].wang != NULL;
    if (nw == 0)
        return place_choices(scene, o, layout, report, choices, err);
    memset(layout, 0, sizeof *layout);
    memset(report, 0, sizeof *report);
    if (nw == n)
        return vt_error_set(err, VTS_ERR_BAD_INPUT,
                            "'%s': nothing to place: every material the faces use names a Wang "
                            "pack (vt_wang); an atlas needs at least one other",
                            scene->materials[0].obj ? scene->materials[0].obj : "scene");
    struct vt_atlas_scene sub = *scene;
    uint32_t *idx = malloc((size_t)n * sizeof *idx);
    struct vt_atlas_place_choice *sub_choices =
        choices ? calloc(n - nw, sizeof *sub_choices) : NULL;
    sub.materials = malloc((size_t)(n - nw) * sizeof *sub.materials);
    sub.material_count = n - nw;
    int rc = 0;
    if (!idx || !sub.materials || (choices && !sub_choices)) {
        rc = vt_error_set(err, VTS_ERR_NOMEM, "out of memory for %u materials", n);
        goto out;
    }
    /* idx: the placed materials first (sub's order), then the pack materials */
    for (uint32_t i = 0, a = 0, b = n - nw; i < n; i++) {
        if (scene->materials[i].wang) {
            idx[b++] = i;
        } else {
            sub.materials[a] = scene->materials[i];
            idx[a++] = i;
        }
    }
    rc = place_choices(&sub, o, layout, report, sub_choices, err);
    if (!rc)
        rc = fill_wangs(scene, idx + (n - nw), nw, o, layout, err);
    if (!rc) {
        report->wang = nw;
    }
    for (uint32_t i = 0; !rc && choices && i < n; i++)
        choices[idx[i]] = i < n - nw
                              ? sub_choices[i]
                              : (struct vt_atlas_place_choice){.how = "wang", .entry = UINT32_MAX};
out:
    free(idx);
    free(sub_choices);
    free(sub.materials);
    return rc;
}
