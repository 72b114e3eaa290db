/* vt-view streaming benchmark (scripts/bench/view-streaming): tiles of one level of a JPEG store
 * are (a) decoded from memory with raw TurboJPEG (tjDecompress2, one thread, payloads preloaded)
 * and (b) streamed the way vt-view streams them: read through libvts, decoded by the layer's codec
 * on N loader threads, converted to RGBA8 and uploaded with glTexSubImage2D into a physical
 * texture (headless EGL context, glFinish at the end). Prints tiles/s and MP/s (payload texels)
 * for both, and the ratio streaming / raw.
 * usage: vtv_bench_stream STORE.vts [--level L] [--threads N] [--runs R] */
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <turbojpeg.h>

#include <epoxy/gl.h>

#include "vtv_context.h"
#include "vtv_loader.h"

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + ts.tv_nsec * 1e-9;
}

int main(int argc, char **argv)
{
    const char *path = NULL;
    uint32_t level = 0, threads = 2, runs = 3;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--level") && i + 1 < argc)
            level = (uint32_t)atoi(argv[++i]);
        else if (!strcmp(argv[i], "--threads") && i + 1 < argc)
            threads = (uint32_t)atoi(argv[++i]);
        else if (!strcmp(argv[i], "--runs") && i + 1 < argc)
            runs = (uint32_t)atoi(argv[++i]);
        else
            path = argv[i];
    }
    struct vts_error err = {0};
    struct vts_store *s = path ? vts_open(path, &err) : NULL;
    if (!s) {
        fprintf(stderr, "vtv_bench_stream: %s\n", path ? err.message : "usage: STORE.vts ...");
        return 2;
    }
    const struct vts_geometry *g = vts_store_geometry(s);
    if (vts_store_layer(s, 0)->codec != VTS_CODEC_JPEG || level >= g->level_count) {
        fprintf(stderr, "vtv_bench_stream: needs a JPEG store and an existing level\n");
        return 2;
    }
    struct vts_level lv;
    vts_store_level(s, level, &lv);
    uint32_t n = lv.tiles_x * lv.tiles_y, pp = g->tile_payload_px;
    uint32_t maxp = vts_store_max_payload(s);
    uint8_t *payloads = malloc((size_t)n * maxp);
    size_t *lens = calloc(n, sizeof(*lens));
    uint8_t *pixels = malloc((size_t)pp * pp * 4);
    for (uint32_t i = 0; i < n; i++)
        if (vts_store_read(s, 0, level, i % lv.tiles_x, i / lv.tiles_x, payloads + (size_t)i * maxp,
                           maxp, &lens[i], 0, &err) != 0) {
            fprintf(stderr, "vtv_bench_stream: %s\n", err.message);
            return 1;
        }
    double mp = (double)n * pp * pp / 1e6;

    /* (a) raw TurboJPEG from memory */
    int pf = vts_store_layer(s, 0)->channels == 1   ? TJPF_GRAY
             : vts_store_layer(s, 0)->channels == 3 ? TJPF_RGB
                                                    : TJPF_RGBA;
    tjhandle tj = tjInitDecompress();
    double best_raw = 1e30;
    for (uint32_t r = 0; r < runs; r++) {
        double t0 = now_s();
        for (uint32_t i = 0; i < n; i++)
            if (lens[i] && tjDecompress2(tj, payloads + (size_t)i * maxp, lens[i], pixels, (int)pp,
                                         0, (int)pp, pf, 0) != 0) {
                fprintf(stderr, "vtv_bench_stream: %s\n", tjGetErrorStr2(tj));
                return 1;
            }
        double t = now_s() - t0;
        best_raw = t < best_raw ? t : best_raw;
    }
    tjDestroy(tj);

    /* read + decode + RGBA8 on this thread, no GL (where the streaming time goes) */
    struct vtv_loader *l0 = vtv_loader_create(s, 0, 0, 0, &err);
    double best_load = 1e30;
    for (uint32_t r = 0; l0 && r < runs; r++) {
        double t0 = now_s();
        for (uint32_t i = 0; i < n; i++)
            vtv_loader_release(l0,
                               vtv_loader_load_now(l0, i, level, i % lv.tiles_x, i / lv.tiles_x));
        double t = now_s() - t0;
        best_load = t < best_load ? t : best_load;
    }
    vtv_loader_destroy(l0);

    /* (b) streaming: loader threads + RGBA8 + glTexSubImage2D */
    struct vtv_context *ctx = vtv_context_headless(&err);
    struct vtv_loader *l = ctx ? vtv_loader_create(s, 0, threads, 0, &err) : NULL;
    if (!l) {
        fprintf(stderr, "vtv_bench_stream: %s\n", err.message);
        return 1;
    }
    const uint32_t slots = 16;
    GLuint tex;
    glGenTextures(1, &tex);
    glBindTexture(GL_TEXTURE_2D, tex);
    glTexStorage2D(GL_TEXTURE_2D, 1, GL_RGBA8, (GLsizei)(slots * pp), (GLsizei)(slots * pp));
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    uint32_t cap = vtv_loader_queue_capacity(l);
    uint64_t *idx = malloc((size_t)cap * sizeof(*idx)), *dropped = malloc((size_t)cap * 8);
    uint32_t *lxy = malloc((size_t)cap * 3 * sizeof(*lxy));
    double best_stream = 1e30, best_upload = 1e30;
    for (uint32_t r = 0; r < runs; r++) {
        double t0 = now_s();
        uint32_t next = 0, done = 0, slot = 0;
        double upload = 0;
        while (done < n) {
            if (next < n) {
                uint32_t k = 0;
                for (; k < cap && next < n; k++, next++) {
                    idx[k] = next;
                    lxy[k * 3] = level;
                    lxy[k * 3 + 1] = next % lv.tiles_x;
                    lxy[k * 3 + 2] = next / lv.tiles_x;
                }
                vtv_loader_submit(l, idx, lxy, k, dropped);
            }
            vtv_loader_wait_idle(l);
            for (struct vtv_load *t = vtv_loader_take(l, UINT32_MAX), *x; t; t = x) {
                x = t->next;
                t->next = NULL;
                if (t->rgba) {
                    double u0 = now_s();
                    glTexSubImage2D(GL_TEXTURE_2D, 0, (GLint)((slot % slots) * pp),
                                    (GLint)((slot / slots % slots) * pp), (GLsizei)pp, (GLsizei)pp,
                                    GL_RGBA, GL_UNSIGNED_BYTE, t->rgba);
                    slot++;
                    upload += now_s() - u0;
                }
                done++;
                vtv_loader_release(l, t);
            }
        }
        double f0 = now_s();
        glFinish();
        upload += now_s() - f0;
        double t = now_s() - t0;
        best_upload = upload < best_upload ? upload : best_upload;
        best_stream = t < best_stream ? t : best_stream;
    }
    printf("store %s, level %u: %u tiles of %ux%u (%.1f MP)\n", path, level, n, pp, pp, mp);
    printf("raw turbojpeg (1 thread, from memory):  %8.0f tiles/s %8.1f MP/s\n", n / best_raw,
           mp / best_raw);
    printf("vt-view loader (this thread, no GL):    %8.0f tiles/s %8.1f MP/s\n", n / best_load,
           mp / best_load);
    printf("vt-view streaming (%u loader threads):   %8.0f tiles/s %8.1f MP/s\n", threads,
           n / best_stream, mp / best_stream);
    printf("  of which glTexSubImage2D + glFinish:   %8.3f s of %.3f s\n", best_upload,
           best_stream);
    printf("ratio streaming/raw: %.2f\n", best_raw / best_stream);
    glDeleteTextures(1, &tex);
    vtv_loader_destroy(l);
    vtv_context_destroy(ctx);
    vts_close(s);
    free(idx);
    free(dropped);
    free(lxy);
    free(payloads);
    free(lens);
    free(pixels);
    return 0;
}
