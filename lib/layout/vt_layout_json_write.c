/* atlas.json writer (jansson): the layout model as JSON, written atomically; and the materials as
 * store metadata. The reader is vt_layout_json.c. Schema: docs/atlas-format.md. */
#include <jansson.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vt_atomic_file.h"
#include "vt_error.h"
#include "vt_layout.h"
#include "vts.h"

static json_t *pair(int64_t a, int64_t b)
{
    return json_pack("[II]", (json_int_t)a, (json_int_t)b);
}

static json_t *texture_json(const struct vt_layout_texture *t)
{
    if (!t->path)
        return json_pack("{s:[ffff]}", "fill", t->fill[0], t->fill[1], t->fill[2], t->fill[3]);
    return json_pack("{s:s, s:I, s:I}", "path", t->path, "width", (json_int_t)t->width, "height",
                     (json_int_t)t->height);
}

static json_t *entry_json(const struct vt_layout *l, const struct vt_layout_entry *e)
{
    json_t *tex = json_array();
    for (uint32_t k = 0; tex && k < l->layer_count; k++)
        if (json_array_append_new(tex, texture_json(&e->textures[k]))) {
            json_decref(tex);
            return NULL;
        }
    json_t *aliases = NULL;
    if (e->alias_count) {
        aliases = json_array();
        for (uint32_t a = 0; aliases && a < e->alias_count; a++)
            if (json_array_append_new(aliases, json_string(e->aliases[a]))) {
                json_decref(aliases);
                json_decref(tex);
                return NULL;
            }
    }
    /* The name and its aliases first, for the reader of the file. */
    json_t *o = json_pack("{s:s}", "name", e->name);
    if (o && aliases && json_object_set_new(o, "aliases", aliases)) {
        json_decref(o);
        o = NULL;
    } else if (!o) {
        json_decref(aliases);
    }
    json_t *rest = json_pack(
        "{s:I, s:I, s:I, s:I, s:o, s:o, s:I, s:I, s:I, s:f, s:o}", "x", (json_int_t)e->x, "y",
        (json_int_t)e->y, "width", (json_int_t)e->width, "height", (json_int_t)e->height, "repeat",
        pair(e->repeat_u, e->repeat_v), "origin", pair(e->origin_u, e->origin_v), "cell_width",
        (json_int_t)e->cell_width, "cell_height", (json_int_t)e->cell_height, "alignment",
        (json_int_t)e->alignment, "scale", e->scale, "textures", tex);
    /* cell_x/cell_y only with a gutter: layouts without one read as before. */
    if (!o || !rest || json_object_update(o, rest) ||
        (e->group && json_object_set_new(o, "group", json_integer(e->group))) ||
        ((e->cell_left || e->cell_top) &&
         (json_object_set_new(o, "cell_x", json_integer(vt_layout_cell_x(e))) ||
          json_object_set_new(o, "cell_y", json_integer(vt_layout_cell_y(e)))))) {
        json_decref(o);
        json_decref(rest);
        return NULL;
    }
    json_decref(rest);
    /* crop only when it is not the whole block, wrap only when true: layouts without them are
     * written as before the fields existed */
    uint64_t bw = (uint64_t)e->width * e->repeat_u, bh = (uint64_t)e->height * e->repeat_v;
    if ((e->crop_x || e->crop_y || e->crop_width != bw || e->crop_height != bh) &&
        json_object_set_new(o, "crop",
                            json_pack("[IIII]", (json_int_t)e->crop_x, (json_int_t)e->crop_y,
                                      (json_int_t)e->crop_width, (json_int_t)e->crop_height))) {
        json_decref(o);
        return NULL;
    }
    if (e->wrap && json_object_set_new(o, "wrap", json_true())) {
        json_decref(o);
        return NULL;
    }
    return o;
}

static json_t *rgb(const double c[3])
{
    return json_pack("[fff]", c[0], c[1], c[2]);
}

static json_t *material_json(const struct vt_layout *l, const struct vt_layout_material *m)
{
    json_t *layers = json_array();
    for (uint32_t k = 0; layers && k < l->layer_count; k++)
        if ((m->layer_mask >> k & 1) &&
            json_array_append_new(layers, json_string(l->layers[k].name))) {
            json_decref(layers);
            return NULL;
        }
    return json_pack("{s:s, s:s, s:o, s:s, s:o, s:o, s:o, s:o, s:f, s:f, s:I}", "name", m->name,
                     "entry", l->entries[m->entry].name, "layers", layers, "alpha",
                     vt_layout_alpha_name(m->alpha), "Kd", rgb(m->kd), "Ka", rgb(m->ka), "Ks",
                     rgb(m->ks), "Ke", rgb(m->ke), "Ns", m->ns, "d", m->d, "illum",
                     (json_int_t)m->illum);
}

/* One pack material of "wang_materials": name, pack, scale and the constants. */
static json_t *wang_json(const struct vt_layout_wang *w)
{
    const struct vt_layout_material *m = &w->m;
    return json_pack("{s:s, s:s, s:f, s:s, s:o, s:o, s:o, s:o, s:f, s:f, s:I}", "name", m->name,
                     "pack", w->pack, "scale", w->scale, "alpha", vt_layout_alpha_name(m->alpha),
                     "Kd", rgb(m->kd), "Ka", rgb(m->ka), "Ks", rgb(m->ks), "Ke", rgb(m->ke), "Ns",
                     m->ns, "d", m->d, "illum", (json_int_t)m->illum);
}

static json_t *wangs_json(const struct vt_layout *l)
{
    json_t *arr = json_array();
    for (uint32_t i = 0; arr && i < l->wang_count; i++)
        if (json_array_append_new(arr, wang_json(&l->wangs[i]))) {
            json_decref(arr);
            return NULL;
        }
    return arr;
}

static json_t *materials_json(const struct vt_layout *l)
{
    json_t *arr = json_array();
    for (uint32_t i = 0; arr && i < l->material_count; i++)
        if (json_array_append_new(arr, material_json(l, &l->materials[i]))) {
            json_decref(arr);
            return NULL;
        }
    return arr;
}

char *vt_layout_materials_meta(const struct vt_layout *layout, size_t max_bytes,
                               struct vts_error *err)
{
    json_t *arr = materials_json(layout);
    char *text =
        arr ? json_dumps(arr, JSON_COMPACT | JSON_PRESERVE_ORDER | JSON_REAL_PRECISION(17)) : NULL;
    json_decref(arr);
    if (!text) {
        vt_error_set(err, VTS_ERR_NOMEM, "out of memory for the materials of the layout");
        return NULL;
    }
    if (strlen(text) > max_bytes) {
        vt_error_set(err, VTS_ERR_LIMIT,
                     "the materials of the layout take %zu bytes of metadata, more than the %zu "
                     "left",
                     strlen(text), max_bytes);
        free(text);
        return NULL;
    }
    return text;
}

static json_t *layout_json(const struct vt_layout *l)
{
    json_t *layers = json_array(), *entries = json_array();
    for (uint32_t i = 0; layers && i < l->layer_count; i++)
        if (json_array_append_new(layers, json_pack("{s:s, s:s, s:s}", "name", l->layers[i].name,
                                                    "map", l->layers[i].map, "colour",
                                                    vt_layout_colour_name(l->layers[i].colour))))
            goto fail;
    for (uint32_t i = 0; entries && i < l->entry_count; i++)
        if (json_array_append_new(entries, entry_json(l, &l->entries[i])))
            goto fail;
    if (!layers || !entries)
        goto fail;
    json_t *root =
        json_pack("{s:s, s:i, s:s, s:I, s:I, s:I, s:I, s:o, s:o}", "format", VT_LAYOUT_FORMAT,
                  "version", VT_LAYOUT_VERSION, "generator", l->generator ? l->generator : "vtpipe",
                  "width", (json_int_t)l->width, "height", (json_int_t)l->height, "tile_content",
                  (json_int_t)l->tile_content, "border", (json_int_t)l->border, "layers", layers,
                  "entries", entries);
    /* materials only when there are some: layouts without them are written as before */
    if (root && l->material_count && json_object_set_new(root, "materials", materials_json(l))) {
        json_decref(root);
        return NULL;
    }
    /* pack materials likewise only when there are some */
    if (root && l->wang_count && json_object_set_new(root, "wang_materials", wangs_json(l))) {
        json_decref(root);
        return NULL;
    }
    return root;
fail:
    json_decref(layers);
    json_decref(entries);
    return NULL;
}

int vt_layout_write(const char *path, struct vt_layout *layout, struct vts_error *err)
{
    int rc = vt_layout_check(layout, path, err);
    if (rc)
        return rc;
    for (uint32_t i = 0; i < layout->layer_count; i++)
        if (layout->layers[i].colour < VTS_COLOUR_SRGB ||
            layout->layers[i].colour > VTS_COLOUR_DATA)
            return vt_error_set(err, VTS_ERR_ARG, "'%s': layer %u has no colour", path, i);
    json_t *root = layout_json(layout);
    char *text =
        root ? json_dumps(root, JSON_INDENT(1) | JSON_PRESERVE_ORDER | JSON_REAL_PRECISION(17))
             : NULL;
    json_decref(root);
    if (!text)
        return vt_error_set(err, VTS_ERR_NOMEM, "'%s': out of memory writing the layout", path);
    struct vt_atomic_file f;
    rc = vt_atomic_file_create(&f, path, "tmp", VT_ATOMIC_FILE_SEQUENTIAL, err);
    if (!rc) {
        size_t n = strlen(text);
        rc = vt_atomic_file_pwrite(&f, text, n, 0, err);
        if (!rc)
            rc = vt_atomic_file_pwrite(&f, "\n", 1, n, err);
        if (!rc)
            rc = vt_atomic_file_commit(&f, err);
        else
            vt_atomic_file_abort(&f);
    }
    free(text);
    return rc;
}
