/* A Wang pack's parameters from a store's metadata (vt_wang.h, docs/wang.md). */
#include <errno.h>
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vt_wang.h"

/* Reads up to n unsigned numbers separated by single spaces, each <= max; returns the count read
 * or -1 for junk. */
static int64_t parse_list(const char *s, uint32_t *out, uint32_t n, uint32_t max)
{
    uint32_t count = 0;
    const char *p = s;
    while (*p) {
        char *end;
        if (*p < '0' || *p > '9' || count == n)
            return -1;
        errno = 0;
        unsigned long v = strtoul(p, &end, 10);
        if (errno || v > max)
            return -1;
        out[count++] = (uint32_t)v;
        p = end;
        if (*p == ' ')
            p++;
        else if (*p)
            return -1;
    }
    return count;
}

static bool is_permutation(const uint32_t *v, uint32_t n)
{
    unsigned char *seen = calloc(n, 1);
    bool ok = seen != NULL;
    for (uint32_t i = 0; ok && i < n; i++)
        ok = v[i] < n && !seen[v[i]]++;
    free(seen);
    return ok;
}

static int bad(struct vts_error *err, const char *key)
{
    return vt_error_set(err, VTS_ERR_CORRUPT, "bad Wang pack metadata '%s'", key);
}

int vt_wang_info_parse(const char *(*get)(void *user, const char *key), void *user,
                       struct vt_wang_info *info, struct vts_error *err)
{
    memset(info, 0, sizeof *info);
    const char *kind = get(user, VT_WANG_KEY_KIND), *v;
    char tail;
    if (!kind)
        return vt_error_set(err, VTS_ERR_ARG, "not a Wang pack (no '%s' metadata)",
                            VT_WANG_KEY_KIND);
    if (strcmp(kind, "edge") && strcmp(kind, "corner"))
        return bad(err, VT_WANG_KEY_KIND);
    info->corners = strcmp(kind, "corner") == 0;
    v = get(user, VT_WANG_KEY_COLOURS);
    if (!v || sscanf(v, "%" SCNu32 "x%" SCNu32 "%c", &info->kh, &info->kv, &tail) != 2 ||
        info->kh < 1 || info->kh > VTS_WANG_MAX_COLOURS || info->kv < 1 ||
        info->kv > VTS_WANG_MAX_COLOURS || (info->corners && info->kh != info->kv))
        return bad(err, VT_WANG_KEY_COLOURS);
    v = get(user, VT_WANG_KEY_TILE);
    if (!v || sscanf(v, "%" SCNu32 "%c", &info->tile_px, &tail) != 1 || info->tile_px < 1 ||
        info->tile_px > 65536)
        return bad(err, VT_WANG_KEY_TILE);
    struct vt_wang_params p = {info->tile_px, info->kh, info->kv, info->corners, 0, false, 0};
    uint32_t cols, rows, gc, gr;
    vt_wang_grid(&p, &cols, &rows);
    v = get(user, VT_WANG_KEY_GRID);
    if (!v || sscanf(v, "%" SCNu32 "x%" SCNu32 "%c", &gc, &gr, &tail) != 2 || gc != cols ||
        gr != rows)
        return bad(err, VT_WANG_KEY_GRID);
    info->cols = cols;
    info->rows = rows;
    v = get(user, VT_WANG_KEY_SEED);
    if (v)
        info->seed = strtoull(v, NULL, 10);
    v = get(user, VT_WANG_KEY_HASH);
    info->hash = malloc(VTS_WANG_MAX_HASH * sizeof *info->hash);
    if (!info->hash)
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
    int64_t n = v ? parse_list(v, info->hash, VTS_WANG_MAX_HASH, VTS_WANG_MAX_HASH - 1) : -1;
    if (n < 1 || !is_permutation(info->hash, (uint32_t)n)) {
        vt_wang_info_release(info);
        return bad(err, VT_WANG_KEY_HASH);
    }
    info->hash_n = (uint32_t)n;
    if ((v = get(user, VT_WANG_KEY_ORDER)) != NULL) {
        uint32_t slots = cols * rows;
        info->order = malloc(slots * sizeof *info->order);
        bool allocated = info->order != NULL;
        if (!allocated || parse_list(v, info->order, slots, slots - 1) != slots ||
            !is_permutation(info->order, slots)) {
            vt_wang_info_release(info);
            return allocated ? bad(err, VT_WANG_KEY_ORDER)
                             : vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
        }
    }
    return 0;
}

void vt_wang_info_release(struct vt_wang_info *info)
{
    if (!info)
        return;
    free(info->hash);
    free(info->order);
    info->hash = info->order = NULL;
}
