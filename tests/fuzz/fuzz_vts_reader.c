/* libFuzzer target for the .vts store reader (scripts/fuzz): open the input from memory, and if it
 * opens, read every tile into a buffer of exactly the largest payload and walk every accessor.
 * Invariants are checked, not only crashes: a failed open must give a reader status with a one-line
 * message naming the input; a store that opens must read every tile with status 0 or CHECKSUM.
 *
 * The custom mutator re-seals the CRCs of half of the mutants (tests/robust/vts_reseal.c), so that
 * mutations reach the structural checks behind the header, layer, index and metadata CRCs. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "robust/vts_reseal.h"
#include "vts.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
size_t LLVMFuzzerMutate(uint8_t *data, size_t size, size_t max_size);
size_t LLVMFuzzerCustomMutator(uint8_t *data, size_t size, size_t max_size, unsigned int seed);

#define NAME "fuzz.vts"

static void walk(const struct vts_store *s)
{
    const struct vts_geometry *g = vts_store_geometry(s);
    uint64_t per_layer = vts_store_tile_count(s) / g->layer_count;
    uint32_t max = vts_store_max_payload(s);
    unsigned char *buf = max ? malloc(max) : NULL; /* no payload at all: reads need no buffer */
    if (max && !buf)
        abort();
    unsigned major, minor;
    vts_store_version(s, &major, &minor);
    if (major != VTS_FORMAT_MAJOR || strcmp(vts_store_name(s), NAME) != 0 ||
        vts_store_layer(s, g->layer_count) != NULL || vts_store_entry(s, vts_store_tile_count(s)))
        abort();
    struct vts_error err;
    size_t len;
    for (uint32_t layer = 0; layer < g->layer_count; layer++) {
        const struct vts_layer *L = vts_store_layer(s, layer);
        if (!L || !memchr(L->name, '\0', sizeof L->name) || L->channels < 1 || L->channels > 4)
            abort();
        /* what vt-info prints of a layer, from untrusted bytes */
        char codec[5];
        vts_codec_name(L->codec, codec);
        if (strlen(codec) > 4 || strcmp(vts_sample_name(L->sample), "?") == 0 ||
            strcmp(vts_colour_name(L->colour), "?") == 0 || vts_layer_tile_bytes(g, L) == 0)
            abort();
        for (uint32_t level = 0; level < g->level_count; level++) {
            struct vts_level lv;
            vts_store_level(s, level, &lv);
            for (uint32_t ty = 0; ty < lv.tiles_y; ty++)
                for (uint32_t tx = 0; tx < lv.tiles_x; tx++) {
                    struct vts_tile_entry e;
                    if (vts_store_tile(s, layer, level, tx, ty, &e, &err) != 0 || e.length > max ||
                        e.offset > vts_store_file_size(s) ||
                        e.length > vts_store_file_size(s) - e.offset)
                        abort();
                    const struct vts_tile_entry *by_index = vts_store_entry(
                        s, layer * per_layer + lv.first_tile + (uint64_t)ty * lv.tiles_x + tx);
                    if (!by_index || memcmp(by_index, &e, sizeof e) != 0)
                        abort();
                    int rc = vts_store_read(s, layer, level, tx, ty, buf, max, &len,
                                            (tx ^ ty) & 1 ? VTS_READ_NO_CRC : 0, &err);
                    if ((rc != 0 && rc != VTS_ERR_CHECKSUM) || (rc == 0 && len != e.length))
                        abort();
                    if (e.length > 0 && vts_store_read(s, layer, level, tx, ty, buf, e.length - 1,
                                                       &len, 0, &err) != VTS_ERR_LIMIT)
                        abort();
                }
            if (vts_store_read(s, layer, level, lv.tiles_x, 0, buf, max, &len, 0, &err) !=
                VTS_ERR_RANGE)
                abort();
        }
    }
    for (uint32_t i = 0; i < vts_store_meta_count(s); i++) {
        const char *k = vts_store_meta_key(s, i), *v = vts_store_meta_value(s, i);
        if (!k || !v || !*k || strchr(k, '=') || strchr(k, ' ') || !vts_store_meta_find(s, k))
            abort();
    }
    free(buf);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    struct vts_error err = {0};
    struct vts_store *s = vts_open_memory(data, size, NAME, &err);
    if (!s) {
        if ((err.status != VTS_ERR_NOT_VTS && err.status != VTS_ERR_VERSION &&
             err.status != VTS_ERR_CORRUPT && err.status != VTS_ERR_CHECKSUM) ||
            !strstr(err.message, NAME) || strchr(err.message, '\n'))
            abort();
        return 0;
    }
    walk(s);
    vts_close(s);
    return 0;
}

size_t LLVMFuzzerCustomMutator(uint8_t *data, size_t size, size_t max_size, unsigned int seed)
{
    size = LLVMFuzzerMutate(data, size, max_size);
    if (seed & 1)
        vts_reseal_all(data, size);
    return size;
}
