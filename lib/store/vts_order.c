#include "internal/vts_order.h"
#include "vt_error.h"

#include <stdlib.h>

uint64_t vts_hilbert_index(uint32_t order_bits, uint32_t x, uint32_t y)
{
    uint64_t d = 0;
    uint64_t n = 1ull << order_bits;
    for (uint64_t s = n / 2; s > 0; s /= 2) {
        uint32_t rx = (x & s) != 0, ry = (y & s) != 0;
        d += s * s * ((3u * rx) ^ ry);
        if (ry == 0) { /* rotate the quadrant so the curve stays continuous */
            if (rx == 1) {
                x = (uint32_t)(n - 1 - x);
                y = (uint32_t)(n - 1 - y);
            }
            uint32_t t = x;
            x = y;
            y = t;
        }
    }
    return d;
}

struct keyed {
    uint64_t key, tile;
};

static int compare_keyed(const void *a, const void *b)
{
    const struct keyed *x = a, *y = b;
    return x->key < y->key ? -1 : x->key > y->key;
}

int vts_order_level(uint32_t tiles_x, uint32_t tiles_y, uint64_t *out, struct vts_error *err)
{
    uint64_t count = (uint64_t)tiles_x * tiles_y;
    uint32_t bits = 0;
    while ((1ull << bits) < tiles_x || (1ull << bits) < tiles_y)
        bits++;
    struct keyed *k = malloc((size_t)count * sizeof *k);
    if (!k)
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory ordering %llu tiles",
                            (unsigned long long)count);
    for (uint32_t y = 0; y < tiles_y; y++)
        for (uint32_t x = 0; x < tiles_x; x++) {
            uint64_t t = (uint64_t)y * tiles_x + x;
            k[t] = (struct keyed){vts_hilbert_index(bits, x, y), t};
        }
    qsort(k, (size_t)count, sizeof *k, compare_keyed);
    for (uint64_t i = 0; i < count; i++)
        out[i] = k[i].tile;
    free(k);
    return 0;
}
