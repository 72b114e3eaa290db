/* Shared helpers of the vt-offset unit tests (offset_fixture.h). */
#include "offset_fixture.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vt_error.h"
#include "vts.h"

void offset_fixture_layout(struct vt_layout *l, uint32_t width, uint32_t height,
                           const struct spec *specs, uint32_t n)
{
    struct vts_error err = {0};
    int rc = vt_layout_alloc(l, 1, n, &err);
    if (rc < 0) {
        fprintf(stderr, "layout: %s\n", err.message);
        abort(); /* a fixture that cannot be built fails the test outright */
    }
    l->width = width;
    l->height = height;
    l->tile_content = 256;
    l->border = 4;
    l->layers[0].name = strdup("diffuse");
    l->layers[0].map = strdup("map_Kd");
    l->layers[0].colour = VTS_COLOUR_SRGB;
    for (uint32_t i = 0; i < n; i++) {
        struct vt_layout_entry *e = &l->entries[i];
        e->name = strdup(specs[i].name);
        e->x = specs[i].x, e->y = specs[i].y, e->width = specs[i].w, e->height = specs[i].h;
        e->repeat_u = specs[i].ru ? specs[i].ru : 1;
        e->repeat_v = specs[i].rv ? specs[i].rv : 1;
        e->origin_u = specs[i].ou, e->origin_v = specs[i].ov;
        e->cell_width = e->width * e->repeat_u;
        e->cell_height = e->height * e->repeat_v;
        /* A texture file, except for entries named "const...": a material without textures. */
        if (strncmp(e->name, "const", 5) != 0) {
            e->textures[0].path = strdup("tex.png");
            e->textures[0].resolved = strdup("tex.png");
            e->textures[0].width = e->width, e->textures[0].height = e->height;
        }
    }
    rc = vt_layout_index(l, &err);
    if (rc < 0) {
        fprintf(stderr, "layout: %s\n", err.message);
        abort();
    }
}

int offset_fixture_write(void *user, const void *data, size_t size, struct vts_error *err)
{
    struct membuf *m = user;
    (void)err;
    if (m->len + size + 1 > m->cap) {
        size_t cap = (m->len + size + 1) * 2;
        char *p = realloc(m->data, cap);
        if (!p)
            return VTS_ERR_NOMEM;
        m->data = p;
        m->cap = cap;
    }
    memcpy(m->data + m->len, data, size);
    m->len += size;
    m->data[m->len] = '\0';
    return 0;
}

/* Rewrites text onto l; returns the status, the output in *out (free it), stats and err. */
int offset_fixture_rewrite(const char *text, const struct vt_layout *l, unsigned digits,
                           struct membuf *out, struct vt_offset_stats *stats, struct vts_error *err)
{
    struct vt_offset_options opt;
    vt_offset_options_default(&opt);
    opt.mtllib = "out.mtl";
    opt.digits = digits;
    *out = (struct membuf){0};
    struct vt_offset_sink sink = {offset_fixture_write, out};
    memset(stats, 0, sizeof *stats);
    vt_error_clear(err);
    return vt_offset_rewrite_memory(text, strlen(text), "s.obj", l, &opt, &sink, stats, err);
}

int offset_fixture_expect_output(const char *text, const struct vt_layout *l, unsigned digits,
                                 const char *want, struct vt_offset_stats *stats)
{
    struct membuf out;
    struct vts_error err;
    int rc = offset_fixture_rewrite(text, l, digits, &out, stats, &err);
    int ok = rc == 0 && out.data && strcmp(out.data, want) == 0;
    if (!ok)
        fprintf(stderr, "rc %d (%s)\n--- got:\n%s--- want:\n%s---\n", rc, err.message,
                out.data ? out.data : "(null)", want);
    free(out.data);
    return ok;
}

int offset_fixture_expect_error(const char *text, const struct vt_layout *l, int status,
                                const char *message)
{
    struct membuf out;
    struct vts_error err;
    struct vt_offset_stats stats;
    int rc = offset_fixture_rewrite(text, l, 0, &out, &stats, &err);
    int ok = rc == status && strcmp(err.message, message) == 0 && out.len == 0;
    if (!ok)
        fprintf(stderr, "rc %d, message '%s', %zu bytes written; want %d '%s'\n", rc, err.message,
                out.len, status, message);
    free(out.data);
    return ok;
}

/* Reads the i-th (0-based) vt line of text into u, v. */
int offset_fixture_nth_vt(const char *text, int i, double *u, double *v)
{
    const char *p = text;
    for (int k = 0; p; p = strchr(p, '\n'), p = p ? p + 1 : NULL) {
        if (strncmp(p, "vt ", 3) == 0 && k++ == i)
            return sscanf(p + 3, "%lf %lf", u, v) == 2;
    }
    return 0;
}
