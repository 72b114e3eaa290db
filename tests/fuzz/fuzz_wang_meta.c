/* libFuzzer target for a Wang pack's metadata (lib/wang/vt_wang_meta.c): the bytes are lines of
 * KEY=VALUE. Invariants, not only crashes: parsed metadata has colours, tile and grid in range,
 * the grid that the colours give, a hash and an order that are permutations, and every output
 * tile located inside the pack; a failure has its status and a one-line message naming the key. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "vt_wang.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

struct pairs {
    char *text;
    char *keys[16], *values[16];
    unsigned n;
};

static const char *get(void *user, const char *key)
{
    const struct pairs *p = user;
    const char *found = NULL;
    for (unsigned i = 0; i < p->n; i++)
        if (strcmp(p->keys[i], key) == 0)
            found = p->values[i]; /* the last one wins, as in the store */
    return found;
}

static bool permutation(const uint32_t *v, uint32_t n)
{
    unsigned char *seen = calloc(n, 1);
    bool ok = seen != NULL;
    for (uint32_t i = 0; ok && i < n; i++)
        ok = v[i] < n && !seen[v[i]]++;
    free(seen);
    return ok;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    struct pairs p = {malloc(size + 1), {0}, {0}, 0};
    if (!p.text)
        return 0;
    memcpy(p.text, data, size);
    p.text[size] = '\0';
    for (char *line = p.text, *next; line && p.n < 16; line = next) {
        next = strchr(line, '\n');
        if (next)
            *next++ = '\0';
        char *eq = strchr(line, '=');
        if (eq) {
            *eq = '\0';
            p.keys[p.n] = line;
            p.values[p.n++] = eq + 1;
        }
    }
    struct vt_wang_info info;
    struct vts_error err = {0};
    int rc = vt_wang_info_parse(get, &p, &info, &err);
    if (rc < 0) {
        if (rc != VTS_ERR_ARG && rc != VTS_ERR_CORRUPT && rc != VTS_ERR_NOMEM)
            abort();
        if (!err.message[0] || strchr(err.message, '\n') || !strstr(err.message, "wang."))
            abort();
    } else {
        struct vt_wang_params w = {info.tile_px, info.kh, info.kv, info.corners, 0, false, 0};
        uint32_t cols, rows;
        vt_wang_grid(&w, &cols, &rows);
        if (info.kh < 1 || info.kh > VTS_WANG_MAX_COLOURS || info.kv < 1 ||
            info.kv > VTS_WANG_MAX_COLOURS || cols != info.cols || rows != info.rows ||
            info.hash_n < 1 || !permutation(info.hash, info.hash_n) ||
            (info.order && !permutation(info.order, cols * rows)))
            abort();
        for (uint32_t y = 0; y < 8; y++)
            for (uint32_t x = 0; x < 8; x++) {
                uint32_t col, row;
                vt_wang_info_locate(&info, x * 977u, y * 613u, &col, &row);
                if (col >= cols || row >= rows)
                    abort();
            }
    }
    vt_wang_info_release(&info);
    free(p.text);
    return 0;
}
