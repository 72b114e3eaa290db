/* Tangent-space normal maps through the GPU block codecs (formats/codec, effort fast 0 / best 1):
 * BC5 (x, y; z rebuilt) against BC1 and BC3 carrying xyz in RGB and BC3 in the "DXT5nm" swizzle
 * (x in alpha, y in green, red and blue 0; z rebuilt), and the floor of dropping z alone (8-bit
 * x, y, z rebuilt, no compression).
 *
 * Each image is read whole (formats/input: PNG, JPEG, ...), its first three channels taken as
 * xyz = 2 v / 255 - 1, padded to a multiple of 4 by repeating the edge, and encoded in one call
 * (the codecs are blockwise: a tile or the whole image give the same blocks). Measured over the
 * texels that hold a normal: |xyz| within 10% of 1 and z >= 0 (maps have unused texels, such as
 * white backgrounds), against the original normal made unit length:
 *   - angular error, degrees: mean and 99th percentile (0.01-degree histogram);
 *   - PSNR of the xyz samples as stored (0..255; a rebuilt z rounded to 8 bits);
 *   - encode speed: megatexels per second of CPU time of the one encoding thread
 *     (CLOCK_THREAD_CPUTIME_ID), best of RUNS runs.
 * A rebuilt z is sqrt(max(0, 1 - x^2 - y^2)) in double, as vt-view's shader does in float.
 *
 * usage: vt-bench-normals [--runs N] [--md OUT.md] [--tsv OUT.tsv] IMAGE...
 * Prints one table per image, then the totals over all images (mean of every measured texel,
 * PSNR of the summed squared error, MP/s of the summed time). */
#define _POSIX_C_SOURCE 200809L
#include <getopt.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bench_util.h"
#include "vt_codec.h"
#include "vt_image.h"
#include "vt_image_input.h"

#define HIST_BINS 18001 /* 0.01 degree each, 0 .. 180 */

enum carry {
    CARRY_XYZ3,   /* RGB = xyz */
    CARRY_XYZ4,   /* RGBA = xyz, 255 */
    CARRY_DXT5NM, /* RGBA = 0, y, 0, x */
    CARRY_XY2,    /* RG = xy */
};

struct variant {
    const char *label;
    const char *codec; /* NULL: no codec (the 8-bit x, y floor) */
    enum carry carry;
    int effort;
    int bits; /* per texel */
};

static const struct variant variants[] = {
    {"bc1 fast, xyz in RGB", "bc1", CARRY_XYZ3, VT_CODEC_BC_FAST, 4},
    {"bc1 best, xyz in RGB", "bc1", CARRY_XYZ3, VT_CODEC_BC_BEST, 4},
    {"bc3 fast, xyz in RGB", "bc3", CARRY_XYZ4, VT_CODEC_BC_FAST, 8},
    {"bc3 best, xyz in RGB", "bc3", CARRY_XYZ4, VT_CODEC_BC_BEST, 8},
    {"bc3 fast, DXT5nm (x in A, y in G)", "bc3", CARRY_DXT5NM, VT_CODEC_BC_FAST, 8},
    {"bc3 best, DXT5nm (x in A, y in G)", "bc3", CARRY_DXT5NM, VT_CODEC_BC_BEST, 8},
    {"bc5 fast, xy (z rebuilt)", "bc5", CARRY_XY2, VT_CODEC_BC_FAST, 8},
    {"bc5 best, xy (z rebuilt)", "bc5", CARRY_XY2, VT_CODEC_BC_BEST, 8},
    {"no codec: 8-bit xy, z rebuilt", NULL, CARRY_XY2, 0, 16},
};
#define N_VARIANTS (sizeof variants / sizeof variants[0])

struct result {
    double angle_sum, se, samples, seconds, texels;
    uint64_t count;
    uint64_t hist[HIST_BINS];
};

static struct result totals[N_VARIANTS];

static double cpu_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

/* The image's first three channels (8-bit), padded to a multiple of 4 by repeating the edge. */
static struct rgb load_padded(const char *path, uint32_t *orig_w, uint32_t *orig_h)
{
    struct vt_source src;
    struct vts_error err = {0};
    if (vt_image_input_open(path, NULL, &src, &err) != 0)
        die(path, &err);
    if (src.info.sample != VTS_SAMPLE_U8 || src.info.channels < 3) {
        fprintf(stderr, "%s: %s: not an 8-bit RGB image\n", bench_name, path);
        exit(1);
    }
    struct vt_image img;
    if (vt_image_alloc(&img, src.info.width, src.info.height, src.info.channels, VTS_SAMPLE_U8,
                       &err) != 0 ||
        vt_source_read(&src, 0, 0, &img, &err) != 0)
        die(path, &err);
    vt_source_close(&src);
    uint32_t w = (img.width + 3) & ~3u, h = (img.height + 3) & ~3u;
    struct rgb out = {w, h, xmalloc((size_t)w * h * 3)};
    for (uint32_t y = 0; y < h; y++)
        for (uint32_t x = 0; x < w; x++) {
            uint32_t sx = x < img.width ? x : img.width - 1,
                     sy = y < img.height ? y : img.height - 1;
            memcpy(out.px + ((size_t)y * w + x) * 3, vt_image_at(&img, sx, sy), 3);
        }
    *orig_w = img.width;
    *orig_h = img.height;
    vt_image_release(&img);
    return out;
}

static uint32_t carry_channels(enum carry c)
{
    return c == CARRY_XYZ3 ? 3 : c == CARRY_XY2 ? 2 : 4;
}

static void to_carrier(const struct rgb *n, enum carry c, struct vt_image *dst)
{
    uint32_t ch = carry_channels(c);
    *dst = (struct vt_image){
        n->w, n->h, ch, VTS_SAMPLE_U8, (size_t)n->w * ch, xmalloc((size_t)n->w * n->h * ch)};
    unsigned char *d = dst->pixels;
    for (size_t i = 0; i < (size_t)n->w * n->h; i++, d += ch) {
        const uint8_t *s = n->px + i * 3;
        switch (c) {
        case CARRY_XYZ3:
            memcpy(d, s, 3);
            break;
        case CARRY_XYZ4:
            memcpy(d, s, 3), d[3] = 255;
            break;
        case CARRY_DXT5NM:
            d[0] = 0, d[1] = s[1], d[2] = 0, d[3] = s[0];
            break;
        case CARRY_XY2:
            d[0] = s[0], d[1] = s[1];
            break;
        }
    }
}

/* The decoded carrier texel i as a normal (not made unit length) and its xyz as 8-bit values. */
static void from_carrier(const struct vt_image *dec, enum carry c, size_t i, double n[3], int v[3])
{
    const unsigned char *p = (const unsigned char *)dec->pixels + i * dec->channels;
    if (c == CARRY_XYZ3 || c == CARRY_XYZ4) {
        for (int k = 0; k < 3; k++)
            v[k] = p[k], n[k] = p[k] / 127.5 - 1.0;
        return;
    }
    v[0] = c == CARRY_DXT5NM ? p[3] : p[0];
    v[1] = p[1];
    n[0] = v[0] / 127.5 - 1.0;
    n[1] = v[1] / 127.5 - 1.0;
    double zz = 1.0 - n[0] * n[0] - n[1] * n[1];
    n[2] = zz > 0 ? sqrt(zz) : 0.0;
    v[2] = (int)floor((n[2] + 1.0) * 127.5 + 0.5);
}

/* Encodes the carrier (best of runs), decodes it; returns the decoded image and the seconds. */
static struct vt_image encode_decode(const struct variant *va, const struct vt_image *src, int runs,
                                     double *seconds)
{
    struct vt_image dec = {src->width,    src->height, src->channels,
                           VTS_SAMPLE_U8, src->stride, xmalloc(src->stride * src->height)};
    *seconds = 0;
    if (!va->codec) {
        memcpy(dec.pixels, src->pixels, src->stride * src->height);
        return dec;
    }
    const struct vt_codec *codec = vt_codec_find(va->codec);
    size_t cap = codec->encoded_bound(src->width, src->height, src->channels, src->sample), len;
    unsigned char *payload = xmalloc(cap);
    struct vt_codec_params params = {.effort = va->effort};
    struct vts_error err = {0};
    double best = INFINITY;
    for (int r = 0; r < runs; r++) {
        double t0 = cpu_s();
        if (codec->encode(src, &params, payload, cap, &len, &err) != 0)
            die(va->label, &err);
        double t = cpu_s() - t0;
        best = t < best ? t : best;
    }
    if (codec->decode(payload, len, &dec, &err) != 0)
        die(va->label, &err);
    free(payload);
    *seconds = best;
    return dec;
}

static double p99(const struct result *r)
{
    uint64_t want = r->count - r->count / 100, seen = 0;
    for (int b = 0; b < HIST_BINS; b++)
        if ((seen += r->hist[b]) >= want)
            return b * 0.01;
    return 180.0;
}

static double psnr(const struct result *r)
{
    return r->se > 0 ? 10.0 * log10(255.0 * 255.0 * r->samples / r->se) : 99.0;
}

static void print_row(FILE *md, FILE *tsv, const char *image, const struct variant *va,
                      const struct result *r)
{
    double mps = r->seconds > 0 ? r->texels / r->seconds / 1e6 : NAN;
    char speed[32] = "-";
    if (va->codec)
        snprintf(speed, sizeof speed, "%.1f", mps);
    fprintf(md, "| %s | %d | %.3f | %.2f | %.2f | %s |\n", va->label, va->bits,
            r->angle_sum / (double)r->count, p99(r), psnr(r), speed);
    if (tsv)
        fprintf(tsv, "%s\t%s\t%d\t%.4f\t%.3f\t%.3f\t%.3f\n", image, va->label, va->bits,
                r->angle_sum / (double)r->count, p99(r), psnr(r), va->codec ? mps : 0.0);
}

static void table_head(FILE *md)
{
    fprintf(md, "| encoding | bits per texel | mean angular error, degrees | 99th percentile, "
                "degrees | PSNR of xyz, dB | encode MP/s per core |\n"
                "|---|---:|---:|---:|---:|---:|\n");
}

static void bench_image(const char *path, int runs, FILE *md, FILE *tsv)
{
    uint32_t ow, oh;
    struct rgb n = load_padded(path, &ow, &oh);
    const char *name = strrchr(path, '/') ? strrchr(path, '/') + 1 : path;
    size_t texels = (size_t)n.w * n.h;
    /* the reference normals and which texels hold one */
    double *ref = xmalloc(texels * 3 * sizeof *ref);
    unsigned char *valid = xmalloc(texels);
    uint64_t nvalid = 0;
    for (size_t i = 0; i < texels; i++) {
        uint32_t x = (uint32_t)(i % n.w), y = (uint32_t)(i / n.w);
        double *r = ref + 3 * i, len = 0;
        for (int k = 0; k < 3; k++)
            r[k] = n.px[3 * i + k] / 127.5 - 1.0, len += r[k] * r[k];
        len = sqrt(len);
        valid[i] = x < ow && y < oh && len > 0.9 && len < 1.1 && r[2] >= 0;
        if (valid[i]) {
            for (int k = 0; k < 3; k++)
                r[k] /= len;
            nvalid++;
        }
    }
    fprintf(md, "\n#### %s (%ux%u, %llu texels hold a normal)\n\n", name, ow, oh,
            (unsigned long long)nvalid);
    table_head(md);
    for (size_t vi = 0; vi < N_VARIANTS; vi++) {
        const struct variant *va = &variants[vi];
        struct vt_image src, dec;
        to_carrier(&n, va->carry, &src);
        double seconds;
        dec = encode_decode(va, &src, runs, &seconds);
        struct result *r = calloc(1, sizeof *r);
        if (!r)
            die("result", NULL);
        for (size_t i = 0; i < texels; i++) {
            if (!valid[i])
                continue;
            double d[3], len = 0, dot = 0;
            int v[3];
            from_carrier(&dec, va->carry, i, d, v);
            for (int k = 0; k < 3; k++)
                len += d[k] * d[k];
            len = sqrt(len);
            for (int k = 0; k < 3; k++)
                dot += len > 0 ? ref[3 * i + k] * d[k] / len : 0;
            dot = dot > 1 ? 1 : dot < -1 ? -1 : dot;
            double angle = acos(dot) * (180.0 / 3.14159265358979323846);
            r->angle_sum += angle;
            r->hist[(int)(angle * 100.0 + 0.5)]++;
            r->count++;
            for (int k = 0; k < 3; k++) {
                double e = v[k] - n.px[3 * i + k];
                r->se += e * e;
            }
            r->samples += 3;
        }
        r->seconds = seconds;
        r->texels = (double)texels;
        print_row(md, tsv, name, va, r);
        struct result *t = &totals[vi];
        t->angle_sum += r->angle_sum;
        t->se += r->se;
        t->samples += r->samples;
        t->seconds += r->seconds;
        t->texels += r->texels;
        t->count += r->count;
        for (int b = 0; b < HIST_BINS; b++)
            t->hist[b] += r->hist[b];
        free(r);
        free(src.pixels);
        free(dec.pixels);
    }
    free(ref);
    free(valid);
    free(n.px);
}

int main(int argc, char **argv)
{
    bench_name = "vt-bench-normals";
    int runs = 3;
    const char *md_path = NULL, *tsv_path = NULL;
    static const struct option opts[] = {{"runs", required_argument, 0, 'r'},
                                         {"md", required_argument, 0, 'm'},
                                         {"tsv", required_argument, 0, 't'},
                                         {0, 0, 0, 0}};
    int c;
    while ((c = getopt_long(argc, argv, "", opts, NULL)) != -1) {
        if (c == 'r')
            runs = atoi(optarg);
        else if (c == 'm')
            md_path = optarg;
        else if (c == 't')
            tsv_path = optarg;
        else
            goto usage;
    }
    if (optind >= argc || runs < 1)
        goto usage;
    FILE *md = md_path ? fopen(md_path, "w") : stdout;
    FILE *tsv = tsv_path ? fopen(tsv_path, "w") : NULL;
    if (!md || (tsv_path && !tsv)) {
        perror("vt-bench-normals: cannot open an output");
        return 1;
    }
    for (int i = optind; i < argc; i++)
        bench_image(argv[i], runs, md, tsv);
    fprintf(md, "\n#### All %d images\n\n", argc - optind);
    table_head(md);
    for (size_t vi = 0; vi < N_VARIANTS; vi++)
        print_row(md, tsv, "all", &variants[vi], &totals[vi]);
    if (md != stdout)
        fclose(md);
    if (tsv)
        fclose(tsv);
    return 0;
usage:
    fprintf(stderr, "usage: vt-bench-normals [--runs N] [--md OUT.md] [--tsv OUT.tsv] IMAGE...\n");
    return 2;
}
