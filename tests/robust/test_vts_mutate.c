/* Deterministic mutation test of the store reader: a seeded PRNG mutates valid stores (bit flips,
 * random bytes, boundary values written over header, layer, index and metadata fields, truncation,
 * extension, copied chunks); half of the mutants get their CRCs re-sealed so that the structural
 * checks behind the checksums are reached. Each mutant is opened from an exact-size allocation
 * and, when it opens, every tile is read into a buffer of exactly vts_store_max_payload() bytes.
 * Nothing may crash (the sanitizer build runs this under ASan+UBSan), every failure must carry a
 * reader status and a one-line message naming the file, and a store that opens must be readable.
 *
 * VTS_MUTATE_ITERATIONS and VTS_MUTATE_SEED in the environment override the defaults (20000, 1). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "internal/vts_format.h"
#include "robust/vts_fixture.h"
#include "vt_test.h"
#include "vts.h"

static uint64_t rng_state;

static uint64_t rng(void) /* splitmix64 */
{
    uint64_t z = (rng_state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

static uint64_t below(uint64_t n)
{
    return n ? rng() % n : 0;
}

struct field {
    unsigned off, width;
};

static const struct field header_fields[] = {
    {VTS_H_MAJOR, 2},       {VTS_H_MINOR, 2},       {VTS_H_HEADER_SIZE, 4},
    {VTS_H_WIDTH, 4},       {VTS_H_HEIGHT, 4},      {VTS_H_CONTENT, 4},
    {VTS_H_BORDER, 4},      {VTS_H_PAYLOAD, 4},     {VTS_H_LEVELS, 4},
    {VTS_H_LAYERS, 4},      {VTS_H_FLAGS, 4},       {VTS_H_LAYER_OFFSET, 8},
    {VTS_H_LAYER_ENTRY, 4}, {VTS_H_INDEX_ENTRY, 4}, {VTS_H_INDEX_OFFSET, 8},
    {VTS_H_INDEX_COUNT, 8}, {VTS_H_DATA_OFFSET, 8}, {VTS_H_DATA_SIZE, 8},
    {VTS_H_META_OFFSET, 8}, {VTS_H_META_SIZE, 4},   {VTS_H_LAYERS_CRC, 4},
    {VTS_H_INDEX_CRC, 4},   {VTS_H_META_CRC, 4},    {VTS_H_RESERVED, 4},
    {VTS_H_HEADER_CRC, 4},
};

static uint64_t load(const unsigned char *p, unsigned width)
{
    uint64_t v = 0;
    for (unsigned i = 0; i < width; i++)
        v |= (uint64_t)p[i] << (8 * i);
    return v;
}

static void store(unsigned char *p, unsigned width, uint64_t v)
{
    for (unsigned i = 0; i < width; i++)
        p[i] = (unsigned char)(v >> (8 * i));
}

/* A value that sits on some boundary: limits, powers of two, the file size, the old value +-1. */
static uint64_t boundary_value(uint64_t old, size_t size, unsigned width)
{
    static const uint64_t fixed[] = {0,
                                     1,
                                     2,
                                     3,
                                     4,
                                     5,
                                     7,
                                     8,
                                     15,
                                     16,
                                     17,
                                     31,
                                     32,
                                     33,
                                     47,
                                     48,
                                     63,
                                     64,
                                     65,
                                     127,
                                     128,
                                     129,
                                     255,
                                     256,
                                     4095,
                                     4096,
                                     4097,
                                     16383,
                                     16384,
                                     16385,
                                     65535,
                                     65536,
                                     1u << 24,
                                     1u << 30,
                                     (1u << 30) + 1,
                                     0x7fffffff,
                                     0x80000000,
                                     0xfffffffe,
                                     0xffffffff,
                                     1ull << 32,
                                     1ull << 36,
                                     1ull << 63,
                                     UINT64_MAX - 15,
                                     UINT64_MAX};
    uint64_t v;
    switch (below(6)) {
    case 0:
    case 1:
        v = fixed[below(sizeof fixed / sizeof fixed[0])];
        break;
    case 2:
        v = size + below(3) - 1;
        break;
    case 3:
        v = old + below(5) - 2;
        break;
    case 4:
        v = below(size + 1);
        break;
    default:
        v = rng();
        break;
    }
    return width == 8 ? v : v & ((1ull << (8 * width)) - 1);
}

/* Offset and size of a structure named by the (valid) header, or 0 if it does not fit. */
static bool region(const unsigned char *d, size_t size, unsigned off_field, uint64_t len,
                   uint64_t *off)
{
    *off = vts_load_u64(d + off_field);
    return len > 0 && *off <= size && len <= size - *off;
}

static void mutate_once(unsigned char **data, size_t *size)
{
    unsigned char *d = *data;
    size_t n = *size;
    uint64_t off;
    switch (below(10)) {
    case 0: /* flip a bit */
        if (n)
            d[below(n)] ^= (unsigned char)(1u << below(8));
        break;
    case 1: /* random byte */
        if (n)
            d[below(n)] = (unsigned char)rng();
        break;
    case 2:
    case 3: { /* a header field */
        if (n < VTS_HEADER_SIZE)
            break;
        const struct field *f = &header_fields[below(sizeof header_fields / sizeof *header_fields)];
        store(d + f->off, f->width, boundary_value(load(d + f->off, f->width), n, f->width));
        break;
    }
    case 4:
    case 5: { /* an index entry field: offset, length or CRC; or a copy of another entry */
        if (n < VTS_HEADER_SIZE)
            break;
        uint64_t count = vts_load_u64(d + VTS_H_INDEX_COUNT);
        if (count == 0 || count > n / VTS_INDEX_ENTRY_SIZE ||
            !region(d, n, VTS_H_INDEX_OFFSET, count * VTS_INDEX_ENTRY_SIZE, &off))
            break;
        unsigned char *e = d + off + below(count) * VTS_INDEX_ENTRY_SIZE;
        unsigned k = (unsigned)below(4);
        if (k == 3)
            memcpy(e, d + off + below(count) * VTS_INDEX_ENTRY_SIZE, VTS_INDEX_ENTRY_SIZE);
        else if (k == 0)
            store(e, 8, boundary_value(load(e, 8), n, 8));
        else
            store(e + 4 + 4 * k, 4, boundary_value(load(e + 4 + 4 * k, 4), n, 4));
        break;
    }
    case 6: { /* a layer table byte or word */
        if (n < VTS_HEADER_SIZE)
            break;
        uint64_t layers = vts_load_u32(d + VTS_H_LAYERS);
        if (layers == 0 || layers > VTS_MAX_LAYERS ||
            !region(d, n, VTS_H_LAYER_OFFSET, layers * VTS_LAYER_ENTRY_SIZE, &off))
            break;
        unsigned char *e = d + off + below(layers) * VTS_LAYER_ENTRY_SIZE;
        if (below(2))
            e[below(VTS_L_NAME + 1)] = (unsigned char)boundary_value(0, n, 1);
        else
            memset(e + VTS_L_NAME, 'x', VTS_LAYER_NAME_BYTES - below(2));
        break;
    }
    case 7: { /* a metadata word (count, lengths) or byte */
        if (n < VTS_HEADER_SIZE)
            break;
        uint32_t msize = vts_load_u32(d + VTS_H_META_SIZE);
        if (msize < 4 || !region(d, n, VTS_H_META_OFFSET, msize, &off))
            break;
        uint64_t at = below(msize - 3);
        if (below(2))
            store(d + off + at, 4, boundary_value(load(d + off + at, 4), msize, 4));
        else
            d[off + at] = "= \x01\x7f\0a"[below(6)];
        break;
    }
    case 8: { /* truncate or extend */
        size_t len = below(3) ? below(n + 1) : n + 1 + below(64);
        unsigned char *p = realloc(d, len ? len : 1);
        for (size_t i = n; i < len; i++)
            p[i] = (unsigned char)rng();
        *data = p;
        *size = len;
        break;
    }
    default: { /* copy a chunk over another place */
        if (n < 2)
            break;
        size_t a = below(n), b = below(n), len = 1 + below(32);
        if (len > n - a)
            len = n - a;
        if (len > n - b)
            len = n - b;
        memmove(d + b, d + a, len);
        break;
    }
    }
}

static unsigned long env_or(const char *name, unsigned long fallback)
{
    const char *v = getenv(name);
    return v && *v ? strtoul(v, NULL, 10) : fallback;
}

static void mutants_never_crash_and_fail_with_a_reader_status(void)
{
    char tmpdir[256];
    VT_CHECK(vts_fixture_mkdtemp(tmpdir, sizeof tmpdir, "test_vts_mutate"));
    unsigned char *base[VTS_FIXTURE_COUNT];
    size_t base_size[VTS_FIXTURE_COUNT];
    for (int i = 0; i < VTS_FIXTURE_COUNT; i++) {
        base[i] = vts_fixture_bytes(tmpdir, (enum vts_fixture)i, &base_size[i]);
        VT_CHECK(base[i] != NULL);
        if (!base[i])
            return;
    }
    vts_fixture_rmdir_all(tmpdir);

    unsigned long iterations = env_or("VTS_MUTATE_ITERATIONS", 20000);
    rng_state = env_or("VTS_MUTATE_SEED", 1);
    unsigned long opened[2] = {0}, by_status[2][16] = {{0}}, bad = 0;
    for (unsigned long it = 0; it < iterations; it++) {
        /* mostly the small and medium stores, sometimes the payload-free one */
        int which = it % 8 == 7 ? VTS_FIXTURE_EMPTY : (int)(it % 2);
        size_t size = base_size[which];
        unsigned char *d = malloc(size);
        memcpy(d, base[which], size);
        int ops = 1 + (int)below(4);
        for (int k = 0; k < ops; k++)
            mutate_once(&d, &size);
        int sealed = (int)(it & 1) ^ (int)((it >> 3) & 1);
        if (sealed)
            vts_reseal_all(d, size);
        /* an exact-size copy: the realloc'd buffer may be larger than size */
        unsigned char *exact = malloc(size ? size : 1);
        memcpy(exact, d, size);
        free(d);
        char name[64];
        snprintf(name, sizeof name, "mutant-%lu.vts", it);
        struct vts_error err;
        unsigned read_failures = 0;
        int rc = vts_fixture_exercise(exact, size, name, &err, &read_failures);
        free(exact);
        bool ok;
        if (rc == 0) {
            opened[sealed]++;
            ok = read_failures == 0;
        } else {
            ok = (rc == VTS_ERR_NOT_VTS || rc == VTS_ERR_VERSION || rc == VTS_ERR_CORRUPT ||
                  rc == VTS_ERR_CHECKSUM) &&
                 strstr(err.message, name) != NULL && strchr(err.message, '\n') == NULL;
            by_status[sealed][-rc & 15]++;
        }
        if (!ok && bad++ < 20)
            fprintf(stderr, "  mutant %lu: status %s, %u bad reads, '%s'\n", it,
                    vts_status_name(rc), read_failures, rc ? err.message : "");
    }
    VT_CHECK_INT_EQ(bad, 0);
    for (int sealed = 0; sealed < 2; sealed++)
        fprintf(stderr,
                "     %s: opened %lu, not-vts %lu, version %lu, corrupt %lu, checksum %lu\n",
                sealed ? "re-sealed" : "unsealed ", opened[sealed],
                by_status[sealed][-VTS_ERR_NOT_VTS], by_status[sealed][-VTS_ERR_VERSION],
                by_status[sealed][-VTS_ERR_CORRUPT], by_status[sealed][-VTS_ERR_CHECKSUM]);
    /* The mutations must reach every kind of outcome, or the test exercises too little: re-sealed
     * mutants mostly fail structural checks, unsealed ones mostly checksums, some open. */
    if (iterations >= 20000) {
        unsigned long per_half = iterations / 2;
        VT_CHECK(by_status[1][-VTS_ERR_CORRUPT] > per_half / 4);
        VT_CHECK(by_status[0][-VTS_ERR_CHECKSUM] > per_half / 4);
        VT_CHECK(by_status[1][-VTS_ERR_VERSION] > 0);
        VT_CHECK(by_status[1][-VTS_ERR_NOT_VTS] > 0);
        VT_CHECK(opened[0] + opened[1] > iterations / 100);
    }
    for (int i = 0; i < VTS_FIXTURE_COUNT; i++)
        free(base[i]);
}

int main(void)
{
    VT_RUN(mutants_never_crash_and_fail_with_a_reader_status);
    return vt_test_main_result();
}
