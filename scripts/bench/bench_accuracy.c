/* What accuracy costs in time: every tile codec setting and every mip filter of vt-tiles, measured
 * on real photographs (8-bit RGB PNGs).
 *
 * Codecs: the image is padded to a multiple of 256 by mirroring (real texels, no flat streaks) and
 * cut into 256x256 tiles; every tile is encoded and decoded through the codec table. PSNR (dB, over
 * the R, G and B samples of the whole canvas) and SSIM (Gaussian window, sigma 1.5, 11x11, on
 * BT.601 luma; Wang et al. 2004) against the source, bits per texel (payload bytes), encode and
 * decode MP/s (best of RUNS runs, CLOCK_MONOTONIC, one thread).
 *
 * Filters: the image (cropped to even width and height) is reduced 2:1 by vt_filter_reduce with
 * each kernel, in linear light (colour srgb) and on the encoded values (colour data), through
 * vt_filter_to_working/from_working as vt-tiles does. The reference is the same reduction computed
 * in double precision in linear light with a Lanczos-8 kernel (sinc(x) sinc(x/8), |x| < 8 coarser
 * texels, 32 finer taps, edges clamped), converted back to sRGB without rounding.
 *
 * usage: vt-bench-accuracy [--runs N] --tsv OUT.tsv --md OUT.md IMAGE.png...
 * The TSV has one row per image and setting; the markdown has one table of codecs and one of
 * filters per image. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bench_util.h"
#include "vt_codec.h"
#include "vt_filter.h"
#include "vt_image.h"
#include "vt_png_file.h"

#define TILE  256
#define VT_PI 3.14159265358979323846

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

/* Loads a PNG as 8-bit RGB: grey is expanded, alpha dropped, 16-bit reduced to 8. */
static struct rgb load_rgb(const char *path)
{
    struct vt_image img;
    struct vts_error err;
    if (vt_png_file_read(path, &img, &err) != 0)
        die(path, &err);
    struct rgb out = {img.width, img.height, xmalloc((size_t)img.width * img.height * 3)};
    for (uint32_t y = 0; y < img.height; y++) {
        for (uint32_t x = 0; x < img.width; x++) {
            const unsigned char *s = vt_image_at(&img, x, y);
            uint8_t *d = out.px + ((size_t)y * img.width + x) * 3;
            for (uint32_t c = 0; c < 3; c++) {
                uint32_t sc = img.channels >= 3 ? c : 0;
                if (img.sample == VTS_SAMPLE_U16) {
                    uint16_t v;
                    memcpy(&v, s + sc * 2, 2);
                    d[c] = (uint8_t)((v * 255u + 32767u) / 65535u);
                } else {
                    d[c] = s[sc];
                }
            }
        }
    }
    vt_image_release(&img);
    return out;
}

/* ---- metrics ---- */

static double psnr_rgb(const uint8_t *a, const uint8_t *b, size_t samples)
{
    double se = 0;
    for (size_t i = 0; i < samples; i++) {
        double d = (double)a[i] - (double)b[i];
        se += d * d;
    }
    if (se == 0)
        return INFINITY;
    return 10.0 * log10(255.0 * 255.0 / (se / (double)samples));
}

/* PSNR of 8-bit RGB against a double-precision reference on the 0..255 scale. */
static double psnr_ref(const uint8_t *a, const double *ref, size_t samples)
{
    double se = 0;
    for (size_t i = 0; i < samples; i++) {
        double d = (double)a[i] - ref[i];
        se += d * d;
    }
    if (se == 0)
        return INFINITY;
    return 10.0 * log10(255.0 * 255.0 / (se / (double)samples));
}

/* Separable Gaussian blur (sigma 1.5, 11 taps) of a w x h plane, "valid" region only: out is
 * (w - 10) x (h - 10). */
static void gauss_valid(const double *in, uint32_t w, uint32_t h, double *tmp, double *out)
{
    double g[11], sum = 0;
    for (int i = 0; i < 11; i++) {
        g[i] = exp(-((i - 5) * (i - 5)) / (2 * 1.5 * 1.5));
        sum += g[i];
    }
    for (int i = 0; i < 11; i++)
        g[i] /= sum;
    uint32_t ow = w - 10, oh = h - 10;
    for (uint32_t y = 0; y < h; y++) {
        for (uint32_t x = 0; x < ow; x++) {
            double s = 0;
            for (int i = 0; i < 11; i++)
                s += g[i] * in[(size_t)y * w + x + (uint32_t)i];
            tmp[(size_t)y * ow + x] = s;
        }
    }
    for (uint32_t y = 0; y < oh; y++) {
        for (uint32_t x = 0; x < ow; x++) {
            double s = 0;
            for (int i = 0; i < 11; i++)
                s += g[i] * tmp[(size_t)(y + (uint32_t)i) * ow + x];
            out[(size_t)y * ow + x] = s;
        }
    }
}

/* Mean SSIM of the BT.601 luma of a (8-bit RGB) against ref (RGB on the 0..255 scale, as doubles),
 * Gaussian window, K1 0.01, K2 0.03, L 255. */
static double ssim_luma(const uint8_t *a, const double *ref, uint32_t w, uint32_t h)
{
    if (w < 11 || h < 11)
        return NAN;
    size_t n = (size_t)w * h, on = (size_t)(w - 10) * (h - 10);
    double *x = xmalloc(n * sizeof *x), *y = xmalloc(n * sizeof *y), *p = xmalloc(n * sizeof *p);
    double *tmp = xmalloc(n * sizeof *tmp), *m[5];
    for (int i = 0; i < 5; i++)
        m[i] = xmalloc(on * sizeof *m[i]);
    for (size_t i = 0; i < n; i++) {
        x[i] = 0.299 * a[3 * i] + 0.587 * a[3 * i + 1] + 0.114 * a[3 * i + 2];
        y[i] = 0.299 * ref[3 * i] + 0.587 * ref[3 * i + 1] + 0.114 * ref[3 * i + 2];
    }
    gauss_valid(x, w, h, tmp, m[0]);
    gauss_valid(y, w, h, tmp, m[1]);
    for (size_t i = 0; i < n; i++)
        p[i] = x[i] * x[i];
    gauss_valid(p, w, h, tmp, m[2]);
    for (size_t i = 0; i < n; i++)
        p[i] = y[i] * y[i];
    gauss_valid(p, w, h, tmp, m[3]);
    for (size_t i = 0; i < n; i++)
        p[i] = x[i] * y[i];
    gauss_valid(p, w, h, tmp, m[4]);
    const double c1 = (0.01 * 255) * (0.01 * 255), c2 = (0.03 * 255) * (0.03 * 255);
    double total = 0;
    for (size_t i = 0; i < on; i++) {
        double mx = m[0][i], my = m[1][i];
        double vx = m[2][i] - mx * mx, vy = m[3][i] - my * my, cxy = m[4][i] - mx * my;
        total +=
            ((2 * mx * my + c1) * (2 * cxy + c2)) / ((mx * mx + my * my + c1) * (vx + vy + c2));
    }
    free(x);
    free(y);
    free(p);
    free(tmp);
    for (int i = 0; i < 5; i++)
        free(m[i]);
    return total / (double)on;
}

static double *to_double(const uint8_t *a, size_t samples)
{
    double *d = xmalloc(samples * sizeof *d);
    for (size_t i = 0; i < samples; i++)
        d[i] = a[i];
    return d;
}

/* ---- output ---- */

static FILE *tsv, *md;

static void fmt_db(char *buf, size_t n, double v)
{
    if (isinf(v))
        snprintf(buf, n, "exact");
    else
        snprintf(buf, n, "%.2f", v);
}

static void fmt_mps(char *buf, size_t n, double v)
{
    if (v >= 100)
        snprintf(buf, n, "%.0f", v);
    else if (v >= 10)
        snprintf(buf, n, "%.1f", v);
    else
        snprintf(buf, n, "%.2f", v);
}

/* ---- codecs ---- */

struct setting {
    const char *label; /* shown in tables and the plot */
    const char *codec;
    struct vt_codec_params params;
    uint32_t channels;
};

static const struct setting settings[] = {
    {"jpeg q50 4:2:0", "jpeg", {50, 0, 420}, 3},
    {"jpeg q50 4:4:4", "jpeg", {50, 0, 444}, 3},
    {"jpeg q75 4:2:0", "jpeg", {75, 0, 420}, 3},
    {"jpeg q75 4:4:4", "jpeg", {75, 0, 444}, 3},
    {"jpeg q85 4:2:0", "jpeg", {85, 0, 420}, 3},
    {"jpeg q85 4:4:4", "jpeg", {85, 0, 444}, 3},
    {"jpeg q95 4:2:0", "jpeg", {95, 0, 420}, 3},
    {"jpeg q95 4:4:4", "jpeg", {95, 0, 444}, 3},
    {"png level 1", "png", {0, 1, 0}, 3},
    {"png level 9", "png", {0, 9, 0}, 3},
    {"bc1 fast", "bc1", {0, 0, 0}, 3},
    {"bc1 best", "bc1", {0, 1, 0}, 3},
    {"bc3 fast (RGBA)", "bc3", {0, 0, 0}, 4},
    {"bc3 best (RGBA)", "bc3", {0, 1, 0}, 4},
    /* the references of our BC encoders (enum vt_codec_bc_effort), for the plot */
    {"bc1 ref stb_dxt", "bc1", {0, VT_CODEC_BC_REF_STB_DXT, 0}, 3},
    {"bc1 ref libsquish cluster fit", "bc1", {0, VT_CODEC_BC_REF_SQUISH, 0}, 3},
    {"raw", "raw", {0, 0, 0}, 3},
};

static void bench_codecs(const char *name, const struct rgb *src, int runs)
{
    uint32_t tx = (src->w + TILE - 1) / TILE, ty = (src->h + TILE - 1) / TILE;
    uint32_t cw = tx * TILE, ch = ty * TILE, ntiles = tx * ty;
    size_t cn = (size_t)cw * ch;
    /* The canvas: the image, mirrored past its right and bottom edges. */
    uint8_t *canvas = xmalloc(cn * 3), *out = xmalloc(cn * 3);
    for (uint32_t y = 0; y < ch; y++)
        for (uint32_t x = 0; x < cw; x++)
            memcpy(canvas + ((size_t)y * cw + x) * 3,
                   src->px + ((size_t)mirror(y, src->h) * src->w + mirror(x, src->w)) * 3, 3);
    double *ref = to_double(canvas, cn * 3);
    const double mp = (double)cn / 1e6;

    fprintf(md,
            "\n### %s: codecs\n\n%ux%u image padded by mirroring to %ux%u, %u tiles of %ux%u.\n\n"
            "| codec, setting | bits/texel | PSNR dB | SSIM | encode MP/s | decode MP/s |\n"
            "|---|---:|---:|---:|---:|---:|\n",
            name, src->w, src->h, cw, ch, ntiles, TILE, TILE);

    for (size_t s = 0; s < sizeof settings / sizeof settings[0]; s++) {
        const struct setting *st = &settings[s];
        const struct vt_codec *codec = vt_codec_find(st->codec);
        if (!codec) {
            fprintf(stderr, "vt-bench-accuracy: codec %s not in this build\n", st->codec);
            exit(1);
        }
        struct vts_error err;
        struct vt_image *tiles = xmalloc(ntiles * sizeof *tiles);
        struct vt_image *dec = xmalloc(ntiles * sizeof *dec);
        size_t bound = codec->encoded_bound(TILE, TILE, st->channels, VTS_SAMPLE_U8);
        unsigned char **bytes = xmalloc(ntiles * sizeof *bytes);
        size_t *len = xmalloc(ntiles * sizeof *len);
        for (uint32_t t = 0; t < ntiles; t++) {
            uint32_t ox = (t % tx) * TILE, oy = (t / tx) * TILE;
            if (vt_image_alloc(&tiles[t], TILE, TILE, st->channels, VTS_SAMPLE_U8, &err) != 0 ||
                vt_image_alloc(&dec[t], TILE, TILE, st->channels, VTS_SAMPLE_U8, &err) != 0)
                die("tile", &err);
            for (uint32_t y = 0; y < TILE; y++) {
                for (uint32_t x = 0; x < TILE; x++) {
                    unsigned char *d = vt_image_at(&tiles[t], x, y);
                    memcpy(d, canvas + ((size_t)(oy + y) * cw + ox + x) * 3, 3);
                    if (st->channels == 4)
                        d[3] = 255;
                }
            }
            bytes[t] = xmalloc(bound);
        }
        double best_enc = INFINITY, best_dec = INFINITY;
        for (int r = 0; r < runs; r++) {
            double t0 = now_s();
            for (uint32_t t = 0; t < ntiles; t++)
                if (codec->encode(&tiles[t], &st->params, bytes[t], bound, &len[t], &err) != 0)
                    die(st->label, &err);
            double t1 = now_s();
            for (uint32_t t = 0; t < ntiles; t++)
                if (codec->decode(bytes[t], len[t], &dec[t], &err) != 0)
                    die(st->label, &err);
            double t2 = now_s();
            best_enc = fmin(best_enc, t1 - t0);
            best_dec = fmin(best_dec, t2 - t1);
        }
        size_t total = 0;
        for (uint32_t t = 0; t < ntiles; t++) {
            uint32_t ox = (t % tx) * TILE, oy = (t / tx) * TILE;
            total += len[t];
            for (uint32_t y = 0; y < TILE; y++)
                for (uint32_t x = 0; x < TILE; x++)
                    memcpy(out + ((size_t)(oy + y) * cw + ox + x) * 3, vt_image_at(&dec[t], x, y),
                           3);
            free(bytes[t]);
            vt_image_release(&tiles[t]);
            vt_image_release(&dec[t]);
        }
        free(tiles);
        free(dec);
        free(bytes);
        free(len);
        double bpt = (double)total * 8.0 / (double)cn;
        double psnr = psnr_rgb(out, canvas, cn * 3);
        double ssim = ssim_luma(out, ref, cw, ch);
        double enc = mp / best_enc, decm = mp / best_dec;
        char db[32], e[32], d[32];
        fmt_db(db, sizeof db, psnr);
        fmt_mps(e, sizeof e, enc);
        fmt_mps(d, sizeof d, decm);
        fprintf(tsv, "%s\tcodec\t%s\t%.3f\t%s\t%.5f\t%.4f\t%.4f\n", name, st->label, bpt,
                isinf(psnr) ? "inf" : db, ssim, enc, decm);
        fprintf(md, "| %s | %.2f | %s | %.4f | %s | %s |\n", st->label, bpt, db, ssim, e, d);
        fflush(tsv);
        fprintf(stderr, "  %s %-16s %6.2f bpt %6s dB  enc %8s  dec %8s MP/s\n", name, st->label,
                bpt, db, e, d);
    }
    free(canvas);
    free(out);
    free(ref);
}

/* ---- filters ---- */

static double srgb_to_linear(double v)
{
    return v <= 0.04045 ? v / 12.92 : pow((v + 0.055) / 1.055, 2.4);
}

static double linear_to_srgb(double v)
{
    if (v <= 0)
        return 0;
    if (v >= 1)
        return 1;
    return v <= 0.0031308 ? v * 12.92 : 1.055 * pow(v, 1 / 2.4) - 0.055;
}

static double sinc(double x)
{
    if (fabs(x) < 1e-12)
        return 1;
    return sin(VT_PI * x) / (VT_PI * x);
}

/* 2:1 reduction of one line of n finer texels (stride st doubles) into m = n / 2 coarser ones with
 * Lanczos-8 in coarser-texel units (the geometry of docs/filters.md), positions clamped. */
#define REF_LOBES 8
static void ref_line(const double *in, size_t st, uint32_t n, double *out, size_t ost)
{
    for (uint32_t i = 0; i < n / 2; i++) {
        double sum = 0, wsum = 0;
        for (int64_t j = 2 * (int64_t)i - 2 * REF_LOBES; j <= 2 * (int64_t)i + 2 * REF_LOBES + 1;
             j++) {
            double x = ((double)j + 0.5 - (2.0 * i + 1.0)) / 2.0;
            if (fabs(x) >= REF_LOBES)
                continue;
            double wgt = sinc(x) * sinc(x / REF_LOBES);
            int64_t jc = j < 0 ? 0 : (j >= n ? n - 1 : j);
            sum += wgt * in[(size_t)jc * st];
            wsum += wgt;
        }
        out[(size_t)i * ost] = sum / wsum;
    }
}

/* The reference: sRGB on the 0..255 scale (unrounded, clamped to [0, 255]) of the Lanczos-8
 * reduction in linear light. */
static double *reference_reduce(const struct rgb *img)
{
    uint32_t w = img->w, h = img->h, ow = w / 2, oh = h / 2;
    size_t n = (size_t)w * h * 3;
    double *lin = xmalloc(n * sizeof *lin), *hor = xmalloc((size_t)ow * h * 3 * sizeof *hor);
    double *out = xmalloc((size_t)ow * oh * 3 * sizeof *out);
    for (size_t i = 0; i < n; i++)
        lin[i] = srgb_to_linear(img->px[i] / 255.0);
    for (uint32_t y = 0; y < h; y++)
        for (uint32_t c = 0; c < 3; c++)
            ref_line(lin + (size_t)y * w * 3 + c, 3, w, hor + (size_t)y * ow * 3 + c, 3);
    for (uint32_t x = 0; x < ow; x++)
        for (uint32_t c = 0; c < 3; c++)
            ref_line(hor + (size_t)x * 3 + c, (size_t)ow * 3, h, out + (size_t)x * 3 + c,
                     (size_t)ow * 3);
    for (size_t i = 0; i < (size_t)ow * oh * 3; i++)
        out[i] = 255.0 * linear_to_srgb(out[i]);
    free(lin);
    free(hor);
    return out;
}

static void bench_filters(const char *name, const struct rgb *full, int runs)
{
    /* Even width and height: every coarser texel has its 2x2 finer texels. */
    struct rgb img = {full->w & ~1u, full->h & ~1u, NULL};
    img.px = xmalloc((size_t)img.w * img.h * 3);
    for (uint32_t y = 0; y < img.h; y++)
        memcpy(img.px + (size_t)y * img.w * 3, full->px + (size_t)y * full->w * 3,
               (size_t)img.w * 3);
    uint32_t ow = img.w / 2, oh = img.h / 2;
    size_t n = (size_t)img.w * img.h, on = (size_t)ow * oh;
    double *ref = reference_reduce(&img);
    uint8_t *ref8 = xmalloc(on * 3); /* the reference rounded to 8 bits */
    for (size_t i = 0; i < on * 3; i++)
        ref8[i] = (uint8_t)lround(ref[i]);
    double ref8_psnr = psnr_ref(ref8, ref, on * 3);

    fprintf(
        md,
        "\n### %s: mip filters\n\n%ux%u -> %ux%u. Reference: Lanczos-8 in linear light, double precision (the reference itself rounded to 8 bits scores %.2f dB).\n\n"
        "| filter | colour | PSNR dB | SSIM | MP/s |\n|---|---|---:|---:|---:|\n",
        name, img.w, img.h, ow, oh, ref8_psnr);

    float *work = xmalloc(n * 3 * sizeof *work), *dwork = xmalloc(on * 3 * sizeof *dwork);
    uint8_t *out = xmalloc(on * 3);
    static const enum vt_filter_kind kinds[] = {VT_FILTER_BOX, VT_FILTER_TRIANGLE,
                                                VT_FILTER_LANCZOS3, VT_FILTER_KAISER};
    static const uint32_t colours[] = {VTS_COLOUR_SRGB, VTS_COLOUR_DATA};
    for (size_t k = 0; k < sizeof kinds / sizeof kinds[0]; k++) {
        for (size_t c = 0; c < 2; c++) {
            struct vt_kernel kern;
            vt_kernel_init(&kern, kinds[k]);
            struct vt_pixel_mode mode = {3, colours[c], false};
            struct vt_edges edges = {img.w, img.h, false, false};
            struct vt_fregion src = {0, 0, img.w, img.h, 3, work};
            struct vt_fregion dst = {0, 0, ow, oh, 3, dwork};
            size_t scratch_n = vt_filter_reduce_scratch(&kern, &src, &dst);
            float *scratch = xmalloc(scratch_n * sizeof *scratch);
            struct vts_error err;
            double best = INFINITY;
            for (int r = 0; r < runs; r++) {
                double t0 = now_s();
                vt_filter_to_working(&mode, VTS_SAMPLE_U8, img.px, work, n);
                if (vt_filter_reduce(&kern, &edges, &src, &dst, scratch, scratch_n, &err) != 0)
                    die("vt_filter_reduce", &err);
                vt_filter_from_working(&mode, VTS_SAMPLE_U8, dwork, out, on);
                best = fmin(best, now_s() - t0);
            }
            free(scratch);
            double psnr = psnr_ref(out, ref, on * 3);
            double ssim = ssim_luma(out, ref, ow, oh);
            double mps = (double)n / 1e6 / best;
            const char *cname = colours[c] == VTS_COLOUR_SRGB ? "srgb (linear light)" : "data";
            char db[32], m[32];
            fmt_db(db, sizeof db, psnr);
            fmt_mps(m, sizeof m, mps);
            fprintf(tsv, "%s\tfilter\t%s %s\t-\t%s\t%.5f\t%.4f\t-\n", name,
                    vt_filter_name(kinds[k]), colours[c] == VTS_COLOUR_SRGB ? "srgb" : "data", db,
                    ssim, mps);
            fprintf(md, "| %s | %s | %s | %.4f | %s |\n", vt_filter_name(kinds[k]), cname, db, ssim,
                    m);
            fprintf(stderr, "  %s %-9s %-5s %6s dB  %8s MP/s\n", name, vt_filter_name(kinds[k]),
                    colours[c] == VTS_COLOUR_SRGB ? "srgb" : "data", db, m);
        }
    }
    free(work);
    free(dwork);
    free(out);
    free(ref);
    free(ref8);
    free(img.px);
}

int main(int argc, char **argv)
{
    bench_name = "vt-bench-accuracy";
    const char *tsv_path = NULL, *md_path = NULL;
    int runs = 3, i = 1;
    for (; i < argc && argv[i][0] == '-'; i++) {
        if (!strcmp(argv[i], "--tsv") && i + 1 < argc)
            tsv_path = argv[++i];
        else if (!strcmp(argv[i], "--md") && i + 1 < argc)
            md_path = argv[++i];
        else if (!strcmp(argv[i], "--runs") && i + 1 < argc)
            runs = atoi(argv[++i]);
        else
            break;
    }
    if (!tsv_path || !md_path || i >= argc || runs < 1) {
        fprintf(stderr,
                "usage: vt-bench-accuracy [--runs N] --tsv OUT.tsv --md OUT.md IMAGE.png...\n");
        return 2;
    }
    tsv = fopen(tsv_path, "w");
    md = fopen(md_path, "w");
    if (!tsv || !md) {
        perror("vt-bench-accuracy: cannot open an output");
        return 1;
    }
    fprintf(tsv, "image\tkind\tsetting\tbits_per_texel\tpsnr_db\tssim\tencode_mps\tdecode_mps\n");
    for (; i < argc; i++) {
        const char *path = argv[i], *base = strrchr(path, '/');
        base = base ? base + 1 : path;
        struct rgb img = load_rgb(path);
        if (img.w < 22 || img.h < 22) {
            fprintf(stderr, "vt-bench-accuracy: %s: too small\n", path);
            return 1;
        }
        fprintf(stderr, "%s: %ux%u\n", base, img.w, img.h);
        bench_codecs(base, &img, runs);
        bench_filters(base, &img, runs);
        free(img.px);
    }
    if (fclose(tsv) != 0 || fclose(md) != 0) {
        perror("vt-bench-accuracy: write");
        return 1;
    }
    return 0;
}
