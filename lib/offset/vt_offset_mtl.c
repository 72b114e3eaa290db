/* The MTL of a rewrite (vt_offset_write_mtl() in vt_offset.h): every material the faces use, with
 * its constants and alpha mode from the layout, its maps naming the store and a layer. Syntax:
 * docs/cli/vt-offset.md, "The MTL". */
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "vt_error.h"
#include "vt_offset.h"

struct mtl_out {
    const struct vt_offset_sink *out;
    struct vts_error *err;
    int rc;
};

static void put(struct mtl_out *o, const char *s)
{
    if (o->rc == 0 && *s)
        o->rc = o->out->write(o->out->user, s, strlen(s), o->err);
}

static void putf(struct mtl_out *o, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

static void putf(struct mtl_out *o, const char *fmt, ...)
{
    char line[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(line, sizeof line, fmt, ap); /* numbers only: never truncated */
    va_end(ap);
    put(o, line);
}

static void put_rgb(struct mtl_out *o, const char *kw, const double c[3])
{
    putf(o, "%s %.9g %.9g %.9g\n", kw, c[0], c[1], c[2]);
}

/* The constants a layout without materials implies for the entry e: Kd 1 with a diffuse map,
 * else the diffuse fill (or 0.8 grey: a name the layout lacks); opaque, no specular. */
static void implied_material(const struct vt_layout *l, const struct vt_layout_entry *e,
                             struct vt_layout_material *m)
{
    memset(m, 0, sizeof *m);
    m->d = 1;
    m->illum = 1;
    int diffuse = vt_layout_layer_index(l, "diffuse");
    for (int k = 0; k < 3; k++)
        m->kd[k] = 0.8;
    for (uint32_t k = 0; e && k < l->layer_count; k++)
        if (e->textures[k].path)
            m->layer_mask |= 1u << k;
    if (e && diffuse >= 0)
        for (int k = 0; k < 3; k++)
            m->kd[k] = e->textures[diffuse].path ? 1 : e->textures[diffuse].fill[k];
}

static void put_material(struct mtl_out *o, const struct vt_layout *l, const char *name,
                         const struct vt_layout_material *m, const char *store)
{
    put(o, "\nnewmtl ");
    put(o, name);
    put(o, "\n");
    put_rgb(o, "Ka", m->ka);
    put_rgb(o, "Kd", m->kd);
    put_rgb(o, "Ks", m->ks);
    put_rgb(o, "Ke", m->ke);
    putf(o, "Ns %.9g\nd %.9g\nillum %u\nvt_alpha %s\n", m->ns, m->d, m->illum,
         vt_layout_alpha_name(m->alpha));
    for (uint32_t k = 0; k < l->layer_count; k++)
        if (m->layer_mask >> k & 1) {
            put(o, l->layers[k].map);
            put(o, " ");
            put(o, store);
            put(o, "#");
            put(o, l->layers[k].name);
            put(o, "\n");
        }
}

int vt_offset_write_mtl(const struct vt_layout *layout, const struct vt_offset_used *used,
                        const char *store, const char *header_comment,
                        const struct vt_offset_sink *out, struct vts_error *err)
{
    struct mtl_out o = {out, err, 0};
    for (const char *s = header_comment; s && *s && o.rc == 0;) {
        size_t n = strcspn(s, "\n");
        put(&o, "# ");
        if (o.rc == 0)
            o.rc = out->write(out->user, s, n, err);
        put(&o, "\n");
        s += n + (s[n] == '\n');
    }
    put(&o, "# each map names a layer of the store: <store>#<layer>\n");
    for (uint32_t i = 0; i < used->slot_count && o.rc == 0; i++) {
        uint32_t slot = used->slots[i];
        const struct vt_layout_name *n = &layout->by_name[slot];
        const struct vt_layout_entry *e = &layout->entries[n->entry];
        const char *name = n->alias ? e->aliases[n->alias - 1] : e->name;
        struct vt_layout_material implied;
        const struct vt_layout_material *m =
            slot < layout->material_count ? &layout->materials[slot] : NULL;
        if (!m) {
            implied_material(layout, e, &implied);
            m = &implied;
        }
        put_material(&o, layout, name, m, store);
    }
    for (uint32_t i = 0; i < used->unknown_count && o.rc == 0; i++) {
        const struct vt_layout_wang *w = vt_layout_wang_find(layout, used->unknown[i]);
        if (w) { /* a pack material (docs/wang.md): its constants and its pack, no maps */
            if (strpbrk(w->pack, " \t\r\n"))
                return vt_error_set(err, VTS_ERR_BAD_INPUT,
                                    "material '%s': pack path '%s' has white space (a vt_wang "
                                    "path is one token)",
                                    w->m.name, w->pack);
            put_material(&o, layout, w->m.name, &w->m, store);
            put(&o, "vt_wang ");
            put(&o, w->pack);
            putf(&o, " scale %.17g\n", w->scale);
            continue;
        }
        struct vt_layout_material implied;
        implied_material(layout, NULL, &implied);
        put(&o, "\n# not in the layout (its faces have no texture coordinates)");
        put_material(&o, layout, used->unknown[i], &implied, store);
    }
    return o.rc;
}
