/* Atlas layout model: validation (sizes, cells inside the atlas, no overlaps), lookup by name,
 * UV mapping. The JSON side is vt_layout_json.c. */
#include "vt_layout.h"
#include "internal/vt_rect_overlap.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "vt_checked.h"
#include "vt_error.h"
#include "vts.h"

void vt_layout_limits_default(struct vt_layout_limits *limits)
{
    *limits = (struct vt_layout_limits){
        .max_file_bytes = 1ull << 30, .max_entries = 1u << 20, .max_edge = 1u << 24};
}

static bool is_pow2(uint64_t v)
{
    return v && !(v & (v - 1));
}

/* ---- validation, shared by the reader and writers ---- */

static bool valid_layer_name(const char *s)
{
    size_t n = strlen(s);
    if (n == 0 || n > 63)
        return false;
    for (size_t i = 0; i < n; i++) {
        char c = s[i];
        if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
              c == '_' || c == '-'))
            return false;
    }
    return true;
}

static bool valid_scale(double s)
{
    if (!(s > 0) || !isfinite(s))
        return false;
    int e;
    double m = frexp(s, &e);
    return m == 0.5 && e - 1 >= -16 && e - 1 <= 16;
}

static const char *name_of(const struct vt_layout *l, const struct vt_layout_name *n)
{
    const struct vt_layout_entry *e = &l->entries[n->entry];
    return n->alias ? e->aliases[n->alias - 1] : e->name;
}

/* Sorting the names with a merge sort (stable, so equal names keep entry order; qsort lacks a
 * context argument and thread-safe globals are not worth it). */
static void sort_names(struct vt_layout_name *idx, struct vt_layout_name *tmp, size_t n,
                       const struct vt_layout *l)
{
    if (n < 2)
        return;
    size_t h = n / 2;
    sort_names(idx, tmp, h, l);
    sort_names(idx + h, tmp, n - h, l);
    size_t i = 0, j = h, k = 0;
    while (i < h && j < n)
        tmp[k++] = strcmp(name_of(l, &idx[j]), name_of(l, &idx[i])) < 0 ? idx[j++] : idx[i++];
    while (i < h)
        tmp[k++] = idx[i++];
    while (j < n)
        tmp[k++] = idx[j++];
    memcpy(idx, tmp, n * sizeof *idx);
}

/* A crop of 0 x 0 (either size 0) in a layout built in memory means the whole block of copies:
 * fills it in when the block's sizes fit in 32 bits (check_entry refuses the entry otherwise). */
static void fill_crop(struct vt_layout_entry *e)
{
    uint64_t bw = (uint64_t)e->width * e->repeat_u, bh = (uint64_t)e->height * e->repeat_v;
    if ((e->crop_width == 0 || e->crop_height == 0) && bw <= UINT32_MAX && bh <= UINT32_MAX) {
        e->crop_width = (uint32_t)bw;
        e->crop_height = (uint32_t)bh;
    }
}

/* The crop and wrap rules (docs/atlas-format.md): the crop lies inside the block of copies, and a
 * wrap entry holds one whole copy. NULL when they hold, else what is wrong. */
static const char *crop_wrap_problem(const struct vt_layout_entry *e)
{
    uint64_t bw = (uint64_t)e->width * e->repeat_u, bh = (uint64_t)e->height * e->repeat_v;
    if (e->crop_width == 0 || e->crop_height == 0) /* fill_crop: a block over 2^32 texels */
        return "does not fit in its cell";
    if ((uint64_t)e->crop_x + e->crop_width > bw || (uint64_t)e->crop_y + e->crop_height > bh)
        return "has a crop outside its block of copies";
    if (e->wrap && (e->repeat_u != 1 || e->repeat_v != 1))
        return "wraps but has a repeat other than [1, 1]";
    if (e->wrap && (e->crop_x || e->crop_y || e->crop_width != bw || e->crop_height != bh))
        return "wraps but has a crop smaller than its texture";
    return NULL;
}

/* Checks one entry against the atlas; the message names the entry. */
static int check_entry(const struct vt_layout *l, uint32_t i, const char *name,
                       struct vts_error *err)
{
    const struct vt_layout_entry *e = &l->entries[i];
    const char *what = NULL;
    /* the cell holds the crop (the whole block of copies without one) after the gutter */
    uint64_t cw = (uint64_t)e->crop_width + e->cell_left,
             ch = (uint64_t)e->crop_height + e->cell_top;
    if (!e->name || !e->name[0])
        what = "has no name";
    else if ((e->alias_count && !e->aliases) || e->alias_count == UINT32_MAX)
        what = "has no alias array or too many aliases";
    else if (e->width == 0 || e->height == 0)
        what = "has an empty size";
    else if (e->repeat_u == 0 || e->repeat_v == 0 || e->repeat_u > 65536 || e->repeat_v > 65536)
        what = "has a repeat outside 1..65536";
    else if ((what = crop_wrap_problem(e)) != NULL)
        ;
    else if (e->cell_left > e->x || e->cell_top > e->y)
        what = "has a cell starting after its texture (cell_x > x or cell_y > y)";
    else if (cw > e->cell_width || ch > e->cell_height)
        what = "does not fit in its cell";
    else if ((uint64_t)vt_layout_cell_x(e) + e->cell_width > l->width ||
             (uint64_t)vt_layout_cell_y(e) + e->cell_height > l->height)
        what = "has a cell outside the atlas";
    else if (!is_pow2(e->alignment) || e->x % e->alignment || e->y % e->alignment ||
             e->cell_left % e->alignment || e->cell_top % e->alignment ||
             e->cell_width % e->alignment || e->cell_height % e->alignment)
        what = "has an alignment that is not a power of two dividing its cell";
    else if (!valid_scale(e->scale))
        what = "has a scale that is not a power of two in 2^-16..2^16";
    if (what)
        return vt_error_set(err, VTS_ERR_BAD_INPUT, "'%s': entry %u ('%s') %s", name, i,
                            e->name ? e->name : "", what);
    for (uint32_t a = 0; a < e->alias_count; a++)
        if (!e->aliases[a] || !e->aliases[a][0])
            return vt_error_set(err, VTS_ERR_BAD_INPUT, "'%s': entry '%s' has an empty alias", name,
                                e->name);
    for (uint32_t k = 0; k < l->layer_count; k++) {
        const struct vt_layout_texture *t = &e->textures[k];
        if (t->path && (!t->path[0] || t->width == 0 || t->height == 0))
            return vt_error_set(err, VTS_ERR_BAD_INPUT,
                                "'%s': entry '%s' layer '%s': texture without a path or size", name,
                                e->name, l->layers[k].name);
        for (int c = 0; c < 4 && !t->path; c++)
            if (!(t->fill[c] >= 0 && t->fill[c] <= 1))
                return vt_error_set(err, VTS_ERR_BAD_INPUT,
                                    "'%s': entry '%s' layer '%s': fill outside 0..1", name, e->name,
                                    l->layers[k].name);
    }
    return 0;
}

/* No two cells overlap (vt_rect_overlap_find: a sweep in O(n log n)). */
static int check_overlaps(const struct vt_layout *l, const char *name, struct vts_error *err)
{
    uint32_t n = l->entry_count, a, b;
    struct vt_rect *r = malloc(((size_t)n + 1) * sizeof *r);
    if (!r)
        return vt_error_set(err, VTS_ERR_NOMEM, "'%s': out of memory checking %u cells", name, n);
    for (uint32_t i = 0; i < n; i++) {
        const struct vt_layout_entry *e = &l->entries[i];
        r[i] = (struct vt_rect){vt_layout_cell_x(e), vt_layout_cell_y(e), e->cell_width,
                                e->cell_height};
    }
    int found = vt_rect_overlap_find(r, n, &a, &b);
    free(r);
    if (found < 0)
        return vt_error_set(err, VTS_ERR_NOMEM, "'%s': out of memory checking %u cells", name, n);
    if (found > 0)
        return vt_error_set(err, VTS_ERR_BAD_INPUT, "'%s': the cells of '%s' and '%s' overlap",
                            name, l->entries[a].name, l->entries[b].name);
    return 0;
}

/* Builds l->by_name from every entry name and alias and checks that they are unique. */
static int index_names(struct vt_layout *l, const char *name, struct vts_error *err)
{
    free(l->by_name);
    l->by_name = NULL;
    l->name_count = 0;
    size_t n = l->entry_count;
    for (uint32_t i = 0; i < l->entry_count; i++)
        if (!vt_size_add(n, l->entries[i].alias_count, &n))
            return vt_error_set(err, VTS_ERR_LIMIT, "'%s': too many names", name);
    size_t bytes;
    if (!vt_size_mul(n + 1, sizeof(struct vt_layout_name), &bytes))
        return vt_error_set(err, VTS_ERR_LIMIT, "'%s': too many names", name);
    struct vt_layout_name *idx = malloc(bytes), *tmp = malloc(bytes);
    if (!idx || !tmp) {
        free(idx);
        free(tmp);
        return vt_error_set(err, VTS_ERR_NOMEM, "'%s': out of memory", name);
    }
    size_t k = 0;
    for (uint32_t i = 0; i < l->entry_count; i++)
        for (uint32_t a = 0; a <= l->entries[i].alias_count; a++)
            idx[k++] = (struct vt_layout_name){i, a};
    sort_names(idx, tmp, n, l);
    free(tmp);
    for (size_t i = 1; i < n; i++) {
        const struct vt_layout_name *p = &idx[i - 1], *q = &idx[i];
        if (strcmp(name_of(l, p), name_of(l, q)) != 0)
            continue;
        int rc;
        if (!p->alias && !q->alias)
            rc = vt_error_set(err, VTS_ERR_BAD_INPUT, "'%s': entry '%s' given twice", name,
                              name_of(l, q));
        else
            rc = vt_error_set(err, VTS_ERR_BAD_INPUT,
                              "'%s': name '%s' given twice (entries '%s' and '%s')", name,
                              name_of(l, q), l->entries[p->entry].name, l->entries[q->entry].name);
        free(idx);
        return rc;
    }
    l->by_name = idx;
    l->name_count = n;
    return 0;
}

static bool valid_colour(const double c[3])
{
    for (int k = 0; k < 3; k++)
        if (!isfinite(c[k]) || c[k] < 0)
            return false;
    return true;
}

/* What is wrong with the constants of material m, or NULL. */
static const char *material_problem(const struct vt_layout_material *m)
{
    if (!valid_colour(m->kd) || !valid_colour(m->ka) || !valid_colour(m->ks) ||
        !valid_colour(m->ke))
        return "has a colour (Kd, Ka, Ks, Ke) that is not finite and >= 0";
    if (!isfinite(m->ns) || m->ns < 0)
        return "has an Ns that is not finite and >= 0";
    if (!(m->d >= 0 && m->d <= 1))
        return "has a d outside 0..1";
    if (m->illum > 100)
        return "has an illum outside 0..100";
    if (m->alpha > VT_LAYOUT_ALPHA_BLEND)
        return "has an unknown alpha mode";
    return NULL;
}

/* The materials, when there are any: one per name of the name index, in its order (sorted by
 * name), each naming the entry that name belongs to, with maps only where the entry has a
 * texture. */
static int check_materials(const struct vt_layout *l, const char *name, struct vts_error *err)
{
    if (l->material_count == 0)
        return 0;
    if (l->material_count != l->name_count)
        return vt_error_set(err, VTS_ERR_BAD_INPUT,
                            "'%s': materials: %u materials for %zu material names (one for each "
                            "entry name and alias)",
                            name, l->material_count, l->name_count);
    for (uint32_t i = 0; i < l->material_count; i++) {
        const struct vt_layout_material *m = &l->materials[i];
        const struct vt_layout_name *n = &l->by_name[i];
        const char *want = name_of(l, n), *what;
        if (!m->name || strcmp(m->name, want) != 0)
            return vt_error_set(err, VTS_ERR_BAD_INPUT,
                                "'%s': materials[%u] ('%s'): expected material '%s' (one for each "
                                "entry name and alias, sorted by name)",
                                name, i, m->name ? m->name : "", want);
        if (m->entry != n->entry)
            return vt_error_set(err, VTS_ERR_BAD_INPUT,
                                "'%s': materials[%u] ('%s'): entry %u, but '%s' is a name of "
                                "entry '%s'",
                                name, i, m->name, m->entry, m->name, l->entries[n->entry].name);
        if (l->layer_count < 32 && (m->layer_mask >> l->layer_count))
            return vt_error_set(err, VTS_ERR_BAD_INPUT,
                                "'%s': materials[%u] ('%s'): layers past the %u of the layout",
                                name, i, m->name, l->layer_count);
        for (uint32_t k = 0; k < l->layer_count; k++)
            if ((m->layer_mask >> k & 1) && !l->entries[n->entry].textures[k].path)
                return vt_error_set(err, VTS_ERR_BAD_INPUT,
                                    "'%s': materials[%u] ('%s'): layer '%s' is a fill of entry "
                                    "'%s', not a map",
                                    name, i, m->name, l->layers[k].name, l->entries[n->entry].name);
        if ((what = material_problem(m)) != NULL)
            return vt_error_set(err, VTS_ERR_BAD_INPUT, "'%s': materials[%u] ('%s') %s", name, i,
                                m->name, what);
    }
    return 0;
}

/* Pack materials: names non-empty, sorted and unique, none an entry's name or alias; a pack path;
 * scale finite > 0; the constants in range as for materials. */
static int check_wangs(const struct vt_layout *l, const char *name, struct vts_error *err)
{
    for (uint32_t i = 0; i < l->wang_count; i++) {
        const struct vt_layout_wang *w = &l->wangs[i];
        const struct vt_layout_material *m = &w->m;
        if (!m->name || !m->name[0] || !w->pack || !w->pack[0])
            return vt_error_set(err, VTS_ERR_BAD_INPUT,
                                "'%s': wang_materials[%u]: empty name or pack", name, i);
        if (i > 0 && strcmp(l->wangs[i - 1].m.name, m->name) >= 0)
            return vt_error_set(err, VTS_ERR_BAD_INPUT,
                                "'%s': wang_materials[%u] ('%s'): not sorted by name, or given "
                                "twice",
                                name, i, m->name);
        if (vt_layout_find(l, m->name))
            return vt_error_set(err, VTS_ERR_BAD_INPUT,
                                "'%s': wang_materials[%u]: name '%s' is also an entry's name or "
                                "alias",
                                name, i, m->name);
        if (!(w->scale > 0 && w->scale <= 1e30))
            return vt_error_set(err, VTS_ERR_BAD_INPUT,
                                "'%s': wang_materials[%u].scale: expected a number > 0", name, i);
        bool ok = m->ns >= 0 && m->ns <= 1e30 && m->d >= 0 && m->d <= 1 && m->illum <= 100 &&
                  m->alpha <= VT_LAYOUT_ALPHA_BLEND;
        for (int k = 0; k < 3; k++)
            ok = ok && m->kd[k] >= 0 && m->ka[k] >= 0 && m->ks[k] >= 0 && m->ke[k] >= 0 &&
                 isfinite(m->kd[k]) && isfinite(m->ka[k]) && isfinite(m->ks[k]) &&
                 isfinite(m->ke[k]);
        if (!ok)
            return vt_error_set(err, VTS_ERR_BAD_INPUT,
                                "'%s': wang_materials[%u] ('%s'): a constant out of range", name, i,
                                m->name);
    }
    return 0;
}

int vt_layout_check(struct vt_layout *l, const char *name, struct vts_error *err)
{
    if (l->width == 0 || l->height == 0)
        return vt_error_set(err, VTS_ERR_BAD_INPUT, "'%s': the atlas has an empty size", name);
    if (!is_pow2(l->tile_content) || l->tile_content < 8 || l->tile_content > 16384 ||
        l->border > 64)
        return vt_error_set(
            err, VTS_ERR_BAD_INPUT,
            "'%s': tile content %u / border %u: content must be a power of two 8..16384 and border 0..64",
            name, l->tile_content, l->border);
    if (l->layer_count == 0 || l->layer_count > VT_LAYOUT_MAX_LAYERS)
        return vt_error_set(err, VTS_ERR_BAD_INPUT, "'%s': %u layers (1..%d)", name, l->layer_count,
                            VT_LAYOUT_MAX_LAYERS);
    for (uint32_t i = 0; i < l->layer_count; i++) {
        const struct vt_layout_layer *a = &l->layers[i];
        if (!a->name || !valid_layer_name(a->name) || !a->map || !a->map[0] ||
            a->colour < VTS_COLOUR_SRGB || a->colour > VTS_COLOUR_DATA)
            return vt_error_set(err, VTS_ERR_BAD_INPUT, "'%s': layer %u: bad name, map or colour",
                                name, i);
        for (uint32_t j = 0; j < i; j++)
            if (strcmp(a->name, l->layers[j].name) == 0)
                return vt_error_set(err, VTS_ERR_BAD_INPUT, "'%s': layer '%s' given twice", name,
                                    a->name);
    }
    for (uint32_t i = 0; i < l->entry_count; i++) {
        fill_crop(&l->entries[i]);
        int rc = check_entry(l, i, name, err);
        if (rc < 0)
            return rc;
    }
    int rc = index_names(l, name, err);
    if (!rc)
        rc = check_overlaps(l, name, err);
    if (!rc)
        rc = check_materials(l, name, err);
    return rc ? rc : check_wangs(l, name, err);
}

int vt_layout_index(struct vt_layout *layout, struct vts_error *err)
{
    return vt_layout_check(layout, "layout", err);
}

const struct vt_layout_entry *vt_layout_find(const struct vt_layout *layout, const char *name)
{
    if (!layout->by_name)
        return NULL;
    size_t lo = 0, hi = layout->name_count;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        const struct vt_layout_name *n = &layout->by_name[mid];
        int c = strcmp(name_of(layout, n), name);
        if (c == 0)
            return &layout->entries[n->entry];
        if (c < 0)
            lo = mid + 1;
        else
            hi = mid;
    }
    return NULL;
}

const struct vt_layout_material *vt_layout_material_find(const struct vt_layout *layout,
                                                         const char *name)
{
    size_t lo = 0, hi = layout->material_count;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        int c = strcmp(layout->materials[mid].name, name);
        if (c == 0)
            return &layout->materials[mid];
        if (c < 0)
            lo = mid + 1;
        else
            hi = mid;
    }
    return NULL;
}

const char *vt_layout_colour_name(uint32_t colour)
{
    static const char *const names[] = {"srgb", "linear", "normal", "data"};
    return colour >= VTS_COLOUR_SRGB && colour <= VTS_COLOUR_SRGB + 3
               ? names[colour - VTS_COLOUR_SRGB]
               : "?";
}

const char *vt_layout_alpha_name(uint32_t alpha)
{
    static const char *const names[] = {"none", "test", "blend"};
    return alpha <= VT_LAYOUT_ALPHA_BLEND ? names[alpha] : "?";
}

static int cmp_material(const void *a, const void *b)
{
    const struct vt_layout_material *x = a, *y = b;
    return strcmp(x->name ? x->name : "", y->name ? y->name : "");
}

void vt_layout_sort_materials(struct vt_layout *layout)
{
    if (layout->material_count > 1)
        qsort(layout->materials, layout->material_count, sizeof *layout->materials, cmp_material);
    if (layout->wang_count > 1) /* m is the first member: cmp_material compares the names */
        qsort(layout->wangs, layout->wang_count, sizeof *layout->wangs, cmp_material);
}

const struct vt_layout_wang *vt_layout_wang_find(const struct vt_layout *layout, const char *name)
{
    size_t lo = 0, hi = layout->wang_count;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        int c = strcmp(layout->wangs[mid].m.name, name);
        if (c == 0)
            return &layout->wangs[mid];
        if (c < 0)
            lo = mid + 1;
        else
            hi = mid;
    }
    return NULL;
}

static void free_wangs(struct vt_layout *layout)
{
    for (uint32_t i = 0; layout->wangs && i < layout->wang_count; i++) {
        free(layout->wangs[i].m.name);
        free(layout->wangs[i].pack);
        free(layout->wangs[i].resolved);
    }
    free(layout->wangs);
    layout->wangs = NULL;
    layout->wang_count = 0;
}

int vt_layout_alloc_wangs(struct vt_layout *layout, uint32_t count, struct vts_error *err)
{
    free_wangs(layout);
    layout->wangs = calloc(count ? count : 1, sizeof *layout->wangs);
    if (!layout->wangs)
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory for %u pack materials", count);
    layout->wang_count = count;
    for (uint32_t i = 0; i < count; i++) {
        layout->wangs[i].m.d = 1;
        layout->wangs[i].scale = 1;
    }
    return 0;
}

int vt_layout_alloc_materials(struct vt_layout *layout, uint32_t count, struct vts_error *err)
{
    for (uint32_t i = 0; i < layout->material_count; i++)
        free(layout->materials[i].name);
    free(layout->materials);
    layout->materials = calloc(count ? count : 1, sizeof *layout->materials);
    layout->material_count = layout->materials ? count : 0;
    if (!layout->materials)
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory for %u materials", count);
    for (uint32_t i = 0; i < count; i++)
        layout->materials[i].d = 1;
    return 0;
}

int vt_layout_layer_index(const struct vt_layout *layout, const char *name)
{
    for (uint32_t i = 0; i < layout->layer_count; i++)
        if (strcmp(layout->layers[i].name, name) == 0)
            return (int)i;
    return -1;
}

void vt_layout_map_uv(const struct vt_layout *layout, const struct vt_layout_entry *e, double u,
                      double v, double *au, double *av)
{
    /* x - crop_x is exact in double; without a crop it is x, as before crops existed */
    *au = ((double)e->x - e->crop_x + (u - e->origin_u) * e->width) / layout->width;
    *av = 1.0 - ((double)e->y - e->crop_y + ((double)e->repeat_v - (v - e->origin_v)) * e->height) /
                    layout->height;
}

bool vt_layout_uv_covered(const struct vt_layout_entry *e, double u, double v)
{
    /* The crop's UV range; crop 0 x 0 (a layout not checked yet) is the whole block. The bounds
     * are exact for the whole block: (width * repeat_u) / width is repeat_u, so an entry without
     * a crop covers [origin, origin + repeat] exactly, as before crops existed. */
    uint64_t cw = e->crop_width, chh = e->crop_height;
    if (cw == 0 || chh == 0) {
        cw = (uint64_t)e->width * e->repeat_u;
        chh = (uint64_t)e->height * e->repeat_v;
    }
    double u0 = e->origin_u + (double)e->crop_x / e->width,
           u1 = e->origin_u + (double)(e->crop_x + cw) / e->width;
    double v1 = (double)e->origin_v + e->repeat_v - (double)e->crop_y / e->height,
           v0 = (double)e->origin_v + e->repeat_v - (double)(e->crop_y + chh) / e->height;
    return u >= u0 && u <= u1 && v >= v0 && v <= v1;
}

int vt_layout_alloc(struct vt_layout *layout, uint32_t layer_count, uint32_t entry_count,
                    struct vts_error *err)
{
    memset(layout, 0, sizeof *layout);
    layout->layers = calloc(layer_count ? layer_count : 1, sizeof *layout->layers);
    layout->entries = calloc(entry_count ? entry_count : 1, sizeof *layout->entries);
    if (!layout->layers || !layout->entries)
        goto nomem;
    layout->layer_count = layer_count;
    layout->entry_count = entry_count;
    for (uint32_t i = 0; i < entry_count; i++) {
        struct vt_layout_entry *e = &layout->entries[i];
        e->textures = calloc(layer_count ? layer_count : 1, sizeof *e->textures);
        if (!e->textures)
            goto nomem;
        e->repeat_u = e->repeat_v = 1;
        e->alignment = 1;
        e->scale = 1;
    }
    return 0;
nomem:
    vt_layout_release(layout);
    return vt_error_set(err, VTS_ERR_NOMEM, "out of memory for a layout of %u entries",
                        entry_count);
}

void vt_layout_release(struct vt_layout *layout)
{
    if (!layout)
        return;
    for (uint32_t i = 0; layout->layers && i < layout->layer_count; i++) {
        free(layout->layers[i].name);
        free(layout->layers[i].map);
    }
    for (uint32_t i = 0; layout->entries && i < layout->entry_count; i++) {
        struct vt_layout_entry *e = &layout->entries[i];
        for (uint32_t k = 0; e->textures && k < layout->layer_count; k++) {
            free(e->textures[k].path);
            free(e->textures[k].resolved);
        }
        free(e->textures);
        free(e->name);
        for (uint32_t a = 0; e->aliases && a < e->alias_count; a++)
            free(e->aliases[a]);
        free(e->aliases);
    }
    for (uint32_t i = 0; layout->materials && i < layout->material_count; i++)
        free(layout->materials[i].name);
    free(layout->materials);
    free_wangs(layout);
    free(layout->layers);
    free(layout->entries);
    free(layout->by_name);
    free(layout->generator);
    memset(layout, 0, sizeof *layout);
}
