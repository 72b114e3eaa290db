/* The state shared by vt-offset's two passes and its buffered output (see vt_offset_run.h). */
#include "internal/vt_offset_impl.h"

#include <stdlib.h>
#include <string.h>

#include "vt_error.h"
#include "vt_text.h"

int vt_offset_run_flush(struct vt_offset_run *r, struct vts_error *err)
{
    if (r->olen == 0)
        return 0;
    int rc = r->out->write(r->out->user, r->obuf, r->olen, err);
    r->olen = 0;
    return rc < 0 ? rc : 0;
}

int vt_offset_run_put(struct vt_offset_run *r, const void *data, size_t n, struct vts_error *err)
{
    if (n > VT_OFFSET_OUT_CHUNK - r->olen) {
        int rc = vt_offset_run_flush(r, err);
        if (rc < 0)
            return rc;
        if (n > VT_OFFSET_OUT_CHUNK) {
            rc = r->out->write(r->out->user, data, n, err);
            return rc < 0 ? rc : 0;
        }
    }
    memcpy(r->obuf + r->olen, data, n);
    r->olen += n;
    return 0;
}

int vt_offset_run_str(struct vt_offset_run *r, const char *s, struct vts_error *err)
{
    return vt_offset_run_put(r, s, strlen(s), err);
}

/* Copies the line as vt_obj sees it into r->clean: '\r' before '\n' dropped, a continuing '\'
 * turned into a space, the '\n's removed. */
static int clean_line(struct vt_offset_run *r, const unsigned char *p, size_t n,
                      struct vts_error *err)
{
    if (n + 1 > r->clean_cap) {
        char *grown = realloc(r->clean, n + 1);
        if (!grown)
            return vt_error_set(err, VTS_ERR_NOMEM, "'%s': out of memory for a line", r->src.name);
        r->clean = grown;
        r->clean_cap = n + 1;
    }
    size_t len = 0;
    const unsigned char *end = p + n;
    while (p < end) {
        const unsigned char *nl = memchr(p, '\n', (size_t)(end - p));
        const unsigned char *pe = nl ? nl : end;
        size_t start = len;
        memcpy(r->clean + len, p, (size_t)(pe - p));
        len += (size_t)(pe - p);
        if (len > start && r->clean[len - 1] == '\r')
            len--;
        if (len > start && r->clean[len - 1] == '\\')
            r->clean[len - 1] = ' ';
        p = nl ? nl + 1 : end;
    }
    r->clean[len] = '\0';
    return 0;
}

/* The name on a usemtl line (vt_obj: the rest of the line, trimmed). */
int vt_offset_run_usemtl_name(struct vt_offset_run *r, const unsigned char *line, size_t n,
                              char **name, struct vts_error *err)
{
    int rc = clean_line(r, line, n, err);
    if (rc < 0)
        return rc;
    char *cur = r->clean;
    vt_text_token(&cur); /* the keyword */
    *name = vt_text_rest(cur);
    return 0;
}

uint32_t vt_offset_run_material(const struct vt_offset_run *r, const char *name)
{
    const struct vt_layout_entry *e = vt_layout_find(r->layout, name);
    if (e)
        return (uint32_t)(e - r->layout->entries);
    return vt_layout_wang_find(r->layout, name) ? VT_OFFSET_MAT_WANG : VT_OFFSET_MAT_MISSING;
}

uint32_t vt_offset_run_name_slot(const struct vt_offset_run *r, const char *name)
{
    const struct vt_layout *l = r->layout;
    size_t lo = 0, hi = l->name_count;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        const struct vt_layout_name *n = &l->by_name[mid];
        const struct vt_layout_entry *e = &l->entries[n->entry];
        int c = strcmp(name, n->alias ? e->aliases[n->alias - 1] : e->name);
        if (c == 0)
            return (uint32_t)mid;
        if (c < 0)
            hi = mid;
        else
            lo = mid + 1;
    }
    return VT_CHART_NONE;
}

/* True when every layer of e is a constant fill (a material without textures): its texture
 * coordinates do not matter, and every one is mapped to the centre of its cell so that bilinear
 * filtering never reaches the neighbouring cells. */
bool vt_offset_run_constant_entry(const struct vt_layout *l, const struct vt_layout_entry *e)
{
    for (uint32_t k = 0; k < l->layer_count; k++)
        if (e->textures[k].path)
            return false;
    return true;
}

int vt_offset_run_changed_error(struct vt_offset_run *r, struct vts_error *err)
{
    return vt_error_set(err, VTS_ERR_IO, "'%s':%llu: the file changed while it was read",
                        r->src.name, (unsigned long long)r->src.line);
}
