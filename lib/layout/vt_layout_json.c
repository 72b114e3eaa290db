/* atlas.json reader (jansson): every field checked, with messages naming the file and the JSON
 * path; the model and its checks are in vt_layout.c, the writer in vt_layout_json_write.c.
 * Schema: docs/atlas-format.md. */
#include <errno.h>
#include <jansson.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vt_error.h"
#include "vt_layout.h"
#include "vt_obj.h"
#include "vts.h"

/* Parsing context: the file name and the JSON path of the value being read, for messages. */
struct ctx {
    const char *name;
    struct vts_error *err;
};

static int bad(struct ctx *c, const char *where, const char *what)
{
    return vt_error_set(c->err, VTS_ERR_BAD_INPUT, "'%s': %s: %s", c->name, where, what);
}

static int get_uint(struct ctx *c, json_t *obj, const char *key, const char *where, uint64_t min,
                    uint64_t max, bool required, uint64_t dflt, uint64_t *out)
{
    char path[160];
    snprintf(path, sizeof path, "%s%s%s", where, where[0] ? "." : "", key);
    json_t *v = json_object_get(obj, key);
    if (!v) {
        if (required)
            return bad(c, path, "missing");
        *out = dflt;
        return 0;
    }
    if (!json_is_integer(v) || json_integer_value(v) < 0 || (uint64_t)json_integer_value(v) < min ||
        (uint64_t)json_integer_value(v) > max) {
        char what[96];
        snprintf(what, sizeof what, "expected an integer %llu..%llu", (unsigned long long)min,
                 (unsigned long long)max);
        return bad(c, path, what);
    }
    *out = (uint64_t)json_integer_value(v);
    return 0;
}

static int get_u32(struct ctx *c, json_t *obj, const char *key, const char *where, uint32_t min,
                   uint32_t max, uint32_t *out)
{
    uint64_t v;
    int rc = get_uint(c, obj, key, where, min, max, true, 0, &v);
    *out = (uint32_t)v;
    return rc;
}

static int get_string(struct ctx *c, json_t *obj, const char *key, const char *where, bool required,
                      char **out)
{
    char path[160];
    snprintf(path, sizeof path, "%s%s%s", where, where[0] ? "." : "", key);
    json_t *v = json_object_get(obj, key);
    *out = NULL;
    if (!v)
        return required ? bad(c, path, "missing") : 0;
    if (!json_is_string(v) || strlen(json_string_value(v)) != json_string_length(v))
        return bad(c, path, "expected a string without NUL");
    *out = strdup(json_string_value(v));
    return *out ? 0 : vt_error_set(c->err, VTS_ERR_NOMEM, "'%s': out of memory", c->name);
}

/* A pair [a, b] of integers in min..max. */
static int get_pair(struct ctx *c, json_t *obj, const char *key, const char *where, int64_t min,
                    int64_t max, int64_t dflt, int64_t out[2])
{
    char path[160];
    snprintf(path, sizeof path, "%s.%s", where, key);
    json_t *v = json_object_get(obj, key);
    if (!v) {
        out[0] = out[1] = dflt;
        return 0;
    }
    for (size_t i = 0; i < 2; i++) {
        json_t *x = json_is_array(v) && json_array_size(v) == 2 ? json_array_get(v, i) : NULL;
        if (!x || !json_is_integer(x) || json_integer_value(x) < min || json_integer_value(x) > max)
            return bad(c, path, "expected two integers in range");
        out[i] = json_integer_value(x);
    }
    return 0;
}

static int read_layers(struct ctx *c, json_t *root, struct vt_layout *l)
{
    json_t *arr = json_object_get(root, "layers");
    if (!json_is_array(arr) || json_array_size(arr) == 0 ||
        json_array_size(arr) > VT_LAYOUT_MAX_LAYERS)
        return bad(c, "layers", "expected an array of 1..16 layers");
    for (size_t i = 0; i < json_array_size(arr); i++) {
        json_t *o = json_array_get(arr, i);
        char where[32], *colour = NULL;
        snprintf(where, sizeof where, "layers[%zu]", i);
        if (!json_is_object(o))
            return bad(c, where, "expected an object");
        struct vt_layout_layer *a = &l->layers[i];
        int rc = get_string(c, o, "name", where, true, &a->name);
        if (!rc)
            rc = get_string(c, o, "map", where, true, &a->map);
        if (!rc)
            rc = get_string(c, o, "colour", where, true, &colour);
        if (rc)
            return rc;
        a->colour = 0;
        for (uint32_t k = 0; k < 4; k++)
            if (strcmp(colour, vt_layout_colour_name(VTS_COLOUR_SRGB + k)) == 0)
                a->colour = VTS_COLOUR_SRGB + k;
        free(colour);
        if (!a->colour)
            return bad(c, where, "colour must be srgb, linear, normal or data");
    }
    return 0;
}

static int read_texture(struct ctx *c, json_t *o, const char *where, struct vt_layout_texture *t)
{
    if (!json_is_object(o))
        return bad(c, where, "expected an object");
    json_t *fill = json_object_get(o, "fill");
    if (fill) {
        if (!json_is_array(fill) || json_array_size(fill) != 4)
            return bad(c, where, "fill must be [r, g, b, a]");
        for (size_t k = 0; k < 4; k++) {
            json_t *x = json_array_get(fill, k);
            if (!json_is_number(x) || !(json_number_value(x) >= 0 && json_number_value(x) <= 1))
                return bad(c, where, "fill values must be numbers in 0..1");
            t->fill[k] = json_number_value(x);
        }
        return 0;
    }
    int rc = get_string(c, o, "path", where, true, &t->path);
    uint64_t w, h;
    if (!rc)
        rc = get_uint(c, o, "width", where, 1, 1u << 24, true, 0, &w);
    if (!rc)
        rc = get_uint(c, o, "height", where, 1, 1u << 24, true, 0, &h);
    if (rc)
        return rc;
    if (!t->path[0])
        return bad(c, where, "empty path");
    t->width = (uint32_t)w;
    t->height = (uint32_t)h;
    t->resolved = vt_obj_resolve_path(c->name, t->path);
    return t->resolved ? 0 : vt_error_set(c->err, VTS_ERR_NOMEM, "'%s': out of memory", c->name);
}

/* "aliases": optional array of non-empty strings (uniqueness is checked with the names). */
static int read_aliases(struct ctx *c, json_t *arr, const char *where, struct vt_layout_entry *e)
{
    if (!arr)
        return 0;
    char path[96];
    snprintf(path, sizeof path, "%s.aliases", where);
    if (!json_is_array(arr))
        return bad(c, path, "expected an array of names");
    size_t n = json_array_size(arr);
    if (n == 0)
        return 0;
    e->aliases = calloc(n, sizeof *e->aliases);
    if (!e->aliases)
        return vt_error_set(c->err, VTS_ERR_NOMEM, "'%s': out of memory", c->name);
    for (size_t i = 0; i < n; i++) {
        json_t *v = json_array_get(arr, i);
        if (!json_is_string(v) || strlen(json_string_value(v)) != json_string_length(v) ||
            json_string_length(v) == 0)
            return bad(c, path, "expected non-empty strings without NUL");
        e->aliases[i] = strdup(json_string_value(v));
        if (!e->aliases[i])
            return vt_error_set(c->err, VTS_ERR_NOMEM, "'%s': out of memory", c->name);
        e->alias_count = (uint32_t)(i + 1);
    }
    return 0;
}

/* "crop": optional [x, y, width, height] inside the block of copies (width * repeat_u x
 * height * repeat_v); without it the crop stays 0 x 0 and vt_layout_check() makes it the whole
 * block. "wrap": optional boolean; a wrap entry holds one whole copy. The repeat is read first. */
static int read_crop_wrap(struct ctx *c, json_t *o, const char *where, struct vt_layout_entry *e)
{
    char path[96], what[200];
    json_t *crop = json_object_get(o, "crop"), *wrap = json_object_get(o, "wrap");
    uint64_t bw = (uint64_t)e->width * e->repeat_u, bh = (uint64_t)e->height * e->repeat_v;
    if (crop) {
        snprintf(path, sizeof path, "%s.crop", where);
        json_int_t v[4];
        for (size_t k = 0; k < 4; k++) {
            json_t *x =
                json_is_array(crop) && json_array_size(crop) == 4 ? json_array_get(crop, k) : NULL;
            if (!x || !json_is_integer(x) || json_integer_value(x) < (k < 2 ? 0 : 1) ||
                json_integer_value(x) > (json_int_t)UINT32_MAX)
                return bad(c, path,
                           "expected [x, y, width, height]: integers 0..4294967295, width and "
                           "height at least 1");
            v[k] = json_integer_value(x);
        }
        if ((uint64_t)v[0] + (uint64_t)v[2] > bw || (uint64_t)v[1] + (uint64_t)v[3] > bh) {
            snprintf(what, sizeof what,
                     "[%lld, %lld, %lld, %lld] is not inside the block of copies (%llux%llu)",
                     (long long)v[0], (long long)v[1], (long long)v[2], (long long)v[3],
                     (unsigned long long)bw, (unsigned long long)bh);
            return bad(c, path, what);
        }
        e->crop_x = (uint32_t)v[0], e->crop_y = (uint32_t)v[1];
        e->crop_width = (uint32_t)v[2], e->crop_height = (uint32_t)v[3];
    }
    if (!wrap)
        return 0;
    snprintf(path, sizeof path, "%s.wrap", where);
    if (!json_is_boolean(wrap))
        return bad(c, path, "expected true or false");
    e->wrap = json_is_true(wrap);
    if (e->wrap && (e->repeat_u != 1 || e->repeat_v != 1)) {
        snprintf(what, sizeof what,
                 "a wrap entry holds one copy: repeat must be [1, 1], not [%u, %u]", e->repeat_u,
                 e->repeat_v);
        return bad(c, path, what);
    }
    if (e->wrap && crop &&
        (e->crop_x || e->crop_y || e->crop_width != bw || e->crop_height != bh)) {
        snprintf(what, sizeof what,
                 "a wrap entry holds its whole texture: crop must be absent or [0, 0, %u, %u], not "
                 "[%u, %u, %u, %u]",
                 e->width, e->height, e->crop_x, e->crop_y, e->crop_width, e->crop_height);
        return bad(c, path, what);
    }
    return 0;
}

static int read_entry(struct ctx *c, json_t *o, size_t i, const struct vt_layout *l,
                      struct vt_layout_entry *e)
{
    char where[48];
    snprintf(where, sizeof where, "entries[%zu]", i);
    if (!json_is_object(o))
        return bad(c, where, "expected an object");
    int64_t rep[2], org[2];
    uint64_t group, cell_x = 0, cell_y = 0;
    int rc = get_string(c, o, "name", where, true, &e->name);
    if (!rc)
        rc = get_u32(c, o, "x", where, 0, UINT32_MAX, &e->x);
    if (!rc)
        rc = get_u32(c, o, "y", where, 0, UINT32_MAX, &e->y);
    if (!rc)
        rc = get_u32(c, o, "width", where, 1, UINT32_MAX, &e->width);
    if (!rc)
        rc = get_u32(c, o, "height", where, 1, UINT32_MAX, &e->height);
    if (!rc)
        rc = get_u32(c, o, "cell_width", where, 1, UINT32_MAX, &e->cell_width);
    if (!rc)
        rc = get_u32(c, o, "cell_height", where, 1, UINT32_MAX, &e->cell_height);
    if (!rc)
        rc = get_u32(c, o, "alignment", where, 1, 1u << 30, &e->alignment);
    if (!rc)
        rc = get_pair(c, o, "repeat", where, 1, 65536, 1, rep);
    if (!rc)
        rc = get_pair(c, o, "origin", where, -(1 << 30), 1 << 30, 0, org);
    if (!rc)
        rc = get_uint(c, o, "group", where, 0, UINT32_MAX, false, 0, &group);
    if (!rc)
        rc = get_uint(c, o, "cell_x", where, 0, e->x, false, e->x, &cell_x);
    if (!rc)
        rc = get_uint(c, o, "cell_y", where, 0, e->y, false, e->y, &cell_y);
    if (rc)
        return rc;
    e->cell_left = e->x - (uint32_t)cell_x;
    e->cell_top = e->y - (uint32_t)cell_y;
    e->repeat_u = (uint32_t)rep[0], e->repeat_v = (uint32_t)rep[1];
    e->origin_u = (int32_t)org[0], e->origin_v = (int32_t)org[1];
    e->group = (uint32_t)group;
    rc = read_crop_wrap(c, o, where, e);
    if (!rc)
        rc = read_aliases(c, json_object_get(o, "aliases"), where, e);
    if (rc)
        return rc;
    json_t *scale = json_object_get(o, "scale");
    e->scale = 1;
    if (scale) {
        if (!json_is_number(scale))
            return bad(c, where, "scale must be a number");
        e->scale = json_number_value(scale);
    }
    json_t *tex = json_object_get(o, "textures");
    if (!json_is_array(tex) || json_array_size(tex) != l->layer_count)
        return bad(c, where, "textures must be an array with one item per layer");
    for (uint32_t k = 0; k < l->layer_count; k++) {
        char twhere[96];
        snprintf(twhere, sizeof twhere, "%s.textures[%u]", where, k);
        rc = read_texture(c, json_array_get(tex, k), twhere, &e->textures[k]);
        if (rc)
            return rc;
    }
    return 0;
}

/* [r, g, b]: three numbers (the range is checked with the model). */
static int get_rgb(struct ctx *c, json_t *o, const char *key, const char *where, double out[3])
{
    char path[160];
    snprintf(path, sizeof path, "%s.%s", where, key);
    json_t *v = json_object_get(o, key);
    if (!v)
        return bad(c, path, "missing");
    for (size_t k = 0; k < 3; k++) {
        json_t *x = json_is_array(v) && json_array_size(v) == 3 ? json_array_get(v, k) : NULL;
        if (!x || !json_is_number(x) || !(json_number_value(x) >= 0))
            return bad(c, path, "expected [r, g, b]: three numbers >= 0");
        out[k] = json_number_value(x);
    }
    return 0;
}

static int get_number(struct ctx *c, json_t *o, const char *key, const char *where, double min,
                      double max, double *out)
{
    char path[160], what[96];
    snprintf(path, sizeof path, "%s.%s", where, key);
    json_t *v = json_object_get(o, key);
    if (!v)
        return bad(c, path, "missing");
    if (!json_is_number(v) || !(json_number_value(v) >= min && json_number_value(v) <= max)) {
        snprintf(what, sizeof what, "expected a number %g..%g", min, max);
        return bad(c, path, what);
    }
    *out = json_number_value(v);
    return 0;
}

/* "layers": the names of the layers that hold a map of the material, in any order, each once. */
static int read_material_layers(struct ctx *c, json_t *o, const char *where,
                                const struct vt_layout *l, struct vt_layout_material *m)
{
    char path[160], what[160];
    snprintf(path, sizeof path, "%s.layers", where);
    json_t *arr = json_object_get(o, "layers");
    if (!arr)
        return bad(c, path, "missing");
    if (!json_is_array(arr))
        return bad(c, path, "expected an array of layer names");
    for (size_t k = 0; k < json_array_size(arr); k++) {
        json_t *v = json_array_get(arr, k);
        int li = json_is_string(v) ? vt_layout_layer_index(l, json_string_value(v)) : -1;
        if (!json_is_string(v))
            return bad(c, path, "expected an array of layer names");
        if (li < 0) {
            snprintf(what, sizeof what, "no layer '%.100s' in the layout", json_string_value(v));
            return bad(c, path, what);
        }
        if (m->layer_mask >> li & 1) {
            snprintf(what, sizeof what, "layer '%s' given twice", l->layers[li].name);
            return bad(c, path, what);
        }
        m->layer_mask |= 1u << li;
    }
    return 0;
}

static int read_constants(struct ctx *c, json_t *o, const char *where,
                          struct vt_layout_material *m);

static int read_material(struct ctx *c, json_t *o, size_t i, const struct vt_layout *l,
                         struct vt_layout_material *m)
{
    char where[48], *entry = NULL;
    snprintf(where, sizeof where, "materials[%zu]", i);
    if (!json_is_object(o))
        return bad(c, where, "expected an object");
    int rc = get_string(c, o, "name", where, true, &m->name);
    if (!rc)
        rc = get_string(c, o, "entry", where, true, &entry);
    if (!rc) {
        const struct vt_layout_entry *e = vt_layout_find(l, entry);
        char path[64];
        snprintf(path, sizeof path, "%s.entry", where);
        if (!e || strcmp(e->name, entry) != 0)
            rc = bad(c, path, "not the name of an entry");
        else
            m->entry = (uint32_t)(e - l->entries);
    }
    free(entry);
    if (!rc)
        rc = read_material_layers(c, o, where, l, m);
    return rc ? rc : read_constants(c, o, where, m);
}

/* Kd, Ka, Ks, Ke, Ns, d, illum and alpha of a material or a pack material. */
static int read_constants(struct ctx *c, json_t *o, const char *where, struct vt_layout_material *m)
{
    char *alpha = NULL;
    uint64_t illum;
    int rc = get_rgb(c, o, "Kd", where, m->kd);
    if (!rc)
        rc = get_rgb(c, o, "Ka", where, m->ka);
    if (!rc)
        rc = get_rgb(c, o, "Ks", where, m->ks);
    if (!rc)
        rc = get_rgb(c, o, "Ke", where, m->ke);
    if (!rc)
        rc = get_number(c, o, "Ns", where, 0, 1e30, &m->ns);
    if (!rc)
        rc = get_number(c, o, "d", where, 0, 1, &m->d);
    if (!rc)
        rc = get_uint(c, o, "illum", where, 0, 100, true, 0, &illum);
    if (!rc)
        rc = get_string(c, o, "alpha", where, true, &alpha);
    if (rc)
        return rc;
    m->illum = (uint32_t)illum;
    m->alpha = UINT32_MAX;
    for (uint32_t k = VT_LAYOUT_ALPHA_NONE; k <= VT_LAYOUT_ALPHA_BLEND; k++)
        if (strcmp(alpha, vt_layout_alpha_name(k)) == 0)
            m->alpha = k;
    free(alpha);
    if (m->alpha == UINT32_MAX) {
        char path[64];
        snprintf(path, sizeof path, "%s.alpha", where);
        return bad(c, path, "expected \"none\", \"test\" or \"blend\"");
    }
    return 0;
}

/* "materials" (optional: layouts written before it have none): read after the entries are
 * checked and indexed, then checked with them (vt_layout_check). */
static int read_materials(struct ctx *c, json_t *arr, struct vt_layout *l)
{
    if (!json_is_array(arr))
        return bad(c, "materials", "expected an array");
    if (json_array_size(arr) != l->name_count)
        return vt_error_set(c->err, VTS_ERR_BAD_INPUT,
                            "'%s': materials: %zu materials for %zu material names (one for each "
                            "entry name and alias)",
                            c->name, json_array_size(arr), l->name_count);
    int rc = vt_layout_alloc_materials(l, (uint32_t)json_array_size(arr), c->err);
    for (size_t i = 0; !rc && i < l->material_count; i++)
        rc = read_material(c, json_array_get(arr, i), i, l, &l->materials[i]);
    return rc ? rc : vt_layout_check(l, c->name, c->err);
}

/* "wang_materials" (optional, docs/atlas-format.md): pack materials, checked with the model. */
static int read_wangs(struct ctx *c, json_t *arr, struct vt_layout *l, uint32_t max)
{
    if (!json_is_array(arr))
        return bad(c, "wang_materials", "expected an array");
    if (json_array_size(arr) > max)
        return vt_error_set(c->err, VTS_ERR_LIMIT,
                            "'%s': %zu pack materials, more than the limit %u", c->name,
                            json_array_size(arr), max);
    int rc = vt_layout_alloc_wangs(l, (uint32_t)json_array_size(arr), c->err);
    for (size_t i = 0; !rc && i < l->wang_count; i++) {
        struct vt_layout_wang *w = &l->wangs[i];
        json_t *o = json_array_get(arr, i);
        char where[48];
        snprintf(where, sizeof where, "wang_materials[%zu]", i);
        if (!json_is_object(o))
            return bad(c, where, "expected an object");
        rc = get_string(c, o, "name", where, true, &w->m.name);
        if (!rc)
            rc = get_string(c, o, "pack", where, true, &w->pack);
        if (!rc)
            rc = get_number(c, o, "scale", where, 1e-30, 1e30, &w->scale);
        if (!rc)
            rc = read_constants(c, o, where, &w->m);
        if (!rc && !w->pack[0])
            rc = bad(c, where, "empty pack");
        if (!rc && !(w->resolved = vt_obj_resolve_path(c->name, w->pack)))
            rc = vt_error_set(c->err, VTS_ERR_NOMEM, "'%s': out of memory", c->name);
    }
    return rc ? rc : vt_layout_check(l, c->name, c->err);
}

static int read_root(struct ctx *c, json_t *root, const struct vt_layout_limits *lim,
                     struct vt_layout *l)
{
    if (!json_is_object(root))
        return bad(c, "top level", "expected an object");
    json_t *fmt = json_object_get(root, "format");
    if (!json_is_string(fmt) || strcmp(json_string_value(fmt), VT_LAYOUT_FORMAT) != 0)
        return bad(c, "format", "not \"" VT_LAYOUT_FORMAT "\": not an atlas layout");
    uint64_t version;
    int rc = get_uint(c, root, "version", "", 1, UINT32_MAX, true, 0, &version);
    if (rc)
        return rc;
    if (version != VT_LAYOUT_VERSION)
        return vt_error_set(c->err, VTS_ERR_BAD_INPUT,
                            "'%s': layout version %llu; this build reads version %d", c->name,
                            (unsigned long long)version, VT_LAYOUT_VERSION);
    json_t *layers = json_object_get(root, "layers"), *entries = json_object_get(root, "entries");
    if (!json_is_array(entries))
        return bad(c, "entries", "expected an array");
    if (json_array_size(entries) > lim->max_entries)
        return vt_error_set(c->err, VTS_ERR_LIMIT, "'%s': %zu entries, more than the limit %u",
                            c->name, json_array_size(entries), lim->max_entries);
    size_t names = json_array_size(entries);
    for (size_t i = 0; i < json_array_size(entries); i++) {
        json_t *a = json_object_get(json_array_get(entries, i), "aliases");
        names += json_is_array(a) ? json_array_size(a) : 0;
    }
    if (names > lim->max_entries)
        return vt_error_set(
            c->err, VTS_ERR_LIMIT,
            "'%s': %zu material names (entries and aliases), more than the limit %u", c->name,
            names, lim->max_entries);
    size_t layer_count = json_is_array(layers) ? json_array_size(layers) : 0;
    if (layer_count == 0 || layer_count > VT_LAYOUT_MAX_LAYERS)
        return bad(c, "layers", "expected an array of 1..16 layers");
    rc = vt_layout_alloc(l, (uint32_t)layer_count, (uint32_t)json_array_size(entries), c->err);
    if (!rc)
        rc = get_u32(c, root, "width", "", 1, lim->max_edge, &l->width);
    if (!rc)
        rc = get_u32(c, root, "height", "", 1, lim->max_edge, &l->height);
    if (!rc)
        rc = get_u32(c, root, "tile_content", "", 8, 16384, &l->tile_content);
    if (!rc)
        rc = get_u32(c, root, "border", "", 0, 64, &l->border);
    if (!rc)
        rc = get_string(c, root, "generator", "", false, &l->generator);
    if (!rc)
        rc = read_layers(c, root, l);
    for (size_t i = 0; !rc && i < l->entry_count; i++)
        rc = read_entry(c, json_array_get(entries, i), i, l, &l->entries[i]);
    if (!rc)
        rc = vt_layout_check(l, c->name, c->err);
    json_t *materials = json_object_get(root, "materials");
    if (!rc && materials)
        rc = read_materials(c, materials, l);
    json_t *wangs = json_object_get(root, "wang_materials");
    return rc || !wangs ? rc : read_wangs(c, wangs, l, lim->max_entries);
}

int vt_layout_parse_memory(const void *data, size_t size, const char *name,
                           const struct vt_layout_limits *limits, struct vt_layout *layout,
                           struct vts_error *err)
{
    struct vt_layout_limits lim;
    if (limits)
        lim = *limits;
    else
        vt_layout_limits_default(&lim);
    memset(layout, 0, sizeof *layout);
    if (size > lim.max_file_bytes)
        return vt_error_set(err, VTS_ERR_LIMIT, "'%s': %zu bytes, more than the limit %llu", name,
                            size, (unsigned long long)lim.max_file_bytes);
    json_error_t jerr;
    json_t *root = json_loadb(data, size, JSON_REJECT_DUPLICATES, &jerr);
    if (!root)
        return vt_error_set(err, VTS_ERR_BAD_INPUT, "'%s':%d: %s", name, jerr.line, jerr.text);
    struct ctx c = {.name = name, .err = err};
    int rc = read_root(&c, root, &lim, layout);
    json_decref(root);
    return rc;
}

int vt_layout_read(const char *path, const struct vt_layout_limits *limits,
                   struct vt_layout *layout, struct vts_error *err)
{
    struct vt_layout_limits lim;
    if (limits)
        lim = *limits;
    else
        vt_layout_limits_default(&lim);
    memset(layout, 0, sizeof *layout);
    FILE *f = fopen(path, "rb");
    if (!f)
        return vt_error_set(err, VTS_ERR_IO, "cannot open '%s': %s", path, strerror(errno));
    char *buf = NULL;
    size_t len = 0, cap = 0;
    int rc = 0;
    for (;;) {
        if (len == cap) {
            size_t ncap = cap ? cap * 2 : 65536;
            char *nbuf = len > lim.max_file_bytes ? NULL : realloc(buf, ncap);
            if (!nbuf) {
                rc = len > lim.max_file_bytes
                         ? vt_error_set(err, VTS_ERR_LIMIT, "'%s': more than %llu bytes", path,
                                        (unsigned long long)lim.max_file_bytes)
                         : vt_error_set(err, VTS_ERR_NOMEM, "'%s': out of memory", path);
                break;
            }
            buf = nbuf, cap = ncap;
        }
        size_t n = fread(buf + len, 1, cap - len, f);
        len += n;
        if (n == 0) {
            if (ferror(f))
                rc = vt_error_set(err, VTS_ERR_IO, "cannot read '%s': %s", path, strerror(errno));
            break;
        }
    }
    fclose(f);
    if (!rc)
        rc = vt_layout_parse_memory(buf, len, path, &lim, layout, err);
    free(buf);
    return rc;
}
