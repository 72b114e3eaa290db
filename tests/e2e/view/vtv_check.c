/* Test helper for vt-view: compares screenshots and reads statistics.
 *   vtv_check psnr A.png B.png --min DB | --max DB   PSNR over RGB (prints it); a B K times as
 *                                                     wide and high as A (a supersampled
 *                                                     reference) is first box-averaged K x K in
 *                                                     linear light (sRGB frames)
 *   vtv_check stat S.json KEY OP VALUE               KEY in "last" (OP: == != < <= > >=)
 *   vtv_check frames-equal A.json B.json             the "frames" arrays are identical
 *   vtv_check dark A.png MAX                          at most MAX pixels with R+G+B < 24
 *   vtv_check diff A.png B.png OUT.png                |A - B| x 8 as a PNG (for failures), and
 *                                                     the count of pixels off by more than 8
 *   vtv_check maxdiff A.png B.png X Y W H --max N    the largest |A - B| over RGB in the crop
 *                                                     [X, X+W) x [Y, Y+H) (rows from the top,
 *                                                     clipped to the image) is at most N
 *   vtv_check mean A.png X Y W H --min V | --max V   the mean of (R + G + B) / 3 over the crop
 *                                                     (prints it)
 *   vtv_check ramp IMAGE MIN MAX RAMP OUT.png          the CPU reference of --range MIN:MAX
 *                                                     --ramp RAMP over a one-channel image
 *                                                     (u8/u16 normalised, floats as they are):
 *                                                     an RGB PNG of vtv_ramp_at((v - MIN) /
 *                                                     (MAX - MIN)), rounded; prints the
 *                                                     image's smallest and largest value
 *   vtv_check classes OUT.png N [u16]                 an N x N u8 land-class map (values 3, 7,
 *                                                     12, 40, 200: patches, 1-texel roads of
 *                                                     200, single-texel specks of 40); u16: the
 *                                                     same map as u16 with 40000 for 40 and
 *                                                     65535 for 200
 *   vtv_check palette A.png grey|index|index16 --max K | --min K  pixels whose RGB is not the
 *                                                     colour of one of those classes (grey: v,
 *                                                     v, v; index: vtv_index_colour; index16:
 *                                                     that of the u16 classes) nor the background
 *                                                     (26, 26, 26) number at most (at least) K
 *                                                     (prints the count)
 * Exit 0 when the check holds, 1 when it does not, 2 on bad use or unreadable files. */
#include <jansson.h>
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vt_filter.h"
#include "vt_image_input.h"
#include "vt_png_file.h"
#include "vtv_ramp.h"
#include "vtv_select.h"

static int load(const char *path, struct vt_image *img)
{
    struct vts_error err = {0};
    if (vt_png_file_read(path, img, &err) != 0) {
        fprintf(stderr, "vtv_check: %s\n", err.message);
        return -1;
    }
    return 0;
}

static double srgb_to_linear(double v)
{
    return v <= 0.04045 ? v / 12.92 : pow((v + 0.055) / 1.055, 2.4);
}

static double linear_to_srgb(double v)
{
    return v <= 0.0031308 ? v * 12.92 : 1.055 * pow(v, 1 / 2.4) - 0.055;
}

/* Pixel (x, y) channel c of b seen at a's size: b's K x K block averaged in linear light. */
static double sample_down(const struct vt_image *b, uint32_t k, uint32_t x, uint32_t y, int c)
{
    if (k == 1)
        return ((const uint8_t *)vt_image_at(b, x, y))[c];
    double s = 0;
    for (uint32_t j = 0; j < k; j++)
        for (uint32_t i = 0; i < k; i++)
            s += srgb_to_linear(((const uint8_t *)vt_image_at(b, x * k + i, y * k + j))[c] / 255.0);
    return floor(linear_to_srgb(s / ((double)k * k)) * 255.0 + 0.5);
}

static int psnr(int argc, char **argv)
{
    if (argc != 6)
        return 2;
    struct vt_image a = {0}, b = {0};
    if (load(argv[2], &a) || load(argv[3], &b))
        return 2;
    uint32_t k = a.width ? b.width / a.width : 0;
    if (k == 0 || b.width != a.width * k || b.height != a.height * k || a.channels < 3 ||
        b.channels < 3) {
        fprintf(stderr, "vtv_check: images differ in size or channels\n");
        return 2;
    }
    double se = 0;
    for (uint32_t y = 0; y < a.height; y++)
        for (uint32_t x = 0; x < a.width; x++) {
            const uint8_t *p = vt_image_at(&a, x, y);
            for (int c = 0; c < 3; c++) {
                double d = p[c] - sample_down(&b, k, x, y, c);
                se += d * d;
            }
        }
    double mse = se / ((double)a.width * a.height * 3);
    double db = mse > 0 ? 10 * log10(255.0 * 255.0 / mse) : 99.0;
    double limit = atof(argv[5]);
    printf("PSNR %.2f dB (%s %s %.2f)\n", db, argv[4],
           strcmp(argv[4], "--min") ? "<" : ">=", limit);
    vt_image_release(&a);
    vt_image_release(&b);
    if (!strcmp(argv[4], "--min"))
        return db >= limit ? 0 : 1;
    if (!strcmp(argv[4], "--max"))
        return db < limit ? 0 : 1;
    return 2;
}

static json_t *load_json(const char *path)
{
    json_error_t e;
    json_t *j = json_load_file(path, 0, &e);
    if (!j)
        fprintf(stderr, "vtv_check: %s: %s (line %d)\n", path, e.text, e.line);
    return j;
}

static int check_stat(int argc, char **argv)
{
    if (argc != 6)
        return 2;
    json_t *j = load_json(argv[2]);
    json_t *v = j ? json_object_get(json_object_get(j, "last"), argv[3]) : NULL;
    if (!v || !json_is_integer(v)) {
        fprintf(stderr, "vtv_check: no integer last.%s in %s\n", argv[3], argv[2]);
        json_decref(j);
        return 2;
    }
    long long x = json_integer_value(v), y = atoll(argv[5]);
    const char *op = argv[4];
    int ok = !strcmp(op, "==")   ? x == y
             : !strcmp(op, "!=") ? x != y
             : !strcmp(op, "<")  ? x < y
             : !strcmp(op, "<=") ? x <= y
             : !strcmp(op, ">")  ? x > y
             : !strcmp(op, ">=") ? x >= y
                                 : -1;
    printf("last.%s = %lld (%s %lld)\n", argv[3], x, op, y);
    json_decref(j);
    return ok < 0 ? 2 : ok ? 0 : 1;
}

static int frames_equal(int argc, char **argv)
{
    if (argc != 4)
        return 2;
    json_t *a = load_json(argv[2]), *b = load_json(argv[3]);
    if (!a || !b)
        return 2;
    json_t *fa = json_object_get(a, "frames"), *fb = json_object_get(b, "frames");
    int ok = fa && fb && json_array_size(fa) > 0 && json_equal(fa, fb);
    printf("frames %s (%zu frames)\n", ok ? "identical" : "differ", json_array_size(fa));
    json_decref(a);
    json_decref(b);
    return ok ? 0 : 1;
}

static int dark(int argc, char **argv)
{
    if (argc != 4)
        return 2;
    struct vt_image a = {0};
    if (load(argv[2], &a))
        return 2;
    long n = 0;
    for (uint32_t y = 0; y < a.height; y++)
        for (uint32_t x = 0; x < a.width; x++) {
            const uint8_t *p = vt_image_at(&a, x, y);
            n += p[0] + p[1] + p[2] < 24;
        }
    vt_image_release(&a);
    printf("%ld dark pixels (max %s)\n", n, argv[3]);
    return n <= atol(argv[3]) ? 0 : 1;
}

static int diff(int argc, char **argv)
{
    if (argc != 5)
        return 2;
    struct vt_image a = {0}, b = {0};
    struct vts_error err = {0};
    if (load(argv[2], &a) || load(argv[3], &b))
        return 2;
    if (a.width != b.width || a.height != b.height || a.channels < 3 || b.channels < 3)
        return 2;
    uint8_t *out = malloc((size_t)a.width * a.height * 3);
    long n = 0;
    for (uint32_t y = 0; out && y < a.height; y++)
        for (uint32_t x = 0; x < a.width; x++) {
            const uint8_t *p = vt_image_at(&a, x, y), *q = vt_image_at(&b, x, y);
            int big = 0;
            for (int c = 0; c < 3; c++) {
                int d = abs(p[c] - q[c]);
                big |= d > 8;
                out[((size_t)y * a.width + x) * 3 + c] = (uint8_t)(d * 8 > 255 ? 255 : d * 8);
            }
            n += big;
        }
    struct vt_png_file_writer *w =
        out ? vt_png_file_writer_create(argv[4], a.width, a.height, 3, 8, &err) : NULL;
    int st = w ? vt_png_file_writer_rows(w, out, a.height, (size_t)a.width * 3, &err) : -1;
    if (st == 0)
        st = vt_png_file_writer_finish(w, &err);
    vt_png_file_writer_destroy(w);
    free(out);
    vt_image_release(&a);
    vt_image_release(&b);
    printf("%ld pixels differ by more than 8\n", n);
    return st == 0 ? 0 : 2;
}

static int maxdiff(int argc, char **argv)
{
    if (argc != 10 || strcmp(argv[8], "--max"))
        return 2;
    struct vt_image a = {0}, b = {0};
    if (load(argv[2], &a) || load(argv[3], &b))
        return 2;
    if (a.width != b.width || a.height != b.height || a.channels < 3 || b.channels < 3) {
        fprintf(stderr, "vtv_check: images differ in size or channels\n");
        return 2;
    }
    long x0 = atol(argv[4]), y0 = atol(argv[5]);
    long x1 = x0 + atol(argv[6]), y1 = y0 + atol(argv[7]), limit = atol(argv[9]);
    x0 = x0 < 0 ? 0 : x0;
    y0 = y0 < 0 ? 0 : y0;
    x1 = x1 > (long)a.width ? (long)a.width : x1;
    y1 = y1 > (long)a.height ? (long)a.height : y1;
    int worst = 0;
    long wx = -1, wy = -1, over = 0;
    for (long y = y0; y < y1; y++)
        for (long x = x0; x < x1; x++) {
            const uint8_t *p = vt_image_at(&a, (uint32_t)x, (uint32_t)y);
            const uint8_t *q = vt_image_at(&b, (uint32_t)x, (uint32_t)y);
            int d = 0;
            for (int c = 0; c < 3; c++)
                d = abs(p[c] - q[c]) > d ? abs(p[c] - q[c]) : d;
            over += d > limit;
            if (d > worst) {
                worst = d;
                wx = x;
                wy = y;
            }
        }
    vt_image_release(&a);
    vt_image_release(&b);
    if (x0 >= x1 || y0 >= y1) {
        fprintf(stderr, "vtv_check: empty crop\n");
        return 2;
    }
    printf(
        "max difference %d at %ld,%ld in [%ld,%ld) x [%ld,%ld), %ld pixels above %ld (max %ld)\n",
        worst, wx, wy, x0, x1, y0, y1, over, limit, limit);
    return worst <= limit ? 0 : 1;
}

static int mean(int argc, char **argv)
{
    if (argc != 9 || (strcmp(argv[7], "--min") && strcmp(argv[7], "--max")))
        return 2;
    struct vt_image a = {0};
    if (load(argv[2], &a))
        return 2;
    long x0 = atol(argv[3]), y0 = atol(argv[4]);
    long x1 = x0 + atol(argv[5]), y1 = y0 + atol(argv[6]);
    if (a.channels < 3 || x0 < 0 || y0 < 0 || x1 > (long)a.width || y1 > (long)a.height ||
        x0 >= x1 || y0 >= y1) {
        fprintf(stderr, "vtv_check: bad crop or image\n");
        vt_image_release(&a);
        return 2;
    }
    double sum = 0;
    for (long y = y0; y < y1; y++)
        for (long x = x0; x < x1; x++) {
            const uint8_t *p = vt_image_at(&a, (uint32_t)x, (uint32_t)y);
            sum += (p[0] + p[1] + p[2]) / 3.0;
        }
    vt_image_release(&a);
    double m = sum / (double)((x1 - x0) * (y1 - y0)), limit = atof(argv[8]);
    bool min = !strcmp(argv[7], "--min");
    printf("mean %.2f (%s %s %.2f)\n", m, argv[7], min ? ">=" : "<=", limit);
    return (min ? m >= limit : m <= limit) ? 0 : 1;
}

static int ramp(int argc, char **argv)
{
    enum vtv_ramp_kind k;
    if (argc != 7 || !vtv_ramp_parse(argv[5], &k))
        return 2;
    double lo = atof(argv[3]), hi = atof(argv[4]);
    struct vts_error err = {0};
    struct vt_source src = {0};
    struct vt_image img = {0}, out = {0};
    struct vt_png_file_writer *w = NULL;
    int rc = vt_image_input_open(argv[2], NULL, &src, &err) ? 2 : 0;
    if (rc == 0 && src.info.channels != 1) {
        fprintf(stderr, "vtv_check: %s: %u channels, not 1\n", argv[2], src.info.channels);
        rc = 2;
    }
    if (rc == 0 &&
        (vt_image_alloc(&img, src.info.width, src.info.height, 1, src.info.sample, &err) ||
         vt_source_read(&src, 0, 0, &img, &err) ||
         vt_image_alloc(&out, src.info.width, src.info.height, 3, VTS_SAMPLE_U8, &err)))
        rc = 2;
    struct vt_pixel_mode plain = {1, VTS_COLOUR_DATA, false};
    float vmin = INFINITY, vmax = -INFINITY;
    for (uint32_t y = 0; rc == 0 && y < img.height; y++)
        for (uint32_t x = 0; x < img.width; x++) {
            float v, rgb[3];
            vt_filter_to_working(&plain, img.sample, vt_image_at(&img, x, y), &v, 1);
            vmin = v < vmin ? v : vmin;
            vmax = v > vmax ? v : vmax;
            vtv_ramp_at(k, (float)((v - lo) / (hi - lo)), rgb);
            uint8_t *o = vt_image_at(&out, x, y);
            for (int c = 0; c < 3; c++)
                o[c] = (uint8_t)lround(rgb[c] * 255.0);
        }
    if (rc == 0 && (!(w = vt_png_file_writer_create(argv[6], out.width, out.height, 3, 8, &err)) ||
                    vt_png_file_writer_rows(w, out.pixels, out.height, out.stride, &err) ||
                    vt_png_file_writer_finish(w, &err)))
        rc = 2;
    if (rc)
        fprintf(stderr, "vtv_check: %s\n", err.message);
    else
        printf("min %.9g max %.9g\n", (double)vmin, (double)vmax);
    vt_png_file_writer_destroy(w);
    vt_source_close(&src);
    vt_image_release(&img);
    vt_image_release(&out);
    return rc;
}

static const uint8_t classes[] = {3, 7, 12, 40, 200};
static const uint16_t classes16[] = {3, 7, 12, 40000, 65535}; /* the u16 map's */

/* Land classes in irregular patches (one class per 17 x 13 cell of a hashed grid), crossed by
 * 1-texel roads (200) every 37 rows and 29 columns, with single-texel specks (40) every 11th
 * texel of some rows: thin features that any filtering mixes with their neighbours. */
static int make_classes(int argc, char **argv)
{
    bool u16 = argc == 5 && !strcmp(argv[4], "u16");
    if (argc != 4 && !u16)
        return 2;
    uint32_t n = (uint32_t)atoi(argv[3]);
    struct vts_error err = {0};
    struct vt_image img = {0};
    struct vt_png_file_writer *w = NULL;
    if (n < 8 || n > 8192 ||
        vt_image_alloc(&img, n, n, 1, u16 ? VTS_SAMPLE_U16 : VTS_SAMPLE_U8, &err))
        return 2;
    for (uint32_t y = 0; y < n; y++)
        for (uint32_t x = 0; x < n; x++) {
            uint32_t h = (x / 17) * 0x9E3779B1u ^ (y / 13) * 0x85EBCA77u;
            h ^= h >> 13;
            h *= 0xC2B2AE3Du;
            h ^= h >> 16;
            size_t c = h % 3;
            if (x % 29 == 5 || y % 37 == 9)
                c = 4;
            else if (y % 7 == 3 && x % 11 == 2)
                c = 3;
            if (u16)
                *(uint16_t *)vt_image_at(&img, x, y) = classes16[c];
            else
                *(uint8_t *)vt_image_at(&img, x, y) = classes[c];
        }
    int rc = 0;
    if (!(w = vt_png_file_writer_create(argv[2], n, n, 1, u16 ? 16 : 8, &err)) ||
        vt_png_file_writer_rows(w, img.pixels, n, img.stride, &err) ||
        vt_png_file_writer_finish(w, &err)) {
        fprintf(stderr, "vtv_check: %s\n", err.message);
        rc = 2;
    }
    vt_png_file_writer_destroy(w);
    vt_image_release(&img);
    return rc;
}

static int palette(int argc, char **argv)
{
    struct vt_image a = {0};
    bool index16 = argc == 6 && !strcmp(argv[3], "index16");
    bool index = index16 || (argc == 6 && !strcmp(argv[3], "index"));
    if (argc != 6 || (!index && strcmp(argv[3], "grey")) ||
        (strcmp(argv[4], "--max") && strcmp(argv[4], "--min")) || load(argv[2], &a))
        return 2;
    uint8_t colour[sizeof(classes)][3];
    for (size_t i = 0; i < sizeof(classes); i++) {
        if (index)
            vtv_index_colour(index16 ? classes16[i] : classes[i], colour[i]);
        else
            memset(colour[i], classes[i], 3);
    }
    uint64_t off = 0;
    unsigned seen = 0, classes_seen = 0;
    for (uint32_t y = 0; y < a.height; y++)
        for (uint32_t x = 0; x < a.width; x++) {
            const uint8_t *p = vt_image_at(&a, x, y);
            bool found = p[0] == 26 && p[1] == 26 && p[2] == 26; /* the background, 0.1 grey */
            for (size_t i = 0; i < sizeof(classes) && !found; i++)
                if (!memcmp(p, colour[i], 3)) {
                    found = true;
                    seen |= 1u << i;
                }
            off += !found;
        }
    for (size_t i = 0; i < sizeof(classes); i++)
        classes_seen += (seen >> i) & 1;
    uint64_t k = strtoull(argv[5], NULL, 10);
    printf("%s: %llu of %u pixels not a class colour; %u of %zu classes seen\n", argv[2],
           (unsigned long long)off, a.width * a.height, classes_seen, sizeof(classes));
    vt_image_release(&a);
    if (strcmp(argv[4], "--max") == 0) /* a frame without the map (all background) fails too */
        return off > k || classes_seen < 3;
    return off < k;
}

int main(int argc, char **argv)
{
    if (argc < 2)
        return 2;
    if (!strcmp(argv[1], "psnr"))
        return psnr(argc, argv);
    if (!strcmp(argv[1], "stat"))
        return check_stat(argc, argv);
    if (!strcmp(argv[1], "frames-equal"))
        return frames_equal(argc, argv);
    if (!strcmp(argv[1], "dark"))
        return dark(argc, argv);
    if (!strcmp(argv[1], "diff"))
        return diff(argc, argv);
    if (!strcmp(argv[1], "maxdiff"))
        return maxdiff(argc, argv);
    if (!strcmp(argv[1], "mean"))
        return mean(argc, argv);
    if (!strcmp(argv[1], "ramp"))
        return ramp(argc, argv);
    if (!strcmp(argv[1], "classes"))
        return make_classes(argc, argv);
    if (!strcmp(argv[1], "palette"))
        return palette(argc, argv);
    return 2;
}
