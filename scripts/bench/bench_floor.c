/* The floor of a vt-tiles job on a tiled TIFF: the work no tiling tool can avoid, run alone on
 * `threads` threads: decode every input tile once (libtiff, one handle per thread) and encode as
 * many JPEG tiles as the pyramid has (TurboJPEG, 4:2:0, at the given quality; the decoded input
 * tiles, cropped or padded to the payload edge, are the texels; upper-level tiles reuse the last
 * one). Prints the wall time of the two together and of the decoding alone
 * (scripts/bench/tiles-vs-vips divides our wall time by the first).
 * usage: vt-bench-floor IN.tif THREADS PAYLOAD_PX BORDER QUALITY */
#include <pthread.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <tiffio.h>
#include <time.h>
#include <turbojpeg.h>

struct job {
    const char *path;
    unsigned index, threads;
    uint32_t tiles_in, tiles_out, payload, quality;
    int decode, encode;
    int failed;
};

static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + (double)t.tv_nsec * 1e-9;
}

static void *worker(void *arg)
{
    struct job *j = arg;
    TIFF *t = TIFFOpen(j->path, "rm");
    tjhandle tj = tjInitCompress();
    uint32_t tw = 0, th = 0;
    if (t) {
        TIFFGetField(t, TIFFTAG_TILEWIDTH, &tw);
        TIFFGetField(t, TIFFTAG_TILELENGTH, &th);
    }
    if (!t || !tj || tw == 0 || th == 0) {
        j->failed = 1;
        return NULL;
    }
    size_t in_bytes = (size_t)tw * th * 3, pp = j->payload;
    unsigned char *in = calloc(in_bytes, 1), *tile = calloc(pp * pp * 3, 1);
    unsigned long cap = tjBufSize((int)pp, (int)pp, TJSAMP_420);
    unsigned char *out = tjAlloc((int)cap);
    /* output tiles i = index, index + threads, ...; the first tiles_in of them also decode */
    uint32_t n = j->tiles_out > j->tiles_in ? j->tiles_out : j->tiles_in;
    for (uint32_t i = j->index; i < n && !j->failed; i += j->threads) {
        if (j->decode && i < j->tiles_in && TIFFReadEncodedTile(t, i, in, (tmsize_t)in_bytes) < 0)
            j->failed = 1;
        if (!j->encode || i >= j->tiles_out)
            continue;
        for (size_t y = 0; y < pp; y++)
            memcpy(tile + y * pp * 3, in + (y % th) * tw * 3, (pp < tw ? pp : tw) * 3);
        unsigned long size = cap;
        if (tjCompress2(tj, tile, (int)pp, 0, (int)pp, TJPF_RGB, &out, &size, TJSAMP_420,
                        (int)j->quality, TJFLAG_NOREALLOC) != 0)
            j->failed = 1;
    }
    tjFree(out);
    free(in);
    free(tile);
    tjDestroy(tj);
    TIFFClose(t);
    return NULL;
}

static double run(struct job *proto, unsigned threads, int decode, int encode)
{
    pthread_t th[64];
    struct job jobs[64];
    double t0 = now_s();
    for (unsigned i = 0; i < threads; i++) {
        jobs[i] = *proto;
        jobs[i].index = i;
        jobs[i].decode = decode;
        jobs[i].encode = encode;
        pthread_create(&th[i], NULL, worker, &jobs[i]);
    }
    for (unsigned i = 0; i < threads; i++) {
        pthread_join(th[i], NULL);
        proto->failed |= jobs[i].failed;
    }
    return now_s() - t0;
}

int main(int argc, char **argv)
{
    if (argc != 6) {
        fprintf(stderr, "usage: vt-bench-floor IN.tif THREADS PAYLOAD_PX BORDER QUALITY\n");
        return 2;
    }
    unsigned threads = (unsigned)strtoul(argv[2], NULL, 10);
    uint32_t payload = (uint32_t)strtoul(argv[3], NULL, 10);
    uint32_t border = (uint32_t)strtoul(argv[4], NULL, 10);
    uint32_t quality = (uint32_t)strtoul(argv[5], NULL, 10);
    TIFF *t = TIFFOpen(argv[1], "rm");
    if (!t || threads < 1 || threads > 64 || payload <= 2 * border) {
        fprintf(stderr, "vt-bench-floor: bad arguments or '%s' unreadable\n", argv[1]);
        return 1;
    }
    uint32_t w = 0, h = 0;
    TIFFGetField(t, TIFFTAG_IMAGEWIDTH, &w);
    TIFFGetField(t, TIFFTAG_IMAGELENGTH, &h);
    uint32_t tiles_in = TIFFNumberOfTiles(t);
    TIFFClose(t);
    /* the pyramid's tiles: every level down to the one that fits in one tile */
    uint32_t content = payload - 2 * border, tiles_out = 0;
    for (uint32_t lw = w, lh = h;; lw = (lw + 1) / 2, lh = (lh + 1) / 2) {
        tiles_out += ((lw + content - 1) / content) * ((lh + content - 1) / content);
        if (lw <= content && lh <= content)
            break;
    }
    struct job proto = {argv[1], 0, threads, tiles_in, tiles_out, payload, quality, 0, 0, 0};
    double decode = run(&proto, threads, 1, 0);
    double both = run(&proto, threads, 1, 1);
    if (proto.failed) {
        fprintf(stderr, "vt-bench-floor: a decode or an encode failed\n");
        return 1;
    }
    printf("floor %.2f s (decode %u input tiles alone %.2f s, then encode %u tiles; %u threads)\n",
           both, tiles_in, decode, tiles_out, threads);
    return 0;
}
