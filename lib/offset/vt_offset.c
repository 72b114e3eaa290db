/* vt-offset's rewriting engine (see vt_offset.h and docs/cli/vt-offset.md).
 *
 * The OBJ is read twice through the same raw line source. It keeps each logical line as raw bytes
 * (terminators, '\r' and '\' continuations included) so that lines can be copied unchanged, and
 * tokenises the raw bytes with vt_obj's rules: whitespace is space, tab, '\r', '\v', '\f', a
 * '\n' inside a continued line and a '\' that continues the line; a token starting with '#' ends
 * the statement. We do not use vt_obj_read() for pass 1: it keeps every v and vn (the rewrite
 * must grow with the vt count only) and parses their numbers with strtod (too slow here); the
 * statements that matter (vt, f, usemtl, mtllib) are checked with its rules and messages.
 *
 * Modules: vt_offset_src.c (raw logical lines), vt_offset_tok.c (tokens), vt_offset_run.c (state
 * shared by the passes, buffered output), vt_offset_scan.c (pass 1), vt_offset_mesh.c (charts,
 * moves, cuts and keys between the passes), vt_offset_write.c (pass 2);
 * this file holds the public functions and the driver. */
#include "vt_offset.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "internal/vt_offset_impl.h"
#include "internal/vt_offset_src.h"
#include "vt_chart.h"
#include "vt_error.h"
#include "vt_uv_text.h"

void vt_offset_options_default(struct vt_offset_options *opt)
{
    memset(opt, 0, sizeof *opt);
    opt->layout_name = "atlas.json";
    opt->mtllib = "out.mtl";
    opt->material = VT_OFFSET_MATERIAL;
    vt_obj_limits_default(&opt->limits);
}

unsigned vt_offset_default_digits(const struct vt_layout *layout)
{
    double edge = layout->width > layout->height ? layout->width : layout->height;
    unsigned digits = 6;
    /* half a unit of the last place, in texels, at most 1e-4 */
    while (digits < VT_UV_MAX_DIGITS && 0.5 * pow(10.0, -(double)digits) * edge > 1e-4)
        digits++;
    return digits;
}

bool vt_offset_f32_warning(const struct vt_offset_stats *stats)
{
    return stats->max_error_f32 > VT_OFFSET_F32_WARN_TEXELS;
}

static int run_pass(struct vt_offset_run *r, const char *path, const void *mem, size_t size,
                    int pass, struct vts_error *err)
{
    int rc = vt_offset_src_open(&r->src, path, mem, size, r->opt->limits.max_line_bytes, err);
    if (rc < 0)
        return rc;
    const unsigned char *line = NULL;
    size_t n = 0;
    r->mat = VT_OFFSET_MAT_NONE;
    r->mat_group = VT_CHART_NONE;
    while ((rc = vt_offset_src_next(&r->src, &line, &n, err)) == 1) {
        rc = pass == 1 ? vt_offset_scan_line(r, line, n, err)
                       : vt_offset_write_line(r, line, n, err);
        if (rc < 0)
            break;
    }
    if (rc == 0 && pass == 1)
        r->stats.lines = r->src.physical;
    if (rc == 0 && pass == 2 &&
        (r->in_vt != r->nvt || r->in_face != r->faces.count || r->src.physical != r->stats.lines))
        rc = vt_offset_run_changed_error(r, err);
    vt_offset_src_close(&r->src);
    return rc;
}

static int cmp_name(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

/* The used slots in slot order; the unknown names sorted, each once. */
static int finish_used(struct vt_offset_run *r, struct vt_offset_used *u, struct vts_error *err)
{
    size_t n = r->slot_used ? r->layout->name_count : 0;
    uint32_t count = 0;
    for (size_t i = 0; i < n; i++)
        count += r->slot_used[i];
    u->slots = malloc((count ? count : 1) * sizeof *u->slots);
    if (!u->slots)
        return vt_error_set(err, VTS_ERR_NOMEM, "'%s': out of memory", r->name);
    for (size_t i = 0; i < n; i++)
        if (r->slot_used[i])
            u->slots[u->slot_count++] = (uint32_t)i;
    if (u->unknown_count > 1)
        qsort(u->unknown, u->unknown_count, sizeof *u->unknown, cmp_name);
    uint32_t k = 0;
    for (uint32_t i = 0; i < u->unknown_count; i++) {
        if (k && strcmp(u->unknown[k - 1], u->unknown[i]) == 0)
            free(u->unknown[i]);
        else
            u->unknown[k++] = u->unknown[i];
    }
    u->unknown_count = k;
    return 0;
}

void vt_offset_used_release(struct vt_offset_used *used)
{
    if (!used)
        return;
    free(used->slots);
    for (uint32_t i = 0; i < used->unknown_count; i++)
        free(used->unknown[i]);
    free(used->unknown);
    memset(used, 0, sizeof *used);
}

static int rewrite(const char *path, const void *mem, size_t size, const struct vt_layout *layout,
                   const struct vt_offset_options *opt, const struct vt_offset_sink *out,
                   struct vt_offset_stats *stats, struct vts_error *err)
{
    struct vt_offset_options defaults;
    if (!opt) {
        vt_offset_options_default(&defaults);
        opt = &defaults;
    }
    if (!layout || !out || !out->write || opt->digits > VT_UV_MAX_DIGITS || !opt->mtllib)
        return vt_error_set(err, VTS_ERR_ARG, "vt_offset_rewrite: bad arguments");
    if (opt->used)
        memset(opt->used, 0, sizeof *opt->used);
    struct vt_offset_run r = {0};
    r.layout = layout;
    r.name = path;
    r.opt = opt;
    r.out = out;
    r.digits = opt->digits ? opt->digits : vt_offset_default_digits(layout);
    r.stats.digits = r.digits;
    int rc = run_pass(&r, path, mem, size, 1, err);
    if (rc == 0)
        rc = vt_offset_mesh_resolve(&r, path, mem, size, err);
    if (rc == 0) {
        r.obuf = malloc(VT_OFFSET_OUT_CHUNK);
        if (!r.obuf)
            rc = vt_error_set(err, VTS_ERR_NOMEM, "'%s': out of memory", path);
    }
    if (rc == 0) {
        r.stats.vt_lines = r.nvt;
        rc = run_pass(&r, path, mem, size, 2, err);
    }
    if (rc == 0 && !r.mtllib_written) { /* an empty input */
        rc = vt_offset_run_str(&r, "mtllib ", err);
        if (rc == 0)
            rc = vt_offset_run_str(&r, opt->mtllib, err);
        if (rc == 0)
            rc = vt_offset_run_str(&r, "\n", err);
    }
    if (rc == 0)
        rc = vt_offset_run_flush(&r, err);
    if (rc == 0 && opt->used)
        rc = finish_used(&r, opt->used, err);
    if (rc && opt->used)
        vt_offset_used_release(opt->used);
    if (rc == 0 && stats)
        *stats = r.stats;
    vt_offset_mesh_release(&r);
    free(r.uv);
    free(r.first);
    free(r.head);
    free(r.new_index);
    free(r.extra);
    free(r.mat_name);
    free(r.clean);
    free(r.repl);
    free(r.obuf);
    free(r.slot_used);
    return rc;
}

int vt_offset_rewrite(const char *obj_path, const struct vt_layout *layout,
                      const struct vt_offset_options *opt, const struct vt_offset_sink *out,
                      struct vt_offset_stats *stats, struct vts_error *err)
{
    return rewrite(obj_path, NULL, 0, layout, opt, out, stats, err);
}

int vt_offset_rewrite_memory(const void *data, size_t size, const char *name,
                             const struct vt_layout *layout, const struct vt_offset_options *opt,
                             const struct vt_offset_sink *out, struct vt_offset_stats *stats,
                             struct vts_error *err)
{
    static const unsigned char empty[1];
    return rewrite(name, data ? data : empty, data ? size : 0, layout, opt, out, stats, err);
}
