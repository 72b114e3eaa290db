/* Does the store reader add a real cost to decoding? Decodes every stored tile of layer 0 of a
 * store, in one thread, in three ways, interleaved round by round (so that a change of machine
 * load hits all three alike):
 *   memory:   payloads read into memory beforehand, decoded with the layer's codec (for a jpeg
 *             layer: TurboJPEG tjDecompress2 from memory);
 *   store:    vts_store_read (one pread + CRC-32C check) into a buffer, then the same decode;
 *   store-nocrc: the same with VTS_READ_NO_CRC.
 * Prints MP/s (decoded payload texels) of the best round of each and the ratios store/memory.
 * The page cache holds the file (it is read once before timing).
 * usage: vt-bench-decode [--rounds N] STORE.vts */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "vt_codec.h"
#include "vt_image.h"
#include "vts.h"

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

static void die(const char *what, const struct vts_error *err)
{
    fprintf(stderr, "vt-bench-decode: %s: %s\n", what, err ? err->message : "failed");
    exit(1);
}

static void *xmalloc(size_t n)
{
    void *p = malloc(n ? n : 1);
    if (!p) {
        fprintf(stderr, "vt-bench-decode: out of memory\n");
        exit(1);
    }
    return p;
}

struct tile {
    uint32_t level, tx, ty;
    size_t len;
    unsigned char *bytes; /* the payload, for the in-memory run */
};

int main(int argc, char **argv)
{
    int rounds = 7, i = 1;
    if (i + 1 < argc && !strcmp(argv[i], "--rounds")) {
        rounds = atoi(argv[i + 1]);
        i += 2;
    }
    if (i + 1 != argc || rounds < 1) {
        fprintf(stderr, "usage: vt-bench-decode [--rounds N] STORE.vts\n");
        return 2;
    }
    struct vts_error err;
    struct vts_store *store = vts_open(argv[i], &err);
    if (!store)
        die(argv[i], &err);
    const struct vts_geometry *g = vts_store_geometry(store);
    const struct vts_layer *layer = vts_store_layer(store, 0);
    const struct vt_codec *codec = vt_codec_by_fourcc(layer->codec);
    if (!codec) {
        fprintf(stderr, "vt-bench-decode: no codec for layer 0 in this build\n");
        return 1;
    }

    /* Every stored tile of layer 0, with its payload. */
    size_t cap = 64, count = 0, bytes = 0;
    struct tile *tiles = xmalloc(cap * sizeof *tiles);
    for (uint32_t l = 0; l < g->level_count; l++) {
        struct vts_level lv;
        vts_store_level(store, l, &lv);
        for (uint32_t ty = 0; ty < lv.tiles_y; ty++) {
            for (uint32_t tx = 0; tx < lv.tiles_x; tx++) {
                struct vts_tile_entry e;
                if (vts_store_tile(store, 0, l, tx, ty, &e, &err) != 0)
                    die("index", &err);
                if (e.length == 0)
                    continue;
                if (count == cap) {
                    cap *= 2;
                    struct tile *t = realloc(tiles, cap * sizeof *tiles);
                    if (!t)
                        die("out of memory", NULL);
                    tiles = t;
                }
                struct tile *t = &tiles[count++];
                t->level = l;
                t->tx = tx;
                t->ty = ty;
                t->bytes = xmalloc(e.length);
                if (vts_store_read(store, 0, l, tx, ty, t->bytes, e.length, &t->len, 0, &err) != 0)
                    die("read", &err);
                bytes += t->len;
            }
        }
    }
    if (count == 0) {
        fprintf(stderr, "vt-bench-decode: layer 0 has no stored tile\n");
        return 1;
    }
    struct vt_image dec;
    if (vt_image_alloc(&dec, g->tile_payload_px, g->tile_payload_px, layer->channels, layer->sample,
                       &err) != 0)
        die("tile", &err);
    size_t bufcap = vts_store_max_payload(store);
    unsigned char *buf = xmalloc(bufcap);
    const double mp = (double)count * g->tile_payload_px * g->tile_payload_px / 1e6;

    double best[3] = {INFINITY, INFINITY, INFINITY};
    static const char *const names[3] = {"memory", "store", "store-nocrc"};
    for (int r = 0; r < rounds; r++) {
        for (int way = 0; way < 3; way++) {
            double t0 = now_s();
            for (size_t k = 0; k < count; k++) {
                const struct tile *t = &tiles[k];
                const void *src = t->bytes;
                size_t len = t->len;
                if (way > 0) {
                    if (vts_store_read(store, 0, t->level, t->tx, t->ty, buf, bufcap, &len,
                                       way == 2 ? VTS_READ_NO_CRC : 0, &err) != 0)
                        die("read", &err);
                    src = buf;
                }
                if (codec->decode(src, len, &dec, &err) != 0)
                    die("decode", &err);
            }
            double dt = now_s() - t0;
            if (dt < best[way])
                best[way] = dt;
        }
    }
    printf("store: %s (%s, %ux%u, %u levels), layer 0: %s %u channel(s)\n", argv[i], codec->name,
           g->width, g->height, g->level_count, layer->name, layer->channels);
    printf(
        "tiles: %zu stored, %ux%u payload, %.1f MP decoded per round, %.2f bits/texel, best of %d rounds\n",
        count, g->tile_payload_px, g->tile_payload_px, mp, (double)bytes * 8 / (mp * 1e6), rounds);
    for (int way = 0; way < 3; way++)
        printf("%-12s %8.1f MP/s  %8.2f ms/round\n", names[way], mp / best[way], best[way] * 1e3);
    printf("ratio store/memory:       %.3f\n", best[0] / best[1]);
    printf("ratio store-nocrc/memory: %.3f\n", best[0] / best[2]);

    for (size_t k = 0; k < count; k++)
        free(tiles[k].bytes);
    free(tiles);
    free(buf);
    vt_image_release(&dec);
    vts_close(store);
    return 0;
}
