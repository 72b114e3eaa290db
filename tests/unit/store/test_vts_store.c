/* Store writer + reader: round trips of every header field and tile, dedup, empty tiles, data
 * order, metadata, threads, and the atomic-output promise. */
#include <dirent.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "vt_test.h"
#include "vts.h"
#include "vts_writer.h"

static char tmpdir[256];

static void path_in_tmp(char *out, size_t cap, const char *name)
{
    snprintf(out, cap, "%s/%s", tmpdir, name);
}

static const struct vts_geometry geo3x2 = {1000, 600, 120, 4, 128, 4, 2, VTS_STORE_WRAP_X};

static void make_layers(struct vts_layer layers[2])
{
    memset(layers, 0, 2 * sizeof *layers);
    layers[0] = (struct vts_layer){VTS_CODEC_RAW,           4, VTS_SAMPLE_U8, VTS_COLOUR_SRGB,
                                   VTS_LAYER_PREMULTIPLIED, 0, "diffuse"};
    layers[1] =
        (struct vts_layer){VTS_CODEC_PNG, 3, VTS_SAMPLE_U16, VTS_COLOUR_NORMAL, 0, 6, "normal"};
}

/* Payload of a tile: a deterministic byte pattern whose length depends on the tile. Tiles with
 * (tx + ty) % 4 == 1 share one payload per layer; (tx * 3 + ty) % 5 == 2 are empty (level 0). */
static size_t payload_for(uint32_t layer, uint32_t level, uint32_t tx, uint32_t ty,
                          unsigned char *buf)
{
    if (level == 0 && (tx * 3 + ty) % 5 == 2)
        return 0;
    bool shared = (tx + ty) % 4 == 1;
    size_t len = shared ? 77 : 50 + (tx * 7 + ty * 13 + level * 5) % 200;
    for (size_t i = 0; i < len; i++)
        buf[i] = shared ? (unsigned char)(layer * 3 + i)
                        : (unsigned char)(i ^ tx ^ (ty << 3) ^ (level << 5) ^ layer);
    return len;
}

static int write_all(struct vts_writer *w, const struct vts_geometry *g)
{
    unsigned char buf[512];
    for (uint32_t layer = 0; layer < g->layer_count; layer++)
        for (uint32_t level = 0; level < g->level_count; level++) {
            struct vts_level L;
            vts_geometry_level(g, level, &L);
            for (uint32_t ty = 0; ty < L.tiles_y; ty++)
                for (uint32_t tx = 0; tx < L.tiles_x; tx++) {
                    size_t len = payload_for(layer, level, tx, ty, buf);
                    if (vts_writer_put(w, layer, level, tx, ty, buf, len, NULL) != 0)
                        return -1;
                }
        }
    return 0;
}

static void check_all_tiles(const struct vts_store *s, const struct vts_geometry *g)
{
    unsigned char want[512], got[512];
    for (uint32_t layer = 0; layer < g->layer_count; layer++)
        for (uint32_t level = 0; level < g->level_count; level++) {
            struct vts_level L;
            vts_store_level(s, level, &L);
            for (uint32_t ty = 0; ty < L.tiles_y; ty++)
                for (uint32_t tx = 0; tx < L.tiles_x; tx++) {
                    size_t want_len = payload_for(layer, level, tx, ty, want), got_len = 99;
                    VT_CHECK_INT_EQ(
                        vts_store_read(s, layer, level, tx, ty, got, sizeof got, &got_len, 0, NULL),
                        0);
                    VT_CHECK_INT_EQ(got_len, want_len);
                    VT_CHECK(memcmp(got, want, want_len) == 0);
                }
        }
}

static void round_trip_keeps_every_header_field_and_tile(void)
{
    char path[300];
    path_in_tmp(path, sizeof path, "rt.vts");
    struct vts_layer layers[2];
    make_layers(layers);
    struct vts_error err = {0};
    struct vts_writer *w = vts_writer_create(path, &geo3x2, layers, &err);
    VT_CHECK(w != NULL);
    VT_CHECK_INT_EQ(write_all(w, &geo3x2), 0);
    VT_CHECK_INT_EQ(vts_writer_set_meta(w, "source", "aerial 2026.tif", &err), 0);
    VT_CHECK_INT_EQ(vts_writer_set_meta(w, "filter", "box", &err), 0);
    VT_CHECK_INT_EQ(vts_writer_set_meta(w, "filter", "lanczos3", &err), 0); /* replaces */
    VT_CHECK_INT_EQ(vts_writer_set_meta(w, "empty.value", "", &err), 0);
    VT_CHECK(access(path, F_OK) != 0); /* nothing under the final name before finish */
    VT_CHECK_INT_EQ(vts_writer_finish(w, &err), 0);
    struct vts_writer_stats st;
    vts_writer_stats(w, &st);
    vts_writer_destroy(w);

    struct vts_store *s = vts_open(path, &err);
    VT_CHECK(s != NULL);
    if (!s) {
        fprintf(stderr, "%s\n", err.message);
        return;
    }
    const struct vts_geometry *g = vts_store_geometry(s);
    VT_CHECK(memcmp(g, &geo3x2, sizeof *g) == 0);
    for (uint32_t i = 0; i < 2; i++)
        VT_CHECK(memcmp(vts_store_layer(s, i), &layers[i], sizeof layers[i]) == 0);
    VT_CHECK(vts_store_layer(s, 2) == NULL);
    unsigned major, minor;
    vts_store_version(s, &major, &minor);
    VT_CHECK_INT_EQ(major, VTS_FORMAT_MAJOR);
    VT_CHECK_INT_EQ(minor, VTS_FORMAT_MINOR);
    check_all_tiles(s, g);
    VT_CHECK_INT_EQ(vts_store_meta_count(s), 3);
    VT_CHECK(strcmp(vts_store_meta_find(s, "source"), "aerial 2026.tif") == 0);
    VT_CHECK(strcmp(vts_store_meta_find(s, "filter"), "lanczos3") == 0);
    VT_CHECK(strcmp(vts_store_meta_value(s, 2), "") == 0);
    VT_CHECK(vts_store_meta_find(s, "absent") == NULL);

    /* counts: level 0 has 9x5 tiles; empties and shared payloads as payload_for() says */
    uint64_t empty = 0, stored = 0;
    for (uint64_t i = 0; i < vts_store_tile_count(s); i++)
        vts_store_entry(s, i)->length ? stored++ : empty++;
    VT_CHECK_INT_EQ(stored + empty, 2 * (45 + 15 + 6 + 2));
    VT_CHECK_INT_EQ(empty, st.tiles_empty);
    VT_CHECK_INT_EQ(stored, st.tiles_stored);
    VT_CHECK(st.tiles_shared > 10);

    struct vts_error rerr;
    size_t len;
    unsigned char small[8];
    VT_CHECK_INT_EQ(vts_store_read(s, 0, 0, 9, 0, small, sizeof small, &len, 0, &rerr),
                    VTS_ERR_RANGE);
    VT_CHECK_INT_EQ(vts_store_read(s, 0, 4, 0, 0, small, sizeof small, &len, 0, &rerr),
                    VTS_ERR_RANGE);
    VT_CHECK_INT_EQ(vts_store_read(s, 0, 0, 0, 0, small, sizeof small, &len, 0, &rerr),
                    VTS_ERR_LIMIT);
    vts_close(s);
}

static void identical_payloads_share_one_offset(void)
{
    char path[300];
    path_in_tmp(path, sizeof path, "rt.vts");
    struct vts_store *s = vts_open(path, NULL);
    VT_CHECK(s != NULL);
    if (!s)
        return;
    struct vts_tile_entry a, b, c;
    /* (1,0) and (0,1) are both shared tiles of layer 0 level 0; layer 1 differs in content */
    VT_CHECK_INT_EQ(vts_store_tile(s, 0, 0, 1, 0, &a, NULL), 0);
    VT_CHECK_INT_EQ(vts_store_tile(s, 0, 0, 0, 1, &b, NULL), 0);
    VT_CHECK_INT_EQ(vts_store_tile(s, 1, 0, 1, 0, &c, NULL), 0);
    VT_CHECK(a.length == 77 && a.offset == b.offset && a.crc32c == b.crc32c);
    VT_CHECK(c.length == 77 && c.offset != a.offset);
    /* empty tile (0,2): (0*3+2)%5 == 2 */
    VT_CHECK_INT_EQ(vts_store_tile(s, 0, 0, 0, 2, &a, NULL), 0);
    VT_CHECK(a.length == 0 && a.offset == 0 && a.crc32c == 0);
    /* the file holds each distinct payload once: data bytes < sum of all lengths */
    uint64_t sum = 0;
    for (uint64_t i = 0; i < vts_store_tile_count(s); i++)
        sum += vts_store_entry(s, i)->length;
    /* everything after the index (metadata + data) is smaller than the payloads without sharing
     * by at least ten 77-byte copies */
    uint64_t index_end = 128 + 2 * 48 + vts_store_tile_count(s) * 16;
    VT_CHECK(vts_store_file_size(s) - index_end + 10 * 77 < sum);
    vts_close(s);
}

static void coarse_levels_come_first_on_disk(void)
{
    char path[300];
    path_in_tmp(path, sizeof path, "rt.vts");
    struct vts_store *s = vts_open(path, NULL);
    VT_CHECK(s != NULL);
    if (!s)
        return;
    /* every unshared payload of level l+1 lies before every unshared payload of level l */
    uint64_t min_off[4], max_off[4];
    for (int l = 0; l < 4; l++) {
        min_off[l] = UINT64_MAX;
        max_off[l] = 0;
    }
    for (uint32_t level = 0; level < 4; level++) {
        struct vts_level L;
        vts_store_level(s, level, &L);
        for (uint32_t ty = 0; ty < L.tiles_y; ty++)
            for (uint32_t tx = 0; tx < L.tiles_x; tx++) {
                struct vts_tile_entry e;
                vts_store_tile(s, 1, level, tx, ty, &e, NULL);
                if (e.length == 0 || (tx + ty) % 4 == 1)
                    continue;
                if (e.offset < min_off[level])
                    min_off[level] = e.offset;
                if (e.offset > max_off[level])
                    max_off[level] = e.offset;
            }
    }
    for (int l = 0; l < 3; l++)
        VT_CHECK(max_off[l + 1] < min_off[l]);
    /* layers of one tile are adjacent: layer 1 follows layer 0 of an unshared tile */
    struct vts_tile_entry e0, e1;
    vts_store_tile(s, 0, 0, 2, 0, &e0, NULL);
    vts_store_tile(s, 1, 0, 2, 0, &e1, NULL);
    VT_CHECK_INT_EQ(e1.offset, e0.offset + e0.length);
    vts_close(s);
}

struct thread_job {
    struct vts_writer *w;
    const struct vts_geometry *g;
    uint32_t part, parts;
    int failures;
};

/* Each thread puts every parts-th tile, walking the index backwards. */
static void *put_part(void *arg)
{
    struct thread_job *j = arg;
    unsigned char buf[512];
    uint64_t n = 0;
    for (uint32_t layer = j->g->layer_count; layer-- > 0;)
        for (uint32_t level = j->g->level_count; level-- > 0;) {
            struct vts_level L;
            vts_geometry_level(j->g, level, &L);
            for (uint32_t t = L.tiles_x * L.tiles_y; t-- > 0; n++) {
                if (n % j->parts != j->part)
                    continue;
                uint32_t tx = t % L.tiles_x, ty = t / L.tiles_x;
                size_t len = payload_for(layer, level, tx, ty, buf);
                j->failures += vts_writer_put(j->w, layer, level, tx, ty, buf, len, NULL) != 0;
            }
        }
    return NULL;
}

static void threads_and_order_do_not_change_the_bytes(void)
{
    char single[300], multi[300];
    path_in_tmp(single, sizeof single, "rt.vts");
    path_in_tmp(multi, sizeof multi, "mt.vts");
    struct vts_layer layers[2];
    make_layers(layers);
    struct vts_writer *w = vts_writer_create(multi, &geo3x2, layers, NULL);
    VT_CHECK(w != NULL);
    if (!w)
        return;
    pthread_t th[4];
    struct thread_job jobs[4];
    for (uint32_t i = 0; i < 4; i++) {
        jobs[i] = (struct thread_job){w, &geo3x2, i, 4, 0};
        pthread_create(&th[i], NULL, put_part, &jobs[i]);
    }
    for (int i = 0; i < 4; i++) {
        pthread_join(th[i], NULL);
        VT_CHECK_INT_EQ(jobs[i].failures, 0);
    }
    vts_writer_set_meta(w, "source", "aerial 2026.tif", NULL);
    vts_writer_set_meta(w, "filter", "lanczos3", NULL);
    vts_writer_set_meta(w, "empty.value", "", NULL);
    VT_CHECK_INT_EQ(vts_writer_finish(w, NULL), 0);
    vts_writer_destroy(w);
    /* same tiles, other order, 4 threads: byte-identical file */
    FILE *a = fopen(single, "rb"), *b = fopen(multi, "rb");
    VT_CHECK(a && b);
    int ca, cb, same = 1;
    long n = 0;
    do {
        ca = a ? fgetc(a) : EOF;
        cb = b ? fgetc(b) : EOF;
        same &= ca == cb;
        n++;
    } while (ca != EOF && cb != EOF);
    VT_CHECK(same);
    VT_CHECK(n > 1000);
    if (a)
        fclose(a);
    if (b)
        fclose(b);
}

static void writer_rejects_bad_puts(void)
{
    char path[300];
    path_in_tmp(path, sizeof path, "bad.vts");
    struct vts_layer layers[2];
    make_layers(layers);
    struct vts_error err;
    struct vts_writer *w = vts_writer_create(path, &geo3x2, layers, &err);
    VT_CHECK(w != NULL);
    if (!w)
        return;
    unsigned char b[4] = {1, 2, 3, 4};
    VT_CHECK_INT_EQ(vts_writer_put(w, 0, 0, 0, 0, b, 4, &err), 0);
    VT_CHECK_INT_EQ(vts_writer_put(w, 0, 0, 0, 0, b, 4, &err), VTS_ERR_ARG);
    VT_CHECK_STR_CONTAINS(err.message, "put twice");
    VT_CHECK_INT_EQ(vts_writer_put(w, 2, 0, 0, 0, b, 4, &err), VTS_ERR_RANGE);
    VT_CHECK_INT_EQ(vts_writer_put(w, 0, 4, 0, 0, b, 4, &err), VTS_ERR_RANGE);
    VT_CHECK_INT_EQ(vts_writer_put(w, 0, 0, 9, 0, b, 4, &err), VTS_ERR_RANGE);
    VT_CHECK_INT_EQ(vts_writer_put(w, 0, 0, 0, 5, b, 4, &err), VTS_ERR_RANGE);
    VT_CHECK_INT_EQ(vts_writer_set_meta(w, "bad key", "x", &err), VTS_ERR_ARG);
    VT_CHECK_INT_EQ(vts_writer_set_meta(w, "", "x", &err), VTS_ERR_ARG);
    VT_CHECK_INT_EQ(vts_writer_set_meta(w, "a=b", "x", &err), VTS_ERR_ARG);
    vts_writer_destroy(w); /* no finish: nothing left behind */
    VT_CHECK(access(path, F_OK) != 0);

    struct vts_geometry g = geo3x2;
    g.tile_payload_px = 127;
    VT_CHECK(vts_writer_create(path, &g, layers, &err) == NULL);
    VT_CHECK_STR_CONTAINS(err.message, "bad.vts");
    layers[1].channels = 5;
    VT_CHECK(vts_writer_create(path, &geo3x2, layers, &err) == NULL);
    VT_CHECK(vts_writer_create("/nonexistent-dir/x.vts", &geo3x2, layers, &err) == NULL);
}

/* The store size limit counts unique payload bytes: shared copies are free, the put that would
 * pass the limit fails with LIMIT, later puts and finish fail too, and nothing is written. */
static void size_limit_stops_the_store(void)
{
    char path[300];
    path_in_tmp(path, sizeof path, "limit.vts");
    struct vts_layer layers[2];
    make_layers(layers);
    struct vts_error err;
    struct vts_writer *w = vts_writer_create(path, &geo3x2, layers, &err);
    VT_CHECK(w != NULL);
    if (!w)
        return;
    vts_writer_set_max_bytes(w, 10);
    unsigned char a[6] = {1, 2, 3, 4, 5, 6}, b[6] = {6, 5, 4, 3, 2, 1};
    VT_CHECK_INT_EQ(vts_writer_put(w, 0, 0, 0, 0, a, 6, &err), 0);
    VT_CHECK_INT_EQ(vts_writer_put(w, 0, 0, 1, 0, a, 6, &err), 0); /* shared: no new bytes */
    VT_CHECK_INT_EQ(vts_writer_put(w, 0, 0, 2, 0, b, 6, &err), VTS_ERR_LIMIT);
    VT_CHECK_STR_CONTAINS(err.message, "limit.vts' would hold more than 10 bytes of tiles");
    VT_CHECK_INT_EQ(vts_writer_put(w, 0, 0, 0, 1, a, 6, &err), VTS_ERR_LIMIT);
    VT_CHECK_INT_EQ(vts_writer_finish(w, &err), VTS_ERR_LIMIT);
    vts_writer_destroy(w);
    VT_CHECK(access(path, F_OK) != 0);
}

static void finish_replaces_an_old_file_and_leaves_no_temporaries(void)
{
    char path[300];
    path_in_tmp(path, sizeof path, "replace.vts");
    FILE *f = fopen(path, "w");
    fputs("old content", f);
    fclose(f);
    struct vts_geometry g = {5, 3, 4, 0, 4, 2, 1, 0};
    struct vts_layer layer = {VTS_CODEC_RAW, 1, VTS_SAMPLE_U8, VTS_COLOUR_DATA, 0, 0, "d"};
    struct vts_writer *w = vts_writer_create(path, &g, &layer, NULL);
    VT_CHECK(w != NULL);
    if (!w)
        return;
    unsigned char px[16] = {9};
    VT_CHECK_INT_EQ(vts_writer_put(w, 0, 1, 0, 0, px, 16, NULL), 0);
    /* the old file is intact while the writer works */
    struct stat st;
    VT_CHECK(stat(path, &st) == 0 && st.st_size == 11);
    VT_CHECK_INT_EQ(vts_writer_finish(w, NULL), 0);
    vts_writer_destroy(w);
    struct vts_store *s = vts_open(path, NULL);
    VT_CHECK(s != NULL);
    if (s) {
        struct vts_tile_entry e;
        VT_CHECK_INT_EQ(vts_store_tile(s, 0, 0, 1, 0, &e, NULL), 0); /* never put: empty */
        VT_CHECK_INT_EQ(e.length, 0);
        vts_close(s);
    }
    int count = 0;
    DIR *d = opendir(tmpdir);
    for (struct dirent *de; d && (de = readdir(d));)
        count += strncmp(de->d_name, ".replace.vts.", 13) == 0;
    if (d)
        closedir(d);
    VT_CHECK_INT_EQ(count, 0); /* no .replace.vts.tmp-* or .spool-* left */
}

static void store_without_payloads_opens(void)
{
    char path[300];
    path_in_tmp(path, sizeof path, "allempty.vts");
    struct vts_geometry g = {1, 1, 1, 0, 1, 1, 1, 0};
    struct vts_layer layer = {VTS_CODEC_RAW, 1, VTS_SAMPLE_U8, VTS_COLOUR_DATA, 0, 0, "d"};
    struct vts_writer *w = vts_writer_create(path, &g, &layer, NULL);
    VT_CHECK(w && vts_writer_finish(w, NULL) == 0);
    vts_writer_destroy(w);
    struct vts_error err = {0};
    struct vts_store *s = vts_open(path, &err);
    VT_CHECK(s != NULL);
    if (s) {
        VT_CHECK_INT_EQ(vts_store_tile_count(s), 1);
        VT_CHECK_INT_EQ(vts_store_max_payload(s), 0);
        vts_close(s);
    } else {
        fprintf(stderr, "%s\n", err.message);
    }
}

/* The API's one rule for out-of-range arguments (include/vts/vts.h): NULL from pointer accessors,
 * VTS_ERR_RANGE and a zeroed output from int ones; never a clamp. */
static void out_of_range_arguments_follow_one_rule(void)
{
    char path[300];
    path_in_tmp(path, sizeof path, "range.vts");
    struct vts_geometry g = {300, 200, 62, 1, 64, 0, 1, 0};
    g.level_count = vts_full_level_count(g.width, g.height, g.tile_content_px);
    struct vts_layer layer = {VTS_CODEC_RAW, 1, VTS_SAMPLE_U8, VTS_COLOUR_DATA, 0, 0, "d"};
    struct vts_writer *w = vts_writer_create(path, &g, &layer, NULL);
    VT_CHECK(w && vts_writer_finish(w, NULL) == 0);
    vts_writer_destroy(w);
    struct vts_store *s = vts_open(path, NULL);
    VT_CHECK(s != NULL);
    if (!s)
        return;
    struct vts_level lv;
    VT_CHECK_INT_EQ(vts_store_level(s, g.level_count - 1, &lv), 0);
    VT_CHECK_INT_EQ(lv.tiles_x, 1);
    memset(&lv, 0xff, sizeof lv);
    VT_CHECK_INT_EQ(vts_store_level(s, g.level_count, &lv), VTS_ERR_RANGE);
    VT_CHECK_INT_EQ(lv.width, 0);
    VT_CHECK_INT_EQ(lv.tiles_x, 0);
    memset(&lv, 0xff, sizeof lv);
    VT_CHECK_INT_EQ(vts_geometry_level(vts_store_geometry(s), 99, &lv), VTS_ERR_RANGE);
    VT_CHECK_INT_EQ(lv.height, 0);
    VT_CHECK(vts_store_layer(s, 0) != NULL);
    VT_CHECK(vts_store_layer(s, 1) == NULL);
    VT_CHECK(vts_store_entry(s, vts_store_tile_count(s) - 1) != NULL);
    VT_CHECK(vts_store_entry(s, vts_store_tile_count(s)) == NULL);
    VT_CHECK(vts_store_meta_key(s, vts_store_meta_count(s)) == NULL);
    VT_CHECK(vts_store_meta_value(s, vts_store_meta_count(s)) == NULL);
    struct vts_tile_entry e;
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(vts_store_tile(s, 0, 0, 5, 0, &e, &err), VTS_ERR_RANGE);
    VT_CHECK_STR_CONTAINS(err.message, "has no tile 5,0");
    vts_close(s);
}

static void version_matches_the_header(void)
{
    VT_CHECK_INT_EQ(vts_version(), VTS_VERSION_NUMBER);
    char expect[32];
    snprintf(expect, sizeof expect, "%d.%d.%d", VTS_VERSION_MAJOR, VTS_VERSION_MINOR,
             VTS_VERSION_PATCH);
    VT_CHECK(strcmp(vts_version_string(), expect) == 0);
    VT_CHECK(strcmp(vts_status_name(VTS_ERR_RANGE), "range") == 0);
    VT_CHECK(strcmp(vts_status_name(42), "unknown") == 0);
}

/* ---- a store larger than the writer's buffers ---- */

/* Payload of tile (level, tx, ty) of a large store: pseudo-random bytes (incompressible, as
 * codec output), 2000..17999 bytes; every 7th tile of level 0 shares one 30000-byte payload and
 * every 11th is empty. */
static size_t big_payload(uint32_t level, uint32_t tx, uint32_t ty, unsigned char *buf)
{
    uint32_t n = (ty * 131 + tx) * 8 + level;
    if (level == 0 && n % 11 == 3)
        return 0;
    bool shared = level == 0 && n % 7 == 2;
    uint32_t x = shared ? 0x9e3779b9u : n * 2654435761u + 1;
    size_t len = shared ? 30000 : 2000 + (x >> 8) % 16000;
    for (size_t i = 0; i < len; i++) {
        x ^= x << 13, x ^= x >> 17, x ^= x << 5;
        buf[i] = (unsigned char)x;
    }
    return len;
}

/* Writes a 4000² store of about 14 MB of payloads (past the spool buffer, and past the size from
 * which the data section is written with direct I/O) at path, putting level 0 in reverse order
 * when `reverse`. */
static void write_big(const char *path, bool reverse)
{
    static const struct vts_geometry g = {4000, 4000, 120, 4, 128, 6, 1, 0};
    struct vts_layer layer = {VTS_CODEC_RAW, 3, VTS_SAMPLE_U8, VTS_COLOUR_SRGB, 0, 0, "diffuse"};
    struct vts_error err = {0};
    struct vts_writer *w = vts_writer_create(path, &g, &layer, &err);
    unsigned char *buf = malloc(30000);
    VT_CHECK(w && buf);
    int failed = 0;
    for (uint32_t level = 0; w && buf && level < g.level_count; level++) {
        struct vts_level L;
        vts_geometry_level(&g, level, &L);
        for (uint32_t i = 0; i < L.tiles_x * L.tiles_y; i++) {
            uint32_t k = reverse && level == 0 ? L.tiles_x * L.tiles_y - 1 - i : i;
            size_t len = big_payload(level, k % L.tiles_x, k / L.tiles_x, buf);
            failed +=
                vts_writer_put(w, 0, level, k % L.tiles_x, k / L.tiles_x, buf, len, &err) != 0;
        }
    }
    VT_CHECK_INT_EQ(failed, 0);
    if (w) {
        vts_writer_set_meta(w, "source", "big", NULL);
        VT_CHECK_INT_EQ(vts_writer_finish(w, &err), 0);
    }
    vts_writer_destroy(w);
    free(buf);
}

/* Every payload of the large store reads back (CRCs checked), the head (index, metadata) is
 * intact, the file ends with the data, and two put orders give the same bytes; in the build
 * directory (a disk file system: direct I/O) and in /dev/shm when there is one (tmpfs). */
static void large_store_round_trips_through_the_buffers(const char *dir)
{
    char a[300], b[300];
    snprintf(a, sizeof a, "%s/big_a.vts", dir);
    snprintf(b, sizeof b, "%s/big_b.vts", dir);
    write_big(a, false);
    write_big(b, true);
    struct vts_error err = {0};
    struct vts_store *s = vts_open(a, &err);
    VT_CHECK(s != NULL);
    if (!s)
        return;
    unsigned char *want = malloc(30000), *got = malloc(30000);
    int bad = 0;
    uint64_t bytes = 0;
    const struct vts_geometry *g = vts_store_geometry(s);
    for (uint32_t level = 0; level < g->level_count; level++) {
        struct vts_level L;
        vts_store_level(s, level, &L);
        for (uint32_t ty = 0; ty < L.tiles_y; ty++)
            for (uint32_t tx = 0; tx < L.tiles_x; tx++) {
                size_t wl = big_payload(level, tx, ty, want), gl = 0;
                int rc = vts_store_read(s, 0, level, tx, ty, got, 30000, &gl, 0, &err);
                bad += rc != 0 || gl != wl || memcmp(got, want, wl) != 0;
                bytes += wl;
            }
    }
    VT_CHECK_INT_EQ(bad, 0);
    VT_CHECK(bytes > (12u << 20));
    VT_CHECK_STR_EQ(vts_store_meta_find(s, "source"), "big");
    struct stat st;
    VT_CHECK(stat(a, &st) == 0 && (uint64_t)st.st_size == vts_store_file_size(s));
    vts_close(s);
    /* the same bytes whatever the put order; and a changed byte is seen by that comparison */
    FILE *fa = fopen(a, "rb"), *fb = fopen(b, "rb");
    size_t diff = 0, n = 0;
    int ca = 0, cb = 0;
    while (fa && fb && (ca = fgetc(fa)) != EOF && (cb = fgetc(fb)) != EOF) {
        diff += ca != cb;
        n++;
    }
    VT_CHECK(fa && fb && ca == EOF && fgetc(fb) == EOF);
    VT_CHECK_INT_EQ(diff, 0);
    VT_CHECK_INT_EQ(n, (uint64_t)st.st_size);
    if (fa)
        fclose(fa);
    if (fb)
        fclose(fb);
    free(want);
    free(got);
    unlink(a);
    unlink(b);
}

static void large_stores_round_trip_on_disk_and_in_memory(void)
{
    large_store_round_trips_through_the_buffers(".");
    struct stat st;
    if (stat("/dev/shm", &st) == 0 && S_ISDIR(st.st_mode) && access("/dev/shm", W_OK) == 0)
        large_store_round_trips_through_the_buffers("/dev/shm");
}

int main(void)
{
    snprintf(tmpdir, sizeof tmpdir, "/tmp/test_vts_store.XXXXXX");
    if (!mkdtemp(tmpdir))
        return 1;
    VT_RUN(round_trip_keeps_every_header_field_and_tile);
    VT_RUN(identical_payloads_share_one_offset);
    VT_RUN(coarse_levels_come_first_on_disk);
    VT_RUN(threads_and_order_do_not_change_the_bytes);
    VT_RUN(writer_rejects_bad_puts);
    VT_RUN(size_limit_stops_the_store);
    VT_RUN(finish_replaces_an_old_file_and_leaves_no_temporaries);
    VT_RUN(store_without_payloads_opens);
    VT_RUN(out_of_range_arguments_follow_one_rule);
    VT_RUN(version_matches_the_header);
    VT_RUN(large_stores_round_trip_on_disk_and_in_memory);
    char cmd[300];
    snprintf(cmd, sizeof cmd, "rm -rf %s", tmpdir);
    if (system(cmd) != 0)
        fprintf(stderr, "could not remove %s\n", tmpdir);
    return vt_test_main_result();
}
