/* vt-store-check: builds inputs for and checks the outputs of the vt-convert and vt-merge CLI
 * cases (tests/cli/vt-convert/, tests/cli/vt-merge/). Exit 0 when every check holds, 1 when one
 * fails, 2 on bad usage. Checks print one "ok ..." line (part of the cases' golden stdout).
 *
 *   vt-store-check structure A.vts B.vts
 *       same geometry and layer count; each tile empty in A iff empty in B; two tiles share a
 *       payload (offset) in A iff they share one in B.
 *   vt-store-check same-tiles A.vts LA B.vts LB [--psnr MIN_DB]
 *       decodes every tile of layer LA of A and LB of B: the same tiles are stored and every
 *       sample is equal, or, with --psnr, the PSNR over all stored tiles (samples scaled to
 *       [0,1]; the sample types may then differ) is at least MIN_DB.
 *   vt-store-check same-bytes A.vts LA B.vts LB
 *       every tile of layer LA of A has the same payload bytes as in layer LB of B.
 *   vt-store-check split IN.vts A.vts B.vts [--no-shard-key]
 *       writes two shards of IN: tiles with tx < tiles_x / 2 (per level) in A, the others in B;
 *       metadata as IN's plus shard=1/2 and shard=2/2 (nothing added with --no-shard-key).
 *   vt-store-check rename IN.vts OUT.vts LAYER NAME
 *       copies IN with layer LAYER named NAME.
 *   vt-store-check smooth-png OUT.png WIDTH HEIGHT
 *       writes a smooth RGB 8-bit image (gradients and a low-frequency wave). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vt_png_file.h"
#include "vt_tile_reader.h"
#include "vts.h"
#include "vts_writer.h"

static struct vts_store *open_store(const char *path)
{
    struct vts_error err = {0};
    struct vts_store *s = vts_open(path, &err);
    if (!s)
        fprintf(stderr, "vt-store-check: %s\n", err.message);
    return s;
}

/* Calls fn for every (layer, level, tx, ty) of s's geometry, with the index of the entry. */
typedef int (*tile_fn)(void *ctx, uint64_t index, uint32_t layer, uint32_t level, uint32_t tx,
                       uint32_t ty);
static int each_tile(const struct vts_store *s, void *ctx, tile_fn fn)
{
    const struct vts_geometry *g = vts_store_geometry(s);
    uint64_t index = 0;
    for (uint32_t layer = 0; layer < g->layer_count; layer++)
        for (uint32_t level = 0; level < g->level_count; level++) {
            struct vts_level L;
            vts_store_level(s, level, &L);
            for (uint32_t ty = 0; ty < L.tiles_y; ty++)
                for (uint32_t tx = 0; tx < L.tiles_x; tx++, index++)
                    if (fn(ctx, index, layer, level, tx, ty) != 0)
                        return 1;
        }
    return 0;
}

/* ---- structure ---- */

/* first[i]: the lowest index whose entry has the same offset as entry i (i itself if none). */
static uint64_t *first_sharers(const struct vts_store *s)
{
    uint64_t n = vts_store_tile_count(s);
    uint64_t *first = malloc((size_t)n * sizeof *first);
    for (uint64_t i = 0; first && i < n; i++) {
        const struct vts_tile_entry *e = vts_store_entry(s, i);
        first[i] = i;
        for (uint64_t j = 0; e->length && j < i; j++)
            if (vts_store_entry(s, j)->offset == e->offset) {
                first[i] = j;
                break;
            }
    }
    return first;
}

static int check_structure(const struct vts_store *a, const struct vts_store *b)
{
    const struct vts_geometry *ga = vts_store_geometry(a), *gb = vts_store_geometry(b);
    if (memcmp(ga, gb, sizeof *ga) != 0) {
        printf("FAIL geometry differs\n");
        return 1;
    }
    uint64_t n = vts_store_tile_count(a), stored = 0, shared = 0;
    uint64_t *fa = first_sharers(a), *fb = first_sharers(b);
    int rc = !fa || !fb;
    for (uint64_t i = 0; rc == 0 && i < n; i++) {
        bool ea = vts_store_entry(a, i)->length == 0, eb = vts_store_entry(b, i)->length == 0;
        if (ea != eb || fa[i] != fb[i]) {
            printf("FAIL index entry %llu: %s\n", (unsigned long long)i,
                   ea != eb ? "empty in one store only" : "shares a payload in one store only");
            rc = 1;
        }
        stored += !ea;
        shared += !ea && fa[i] != i;
    }
    if (rc == 0)
        printf("ok structure: %llu tiles, %llu stored, %llu shared\n", (unsigned long long)n,
               (unsigned long long)stored, (unsigned long long)shared);
    free(fa);
    free(fb);
    return rc;
}

/* ---- same-tiles, same-bytes ---- */

struct compare {
    struct vts_store *a, *b;
    uint32_t la, lb;
    struct vt_tile_reader ra, rb;
    bool bytes_only;
    double sum_sq;
    uint64_t samples, tiles, diffs;
};

static double sample_at(const struct vt_image *img, size_t i)
{
    const unsigned char *p = img->pixels;
    uint16_t h;
    float f;
    switch (img->sample) {
    case VTS_SAMPLE_U8:
        return p[i] / 255.0;
    case VTS_SAMPLE_U16:
        memcpy(&h, p + 2 * i, 2);
        return h / 65535.0;
    case VTS_SAMPLE_F32:
        memcpy(&f, p + 4 * i, 4);
        return f;
    default:
        memcpy(&h, p + 2 * i, 2);
        return h; /* f16: compared as bits */
    }
}

static int compare_tile(void *ctx, uint64_t index, uint32_t layer, uint32_t level, uint32_t tx,
                        uint32_t ty)
{
    struct compare *c = ctx;
    struct vts_error err = {0};
    bool sa, sb;
    (void)index;
    if (layer != c->la)
        return 0;
    if (c->bytes_only) {
        size_t la = 0, lb = 0;
        int rc = vts_store_read(c->a, c->la, level, tx, ty, c->ra.payload,
                                vts_store_max_payload(c->a), &la, 0, &err);
        if (rc == 0)
            rc = vts_store_read(c->b, c->lb, level, tx, ty, c->rb.payload,
                                vts_store_max_payload(c->b), &lb, 0, &err);
        if (rc != 0 || la != lb || memcmp(c->ra.payload, c->rb.payload, la) != 0) {
            printf("FAIL level %u tile %u,%u: payloads differ %s\n", level, tx, ty, err.message);
            return 1;
        }
        c->tiles += la > 0;
        return 0;
    }
    if (vt_tile_reader_read(&c->ra, level, tx, ty, &sa, &err) != 0 ||
        vt_tile_reader_read(&c->rb, level, tx, ty, &sb, &err) != 0) {
        printf("FAIL %s\n", err.message);
        return 1;
    }
    if (sa != sb) {
        printf("FAIL level %u tile %u,%u: stored in one store only\n", level, tx, ty);
        return 1;
    }
    size_t n = (size_t)c->ra.img.width * c->ra.img.height * c->ra.img.channels;
    for (size_t i = 0; sa && i < n; i++) {
        double d = sample_at(&c->ra.img, i) - sample_at(&c->rb.img, i);
        c->sum_sq += d * d;
        c->diffs += d != 0;
    }
    c->samples += sa ? n : 0;
    c->tiles += sa;
    return 0;
}

static int check_tiles(const char *pa, uint32_t la, const char *pb, uint32_t lb, bool bytes_only,
                       double min_psnr)
{
    struct compare c = {.la = la, .lb = lb, .bytes_only = bytes_only};
    struct vts_error err = {0};
    int rc = 1;
    c.a = open_store(pa);
    c.b = open_store(pb);
    if (!c.a || !c.b)
        goto out;
    if (la >= vts_store_geometry(c.a)->layer_count || lb >= vts_store_geometry(c.b)->layer_count ||
        vt_tile_reader_init(&c.ra, c.a, la, &err) != 0 ||
        vt_tile_reader_init(&c.rb, c.b, lb, &err) != 0) {
        printf("FAIL cannot read the layers %s\n", err.message);
        goto out;
    }
    if (!bytes_only &&
        ((min_psnr == 0 && c.ra.img.sample != c.rb.img.sample) ||
         c.ra.img.channels != c.rb.img.channels || c.ra.img.width != c.rb.img.width)) {
        printf("FAIL the layers have different shapes\n");
        goto out;
    }
    if (each_tile(c.a, &c, compare_tile) != 0)
        goto out;
    double psnr = c.sum_sq > 0 ? 10.0 * log10((double)c.samples / c.sum_sq) : INFINITY;
    if (bytes_only)
        printf("ok same bytes: %llu stored tiles\n", (unsigned long long)c.tiles);
    else if (min_psnr > 0 && psnr >= min_psnr)
        printf("ok psnr >= %g dB over %llu stored tiles\n", min_psnr, (unsigned long long)c.tiles);
    else if (min_psnr == 0 && c.diffs == 0)
        printf("ok same texels: %llu stored tiles\n", (unsigned long long)c.tiles);
    else
        printf("FAIL psnr %.2f dB, %llu samples differ\n", psnr, (unsigned long long)c.diffs);
    rc = bytes_only ? 0 : min_psnr > 0 ? psnr < min_psnr : c.diffs != 0;
out:
    vt_tile_reader_release(&c.ra);
    vt_tile_reader_release(&c.rb);
    vts_close(c.a);
    vts_close(c.b);
    return rc;
}

/* ---- split, rename ---- */

struct copy {
    struct vts_store *in;
    struct vts_writer *out[2];
    unsigned char *buf;
    uint32_t rename_layer;
};

static int copy_tile(void *ctx, uint64_t index, uint32_t layer, uint32_t level, uint32_t tx,
                     uint32_t ty)
{
    struct copy *c = ctx;
    struct vts_error err = {0};
    struct vts_level L;
    size_t len = 0;
    (void)index;
    vts_store_level(c->in, level, &L);
    struct vts_writer *w = c->out[1] && tx >= L.tiles_x / 2 ? c->out[1] : c->out[0];
    int rc = vts_store_read(c->in, layer, level, tx, ty, c->buf, vts_store_max_payload(c->in) + 1,
                            &len, 0, &err);
    if (rc == 0 && len > 0)
        rc = vts_writer_put(w, layer, level, tx, ty, c->buf, len, &err);
    if (rc != 0)
        fprintf(stderr, "vt-store-check: %s\n", err.message);
    return rc != 0;
}

static int copy_store(const char *in, const char *out_a, const char *out_b, bool shard_key,
                      int rename_layer, const char *name)
{
    struct copy c = {0};
    struct vts_layer layers[VTS_MAX_LAYERS];
    struct vts_error err = {0};
    int rc = 1;
    if (!(c.in = open_store(in)))
        return 1;
    const struct vts_geometry *g = vts_store_geometry(c.in);
    for (uint32_t i = 0; i < g->layer_count; i++)
        layers[i] = *vts_store_layer(c.in, i);
    if (rename_layer >= 0 && (uint32_t)rename_layer < g->layer_count)
        snprintf(layers[rename_layer].name, sizeof layers[0].name, "%s", name);
    c.buf = malloc(vts_store_max_payload(c.in) + 1);
    for (int k = 0; k < (out_b ? 2 : 1); k++)
        if (!(c.out[k] = vts_writer_create(k ? out_b : out_a, g, layers, &err)))
            goto out;
    if (!c.buf || each_tile(c.in, &c, copy_tile) != 0)
        goto out;
    for (int k = 0; k < (out_b ? 2 : 1); k++) {
        for (uint32_t i = 0; i < vts_store_meta_count(c.in); i++)
            if (vts_writer_set_meta(c.out[k], vts_store_meta_key(c.in, i),
                                    vts_store_meta_value(c.in, i), &err) != 0)
                goto out;
        if ((out_b && shard_key &&
             vts_writer_set_meta(c.out[k], "shard", k ? "2/2" : "1/2", &err) != 0) ||
            vts_writer_finish(c.out[k], &err) != 0)
            goto out;
    }
    rc = 0;
out:
    if (rc != 0 && err.message[0])
        fprintf(stderr, "vt-store-check: %s\n", err.message);
    vts_writer_destroy(c.out[0]);
    vts_writer_destroy(c.out[1]);
    free(c.buf);
    vts_close(c.in);
    return rc;
}

/* ---- smooth-png ---- */

static int smooth_png(const char *path, uint32_t width, uint32_t height)
{
    struct vts_error err = {0};
    unsigned char *row = malloc((size_t)width * 3);
    struct vt_png_file_writer *w = vt_png_file_writer_create(path, width, height, 3, 8, &err);
    int rc = !row || !w;
    for (uint32_t y = 0; rc == 0 && y < height; y++) {
        for (uint32_t x = 0; x < width; x++) {
            double u = (double)x / width, v = (double)y / height;
            double wave = 0.5 + 0.25 * sin(6.0 * u + 4.0 * v) * cos(5.0 * v - 3.0 * u);
            row[3 * x + 0] = (unsigned char)(255.0 * (0.2 + 0.6 * u) + 0.5);
            row[3 * x + 1] = (unsigned char)(255.0 * wave + 0.5);
            row[3 * x + 2] = (unsigned char)(255.0 * (0.8 - 0.6 * v) + 0.5);
        }
        rc = vt_png_file_writer_rows(w, row, 1, (size_t)width * 3, &err) != 0;
    }
    if (rc == 0)
        rc = vt_png_file_writer_finish(w, &err) != 0;
    if (rc != 0)
        fprintf(stderr, "vt-store-check: %s\n", err.message[0] ? err.message : "out of memory");
    vt_png_file_writer_destroy(w);
    free(row);
    return rc;
}

int main(int argc, char **argv)
{
    const char *cmd = argc > 1 ? argv[1] : "";
    if (argc == 4 && strcmp(cmd, "structure") == 0) {
        struct vts_store *a = open_store(argv[2]), *b = open_store(argv[3]);
        int rc = a && b ? check_structure(a, b) : 1;
        vts_close(a);
        vts_close(b);
        return rc;
    }
    if ((argc == 6 || (argc == 8 && strcmp(argv[6], "--psnr") == 0)) &&
        strcmp(cmd, "same-tiles") == 0)
        return check_tiles(argv[2], (uint32_t)atoi(argv[3]), argv[4], (uint32_t)atoi(argv[5]),
                           false, argc == 8 ? atof(argv[7]) : 0);
    if (argc == 6 && strcmp(cmd, "same-bytes") == 0)
        return check_tiles(argv[2], (uint32_t)atoi(argv[3]), argv[4], (uint32_t)atoi(argv[5]), true,
                           0);
    if ((argc == 5 || (argc == 6 && strcmp(argv[5], "--no-shard-key") == 0)) &&
        strcmp(cmd, "split") == 0)
        return copy_store(argv[2], argv[3], argv[4], argc == 5, -1, NULL);
    if (argc == 6 && strcmp(cmd, "rename") == 0)
        return copy_store(argv[2], argv[3], NULL, false, atoi(argv[4]), argv[5]);
    if (argc == 5 && strcmp(cmd, "smooth-png") == 0)
        return smooth_png(argv[2], (uint32_t)atoi(argv[3]), (uint32_t)atoi(argv[4]));
    fprintf(stderr, "usage: see the head of tests/cli/vt_store_check.c\n");
    return 2;
}
