#include "vts_fixture.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "internal/vts_format.h"
#include "vt_error.h"
#include "vts_writer.h"

static const struct vts_geometry geometries[VTS_FIXTURE_COUNT] = {
    [VTS_FIXTURE_SMALL] = {40, 24, 16, 2, 20, 2, 2, 0},
    [VTS_FIXTURE_MEDIUM] = {300, 200, 60, 2, 64, 3, 3, VTS_STORE_WRAP_X},
    [VTS_FIXTURE_EMPTY] = {1, 1, 1, 0, 1, 1, 1, 0},
};

static const struct vts_layer layer_table[3] = {
    {VTS_CODEC_RAW, 4, VTS_SAMPLE_U8, VTS_COLOUR_SRGB, VTS_LAYER_PREMULTIPLIED, 0, "diffuse"},
    {VTS_CODEC_PNG, 3, VTS_SAMPLE_U16, VTS_COLOUR_NORMAL, 0, 6, "normal"},
    {VTS_CODEC_RAW, 1, VTS_SAMPLE_F32, VTS_COLOUR_DATA, 0, 0, "height"},
};

static const struct vts_layer empty_layer = {
    VTS_CODEC_RAW, 1, VTS_SAMPLE_U8, VTS_COLOUR_DATA, 0, 0, "d"};

const struct vts_geometry *vts_fixture_geometry(enum vts_fixture which)
{
    return &geometries[which];
}

const struct vts_layer *vts_fixture_layers(enum vts_fixture which)
{
    return which == VTS_FIXTURE_EMPTY ? &empty_layer : layer_table;
}

size_t vts_fixture_payload(enum vts_fixture which, uint32_t layer, uint32_t level, uint32_t tx,
                           uint32_t ty, unsigned char *buf)
{
    if (which == VTS_FIXTURE_EMPTY || (level == 0 && (tx * 3 + ty) % 5 == 2))
        return 0;
    bool shared = (tx + ty) % 4 == 1; /* one payload per layer, shared by many tiles */
    size_t len = shared ? 23 : 9 + (tx * 7 + ty * 13 + level * 5 + layer * 11) % 40;
    for (size_t i = 0; i < len; i++)
        buf[i] = shared ? (unsigned char)(layer * 3 + i)
                        : (unsigned char)(i ^ tx ^ (ty << 3) ^ (level << 5) ^ (layer * 0x47));
    return len;
}

int vts_fixture_write(const char *path, enum vts_fixture which, struct vts_error *err)
{
    const struct vts_geometry *g = &geometries[which];
    struct vts_writer *w = vts_writer_create(path, g, vts_fixture_layers(which), err);
    if (!w)
        return err ? err->status : VTS_ERR_IO;
    int rc = 0;
    unsigned char buf[VTS_FIXTURE_MAX_PAYLOAD];
    for (uint32_t layer = 0; layer < g->layer_count && rc == 0; layer++)
        for (uint32_t level = 0; level < g->level_count && rc == 0; level++) {
            struct vts_level L;
            vts_geometry_level(g, level, &L);
            for (uint32_t ty = 0; ty < L.tiles_y && rc == 0; ty++)
                for (uint32_t tx = 0; tx < L.tiles_x && rc == 0; tx++) {
                    size_t len = vts_fixture_payload(which, layer, level, tx, ty, buf);
                    rc = vts_writer_put(w, layer, level, tx, ty, buf, len, err);
                }
        }
    if (rc == 0)
        rc = vts_writer_set_meta(w, "generator", "vts_fixture", err);
    if (rc == 0)
        rc = vts_writer_set_meta(w, "purpose", "robustness tests", err);
    if (rc == 0)
        rc = vts_writer_set_meta(w, "empty.value", "", err);
    if (rc == 0)
        rc = vts_writer_finish(w, err);
    vts_writer_destroy(w);
    return rc;
}

unsigned char *vts_fixture_read_file(const char *path, size_t *size)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    unsigned char *data = NULL;
    size_t n = 0, cap = 0;
    for (;;) {
        if (n == cap) {
            cap = cap ? cap * 2 : 4096;
            unsigned char *p = realloc(data, cap);
            if (!p) {
                free(data);
                fclose(f);
                return NULL;
            }
            data = p;
        }
        size_t got = fread(data + n, 1, cap - n, f);
        n += got;
        if (got == 0)
            break;
    }
    bool failed = ferror(f) != 0;
    fclose(f);
    if (failed) {
        free(data);
        return NULL;
    }
    *size = n;
    return data;
}

int vts_fixture_write_file(const char *path, const void *data, size_t size)
{
    FILE *f = fopen(path, "wb");
    if (!f)
        return -1;
    bool ok = fwrite(data, 1, size, f) == size;
    return fclose(f) == 0 && ok ? 0 : -1;
}

unsigned char *vts_fixture_bytes(const char *dir, enum vts_fixture which, size_t *size)
{
    char path[512];
    snprintf(path, sizeof path, "%s/fixture-%d.vts", dir, (int)which);
    struct vts_error err = {0};
    if (vts_fixture_write(path, which, &err) != 0) {
        fprintf(stderr, "cannot write the fixture store: %s\n", err.message);
        return NULL;
    }
    return vts_fixture_read_file(path, size);
}

bool vts_fixture_mkdtemp(char *out, size_t cap, const char *prefix)
{
    const char *base = getenv("TMPDIR");
    int n = snprintf(out, cap, "%s/%s.XXXXXX", base && *base ? base : "/tmp", prefix);
    return n > 0 && (size_t)n < cap && mkdtemp(out) != NULL;
}

void vts_fixture_rmdir_all(const char *dir)
{
    char cmd[600];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    if (system(cmd) != 0)
        fprintf(stderr, "could not remove %s\n", dir);
}

/* [off, off + len) inside [0, size)? */
static bool inside(uint64_t off, uint64_t len, size_t size)
{
    return off <= size && len <= size - off;
}

static unsigned walk_store(const struct vts_store *s)
{
    unsigned failures = 0;
    const struct vts_geometry *g = vts_store_geometry(s);
    uint32_t max = vts_store_max_payload(s);
    unsigned char *buf = malloc(max ? max : 1); /* exactly max: ASan sees any overrun */
    if (!buf)
        return 1;
    for (uint32_t layer = 0; layer < g->layer_count; layer++) {
        const struct vts_layer *L = vts_store_layer(s, layer);
        failures += L == NULL || memchr(L->name, '\0', sizeof L->name) == NULL;
        for (uint32_t level = 0; level < g->level_count; level++) {
            struct vts_level lv;
            vts_store_level(s, level, &lv);
            for (uint32_t ty = 0; ty < lv.tiles_y; ty++)
                for (uint32_t tx = 0; tx < lv.tiles_x; tx++) {
                    struct vts_tile_entry e;
                    size_t len = 1;
                    struct vts_error err;
                    if (vts_store_tile(s, layer, level, tx, ty, &e, &err) != 0 || e.length > max ||
                        !inside(e.offset, e.length, (size_t)vts_store_file_size(s))) {
                        failures++;
                        continue;
                    }
                    unsigned flags = (tx + ty) % 2 ? VTS_READ_NO_CRC : 0;
                    int rc = vts_store_read(s, layer, level, tx, ty, buf, max, &len, flags, &err);
                    if (rc == VTS_ERR_CHECKSUM && flags == 0)
                        failures += strstr(err.message, vts_store_name(s)) == NULL;
                    else if (rc != 0 || len != e.length)
                        failures++;
                }
        }
    }
    for (uint64_t i = 0; i < vts_store_tile_count(s); i++)
        failures += vts_store_entry(s, i) == NULL;
    failures += vts_store_entry(s, vts_store_tile_count(s)) != NULL;
    for (uint32_t i = 0; i < vts_store_meta_count(s); i++) {
        const char *k = vts_store_meta_key(s, i), *v = vts_store_meta_value(s, i);
        failures += !k || !v || *k == '\0' || strchr(k, '=') || vts_store_meta_find(s, k) == NULL;
        failures += v && strlen(v) > (size_t)vts_store_file_size(s);
    }
    failures += vts_store_meta_key(s, vts_store_meta_count(s)) != NULL;
    free(buf);
    return failures;
}

int vts_fixture_exercise(const unsigned char *data, size_t size, const char *name,
                         struct vts_error *err, unsigned *read_failures)
{
    *read_failures = 0;
    vt_error_clear(err);
    struct vts_store *s = vts_open_memory(data, size, name, err);
    if (!s)
        return err->status;
    *read_failures = walk_store(s);
    vts_close(s);
    return 0;
}
