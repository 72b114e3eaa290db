/* Our BC1/BC3 encoders against the references, on the same texels, through the codec table
 * (formats/codec/vt_codec.h, effort = enum vt_codec_bc_effort): ours best against libsquish's
 * cluster fit, ours fast against stb_dxt.
 *
 * Each image is padded to a multiple of 256 by mirroring and cut into 256x256 tiles: RGB tiles for
 * bc1, RGBA tiles with alpha 255 for bc3. Every encoder encodes every tile; the decoded tiles
 * (our decoder) give the PSNR over the R, G and B samples of the whole canvas. Speed: megatexels
 * per second of CPU time of the one encoding thread (CLOCK_THREAD_CPUTIME_ID, so other load on a
 * shared machine counts less than in wall time), best of RUNS runs.
 *
 * usage: vt-bench-bc [--runs N] [--synth EDGE] [--synth-rgba EDGE] [--md OUT.md] [--only LABEL]
 *                    [IMAGE.png...]
 * --synth-rgba adds bc3 on the generator's RGBA image with its own alpha at EDGE^2 (a multiple of
 * 256; PSNR over R, G, B, A; not in the totals).
 * --only runs the one encoder of that label (e.g. "ours fast"; for perf record), the others'
 * columns stay empty (NaN). --synth adds the tests' photo-like generator (vt_synth_photo, seed 1,
 * chroma 0.6) at EDGE^2. Prints one table per image and format, then the totals over all images
 * (PSNR of the summed squared error, MP/s of the summed time) with the ratios ours/reference. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bench_util.h"
#include "vt_codec.h"
#include "vt_image.h"
#include "vt_png_file.h"
#include "vt_synth_photo.h"

#define TILE 256

static double cpu_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

static struct rgb from_image(const struct vt_image *img)
{
    struct rgb out = {img->width, img->height, xmalloc((size_t)img->width * img->height * 3)};
    for (uint32_t y = 0; y < img->height; y++) {
        for (uint32_t x = 0; x < img->width; x++) {
            const unsigned char *s = vt_image_at(img, x, y);
            uint8_t *d = out.px + ((size_t)y * img->width + x) * 3;
            for (uint32_t c = 0; c < 3; c++) {
                uint32_t sc = img->channels >= 3 ? c : 0;
                if (img->sample == VTS_SAMPLE_U16) {
                    uint16_t v;
                    memcpy(&v, s + sc * 2, 2);
                    d[c] = (uint8_t)((v * 255u + 32767u) / 65535u);
                } else {
                    d[c] = s[sc];
                }
            }
        }
    }
    return out;
}

struct encoder {
    const char *label;
    int effort;
};

/* In pairs: ours, then its reference. */
static const struct encoder encoders[] = {
    {"ours best", VT_CODEC_BC_BEST},
    {"libsquish cluster fit", VT_CODEC_BC_REF_SQUISH},
    {"ours fast", VT_CODEC_BC_FAST},
    {"stb_dxt", VT_CODEC_BC_REF_STB_DXT},
};
#define N_ENCODERS (sizeof encoders / sizeof encoders[0])

struct total {
    double se, samples, seconds, texels;
};
static struct total totals[2][N_ENCODERS]; /* [bc1, bc3][encoder] */

static double psnr_of(double se, double samples)
{
    return se == 0 ? INFINITY : 10.0 * log10(255.0 * 255.0 / (se / samples));
}

static FILE *md;
static const char *only; /* --only: the one encoder to run */

static void report(const char *title, const double psnr[N_ENCODERS], const double mps[N_ENCODERS])
{
    fprintf(
        md,
        "\n%s\n\n| encoder | PSNR dB | MP/s per core | vs reference: dB | vs reference: speed |\n"
        "|---|---:|---:|---:|---:|\n",
        title);
    for (size_t e = 0; e < N_ENCODERS; e++) {
        if (e % 2 == 0)
            fprintf(md, "| %s | %.2f | %.2f | %+.2f | %.1fx |\n", encoders[e].label, psnr[e],
                    mps[e], psnr[e] - psnr[e + 1], mps[e] / mps[e + 1]);
        else
            fprintf(md, "| %s | %.2f | %.2f | | |\n", encoders[e].label, psnr[e], mps[e]);
    }
    printf("%s\n", title);
    for (size_t e = 0; e < N_ENCODERS; e++) {
        printf("  %-22s %7.3f dB %8.2f MP/s per core", encoders[e].label, psnr[e], mps[e]);
        if (e % 2 == 0)
            printf("   ours/%s: %+.3f dB, %.1fx speed", encoders[e + 1].label,
                   psnr[e] - psnr[e + 1], mps[e] / mps[e + 1]);
        printf("\n");
    }
    fflush(stdout);
}

/* Encodes the tiles with every encoder (runs times, the fastest kept) and reports PSNR over the
 * first psnr_channels samples of each texel and MP/s per core; adds to tot[] when not NULL. */
static void bench_tiles(const char *title, const char *codec_name, struct vt_image *tiles,
                        uint32_t ntiles, uint32_t psnr_channels, int runs, struct total *tot)
{
    const struct vt_codec *codec = vt_codec_find(codec_name);
    uint32_t channels = tiles[0].channels;
    size_t cn = (size_t)ntiles * TILE * TILE;
    struct vts_error err;
    struct vt_image dec;
    if (vt_image_alloc(&dec, TILE, TILE, channels, VTS_SAMPLE_U8, &err) != 0)
        die("tile", &err);
    size_t bound = codec->encoded_bound(TILE, TILE, channels, VTS_SAMPLE_U8);
    unsigned char *bytes = xmalloc(bound * ntiles);
    double psnr[N_ENCODERS], mps[N_ENCODERS];
    for (size_t e = 0; e < N_ENCODERS; e++) {
        struct vt_codec_params params = {.effort = encoders[e].effort};
        double best = INFINITY;
        if (only && strcmp(only, encoders[e].label) != 0) {
            psnr[e] = mps[e] = NAN;
            continue;
        }
        for (int r = 0; r < runs; r++) {
            double t0 = cpu_s();
            for (uint32_t t = 0; t < ntiles; t++) {
                size_t len;
                if (codec->encode(&tiles[t], &params, bytes + t * bound, bound, &len, &err))
                    die(encoders[e].label, &err);
            }
            best = fmin(best, cpu_s() - t0);
        }
        double se = 0;
        for (uint32_t t = 0; t < ntiles; t++) {
            if (codec->decode(bytes + t * bound, bound, &dec, &err) != 0)
                die(encoders[e].label, &err);
            for (uint32_t y = 0; y < TILE; y++)
                for (uint32_t x = 0; x < TILE; x++) {
                    const unsigned char *a = vt_image_at(&tiles[t], x, y);
                    const unsigned char *b = vt_image_at(&dec, x, y);
                    for (uint32_t c = 0; c < psnr_channels; c++)
                        se += (double)(a[c] - b[c]) * (a[c] - b[c]);
                }
        }
        psnr[e] = psnr_of(se, (double)cn * psnr_channels);
        mps[e] = (double)cn / 1e6 / best;
        if (tot) {
            tot[e].se += se;
            tot[e].samples += (double)cn * psnr_channels;
            tot[e].seconds += best;
            tot[e].texels += (double)cn;
        }
    }
    report(title, psnr, mps);
    vt_image_release(&dec);
    free(bytes);
}

static void bench_image(const char *name, const struct rgb *src, int runs)
{
    uint32_t tx = (src->w + TILE - 1) / TILE, ty = (src->h + TILE - 1) / TILE;
    uint32_t cw = tx * TILE, ch = ty * TILE, ntiles = tx * ty;
    size_t cn = (size_t)cw * ch;
    uint8_t *canvas = xmalloc(cn * 3);
    for (uint32_t y = 0; y < ch; y++)
        for (uint32_t x = 0; x < cw; x++)
            memcpy(canvas + ((size_t)y * cw + x) * 3,
                   src->px + ((size_t)mirror(y, src->h) * src->w + mirror(x, src->w)) * 3, 3);
    for (int f = 0; f < 2; f++) {
        const char *codec_name = f ? "bc3" : "bc1";
        uint32_t channels = f ? 4 : 3;
        struct vts_error err;
        struct vt_image *tiles = xmalloc(ntiles * sizeof *tiles);
        for (uint32_t t = 0; t < ntiles; t++) {
            uint32_t ox = (t % tx) * TILE, oy = (t / tx) * TILE;
            if (vt_image_alloc(&tiles[t], TILE, TILE, channels, VTS_SAMPLE_U8, &err) != 0)
                die("tile", &err);
            for (uint32_t y = 0; y < TILE; y++)
                for (uint32_t x = 0; x < TILE; x++) {
                    unsigned char *d = vt_image_at(&tiles[t], x, y);
                    memcpy(d, canvas + ((size_t)(oy + y) * cw + ox + x) * 3, 3);
                    if (channels == 4)
                        d[3] = 255;
                }
        }
        char title[256];
        snprintf(title, sizeof title, "#### %s, %s (%ux%u padded to %ux%u%s)", name, codec_name,
                 src->w, src->h, cw, ch, f ? ", RGBA with alpha 255" : ", RGB");
        bench_tiles(title, codec_name, tiles, ntiles, 3, runs, totals[f]);
        for (uint32_t t = 0; t < ntiles; t++)
            vt_image_release(&tiles[t]);
        free(tiles);
    }
    free(canvas);
}

/* bc3 on the tests' photo-like generator with its own alpha (a smooth field and a hard-edged
 * hole: alpha that varies, which the photographs lack), edge^2 (a multiple of TILE); PSNR over
 * R, G, B and A; not in the totals. */
static void bench_synth_rgba(uint32_t edge, int runs)
{
    struct vt_image img = vt_synth_photo(edge, edge, 4, 1, 0.6);
    uint32_t n = edge / TILE, ntiles = n * n;
    struct vts_error err;
    struct vt_image *tiles = xmalloc(ntiles * sizeof *tiles);
    for (uint32_t t = 0; t < ntiles; t++) {
        if (vt_image_alloc(&tiles[t], TILE, TILE, 4, VTS_SAMPLE_U8, &err) != 0)
            die("tile", &err);
        for (uint32_t y = 0; y < TILE; y++)
            memcpy(vt_image_at(&tiles[t], 0, y),
                   vt_image_at(&img, (t % n) * TILE, (t / n) * TILE + y), (size_t)TILE * 4);
    }
    char title[256];
    snprintf(
        title, sizeof title,
        "#### synthetic photo with alpha %ux%u, bc3 (RGBA, its own alpha; PSNR over R, G, B, A)",
        edge, edge);
    bench_tiles(title, "bc3", tiles, ntiles, 4, runs, NULL);
    for (uint32_t t = 0; t < ntiles; t++)
        vt_image_release(&tiles[t]);
    free(tiles);
    free(img.pixels);
}

int main(int argc, char **argv)
{
    bench_name = "vt-bench-bc";
    int runs = 3, i = 1;
    uint32_t synth = 0, synth_rgba = 0;
    const char *md_path = NULL;
    for (; i < argc && argv[i][0] == '-'; i++) {
        if (!strcmp(argv[i], "--runs") && i + 1 < argc)
            runs = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--synth") && i + 1 < argc)
            synth = (uint32_t)atoi(argv[++i]);
        else if (!strcmp(argv[i], "--md") && i + 1 < argc)
            md_path = argv[++i];
        else if (!strcmp(argv[i], "--only") && i + 1 < argc)
            only = argv[++i];
        else if (!strcmp(argv[i], "--synth-rgba") && i + 1 < argc)
            synth_rgba = (uint32_t)atoi(argv[++i]);
        else
            break;
    }
    if (runs < 1 || (i >= argc && synth == 0 && synth_rgba == 0) || synth_rgba % TILE != 0) {
        fprintf(
            stderr,
            "usage: vt-bench-bc [--runs N] [--synth EDGE] [--synth-rgba EDGE] [--md OUT.md] [--only LABEL] [IMAGE.png...]\n");
        return 2;
    }
    md = md_path ? fopen(md_path, "w") : fopen("/dev/null", "w");
    if (!md) {
        perror("vt-bench-bc: cannot open the markdown output");
        return 1;
    }
    int images = 0;
    if (synth) {
        struct vt_image img = vt_synth_photo(synth, synth, 3, 1, 0.6);
        struct rgb r = from_image(&img);
        char name[64];
        snprintf(name, sizeof name, "synthetic photo %ux%u", synth, synth);
        bench_image(name, &r, runs);
        free(r.px);
        free(img.pixels);
        images++;
    }
    for (; i < argc; i++) {
        const char *path = argv[i], *base = strrchr(path, '/');
        struct vt_image img;
        struct vts_error err;
        if (vt_png_file_read(path, &img, &err) != 0)
            die(path, &err);
        struct rgb r = from_image(&img);
        vt_image_release(&img);
        bench_image(base ? base + 1 : path, &r, runs);
        free(r.px);
        images++;
    }
    for (int f = 0; f < 2; f++) {
        double psnr[N_ENCODERS], mps[N_ENCODERS];
        for (size_t e = 0; e < N_ENCODERS; e++) {
            psnr[e] = totals[f][e].samples > 0 ? psnr_of(totals[f][e].se, totals[f][e].samples)
                                               : NAN; /* not run (--only) */
            mps[e] = totals[f][e].texels / 1e6 / totals[f][e].seconds;
        }
        char title[128];
        snprintf(title, sizeof title, "#### All %d images, %s", images, f ? "bc3" : "bc1");
        if (images)
            report(title, psnr, mps);
    }
    if (synth_rgba)
        bench_synth_rgba(synth_rgba, runs);
    if (fclose(md) != 0) {
        perror("vt-bench-bc: write");
        return 1;
    }
    return 0;
}
