/* The writer of vt-synth-scene's scenes (vt_synth_scene.h). */
#include "vt_synth_scene.h"

#include <errno.h>
#include <png.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

_Noreturn void vt_synth_scene_die(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    fputs("vt-synth-scene: ", stderr);
    vfprintf(stderr, fmt, ap);
    fputc('\n', stderr);
    va_end(ap);
    exit(1);
}

uint64_t vt_synth_scene_rng_next(struct vt_synth_scene_rng *r)
{
    uint64_t z = (r->state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

double vt_synth_scene_rng_unit(struct vt_synth_scene_rng *r)
{
    return (double)(vt_synth_scene_rng_next(r) >> 11) * 0x1p-53;
}

uint32_t vt_synth_scene_rng_below(struct vt_synth_scene_rng *r, uint32_t n)
{
    return (uint32_t)(vt_synth_scene_rng_next(r) % n);
}

void vt_synth_scene_mkdirs(const char *path)
{
    char buf[4096];
    size_t n = strlen(path);
    if (n >= sizeof buf)
        vt_synth_scene_die("path too long: '%s'", path);
    memcpy(buf, path, n + 1);
    for (size_t i = 1; i <= n; i++) {
        if (buf[i] != '/' && buf[i] != '\0')
            continue;
        char c = buf[i];
        buf[i] = '\0';
        if (mkdir(buf, 0777) != 0 && errno != EEXIST)
            vt_synth_scene_die("cannot create '%s': %s", buf, strerror(errno));
        buf[i] = c;
    }
}

/* dir + "/" + rel into out; exits when it does not fit. */
static void join(char *out, size_t size, const char *dir, const char *rel)
{
    int n = snprintf(out, size, "%s/%s", dir, rel);
    if (n < 0 || (size_t)n >= size)
        vt_synth_scene_die("path too long: '%s/%s'", dir, rel);
}

/* The directory part of path (without the last '/'), or "." */
static void dirname_of(char *out, size_t size, const char *path)
{
    const char *slash = strrchr(path, '/');
    if (!slash) {
        snprintf(out, size, ".");
        return;
    }
    size_t n = (size_t)(slash - path);
    if (n >= size)
        vt_synth_scene_die("path too long: '%s'", path);
    memcpy(out, path, n);
    out[n] = '\0';
}

static FILE *create(const char *path)
{
    char d[4096];
    dirname_of(d, sizeof d, path);
    vt_synth_scene_mkdirs(d);
    FILE *f = fopen(path, "wb");
    if (!f)
        vt_synth_scene_die("cannot create '%s': %s", path, strerror(errno));
    return f;
}

void vt_synth_scene_open(struct vt_synth_scene *s, const char *dir, const char *obj_name,
                         const char *mtl_path, const char *kind, uint64_t seed)
{
    char path[4096];
    memset(s, 0, sizeof *s);
    if (strlen(dir) >= sizeof s->dir)
        vt_synth_scene_die("path too long: '%s'", dir);
    strcpy(s->dir, dir);
    s->rng.state = seed * 0x2545f4914f6cdd1dull + 1;
    vt_synth_scene_mkdirs(dir);
    join(path, sizeof path, dir, obj_name);
    s->obj = create(path);
    join(path, sizeof path, dir, mtl_path);
    s->mtl = create(path);
    fprintf(s->obj, "# vt-synth-scene %s --seed %llu\nmtllib %s\n", kind, (unsigned long long)seed,
            mtl_path);
    fprintf(s->mtl, "# vt-synth-scene %s --seed %llu\n", kind, (unsigned long long)seed);
}

void vt_synth_scene_close(struct vt_synth_scene *s)
{
    int bad = ferror(s->obj) | ferror(s->mtl);
    bad |= fclose(s->obj) != 0;
    bad |= fclose(s->mtl) != 0;
    if (bad)
        vt_synth_scene_die("cannot write the scene in '%s'", s->dir);
}

void vt_synth_scene_obj(struct vt_synth_scene *s, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vfprintf(s->obj, fmt, ap);
    va_end(ap);
}

void vt_synth_scene_mtl(struct vt_synth_scene *s, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vfprintf(s->mtl, fmt, ap);
    va_end(ap);
}

uint32_t vt_synth_scene_v(struct vt_synth_scene *s, double x, double y, double z)
{
    fprintf(s->obj, "v %.9g %.9g %.9g\n", x, y, z);
    return ++s->v_count;
}

uint32_t vt_synth_scene_vt(struct vt_synth_scene *s, double u, double v)
{
    fprintf(s->obj, "vt %.9g %.9g\n", u, v);
    return ++s->vt_count;
}

uint32_t vt_synth_scene_vt3(struct vt_synth_scene *s, double u, double v, double w)
{
    fprintf(s->obj, "vt %.9g %.9g %.9g\n", u, v, w);
    return ++s->vt_count;
}

uint32_t vt_synth_scene_vn(struct vt_synth_scene *s, double x, double y, double z)
{
    fprintf(s->obj, "vn %.6f %.6f %.6f\n", x, y, z);
    return ++s->vn_count;
}

/* One index: positive as given, or relative to the count of lines of its kind. */
static long long index_text(const struct vt_synth_scene *s, uint32_t i, uint32_t count)
{
    return s->relative ? (long long)i - (long long)count - 1 : (long long)i;
}

void vt_synth_scene_face(struct vt_synth_scene *s, uint32_t n, const uint32_t *v,
                         const uint32_t *vt, const uint32_t *vn)
{
    fputc('f', s->obj);
    for (uint32_t i = 0; i < n; i++) {
        fprintf(s->obj, " %lld", index_text(s, v[i], s->v_count));
        if (vt)
            fprintf(s->obj, "/%lld", index_text(s, vt[i], s->vt_count));
        if (vn)
            fprintf(s->obj, "%s/%lld", vt ? "" : "/", index_text(s, vn[i], s->vn_count));
    }
    fputc('\n', s->obj);
    s->face_count++;
}

uint8_t *vt_synth_scene_noise8(struct vt_synth_scene *s, uint32_t width, uint32_t height,
                               uint32_t channels)
{
    size_t n = (size_t)width * height * channels;
    uint8_t *p = malloc(n);
    if (!p)
        vt_synth_scene_die("out of memory");
    for (size_t i = 0; i < n; i++)
        p[i] = (uint8_t)(vt_synth_scene_rng_next(&s->rng) >> 56);
    return p;
}

/* ---- PNG (libpng's longjmp stays in this part) ---- */

struct png_run {
    FILE *file;
    png_structp png;
    png_infop info;
    const struct vt_synth_scene_png *in;
    png_bytep row;
};

/* Packs row y of the input into r->row as PNG wants it (big-endian 16 bits, packed 4-bit
 * indices). */
static void png_pack_row(struct png_run *r, uint32_t y)
{
    const struct vt_synth_scene_png *in = r->in;
    if (in->palette) {
        const uint8_t *src = (const uint8_t *)in->pixels + (size_t)y * in->width;
        if (in->bits == 8) {
            memcpy(r->row, src, in->width);
            return;
        }
        memset(r->row, 0, (in->width + 1) / 2);
        for (uint32_t x = 0; x < in->width; x++)
            r->row[x / 2] |= (png_byte)((src[x] & 15) << (x % 2 ? 0 : 4));
        return;
    }
    size_t n = (size_t)in->width * in->channels;
    if (in->bits == 8) {
        memcpy(r->row, (const uint8_t *)in->pixels + (size_t)y * n, n);
        return;
    }
    const uint16_t *src = (const uint16_t *)in->pixels + (size_t)y * n;
    for (size_t i = 0; i < n; i++) {
        r->row[2 * i] = (png_byte)(src[i] >> 8);
        r->row[2 * i + 1] = (png_byte)(src[i] & 255);
    }
}

static int png_run_write(struct png_run *r)
{
    static const int types[] = {PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA, PNG_COLOR_TYPE_RGB,
                                PNG_COLOR_TYPE_RGB_ALPHA};
    const struct vt_synth_scene_png *in = r->in;
    if (setjmp(png_jmpbuf(r->png)))
        return -1;
    png_init_io(r->png, r->file);
    png_set_IHDR(r->png, r->info, in->width, in->height, (int)in->bits,
                 in->palette ? PNG_COLOR_TYPE_PALETTE : types[in->channels - 1], PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_BASE, PNG_FILTER_TYPE_BASE);
    if (in->palette) {
        png_color colours[256];
        for (uint32_t i = 0; i < in->palette_size; i++) {
            colours[i].red = in->palette[3 * i];
            colours[i].green = in->palette[3 * i + 1];
            colours[i].blue = in->palette[3 * i + 2];
        }
        png_set_PLTE(r->png, r->info, colours, (int)in->palette_size);
        if (in->trns)
            png_set_tRNS(r->png, r->info, in->trns, (int)in->palette_size, NULL);
    }
    png_write_info(r->png, r->info);
    for (uint32_t y = 0; y < in->height; y++) {
        png_pack_row(r, y);
        png_write_row(r->png, r->row);
    }
    png_write_end(r->png, NULL);
    return 0;
}

void vt_synth_scene_write_png(struct vt_synth_scene *s, const char *rel,
                              const struct vt_synth_scene_png *png)
{
    char path[4096];
    join(path, sizeof path, s->dir, rel);
    if (png->channels < 1 || png->channels > 4 ||
        (png->bits != 8 && png->bits != 16 && !(png->palette && png->bits == 4)))
        vt_synth_scene_die("'%s': bad PNG parameters", path);
    struct png_run r = {create(path), NULL, NULL, png, NULL};
    r.row = malloc((size_t)png->width * png->channels * 2 + 1);
    r.png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    r.info = r.png ? png_create_info_struct(r.png) : NULL;
    int rc = r.info && r.row ? png_run_write(&r) : -1;
    png_destroy_write_struct(&r.png, &r.info);
    free(r.row);
    if (fclose(r.file) != 0 || rc < 0)
        vt_synth_scene_die("cannot write '%s'", path);
}
