/* Image-file generators for tests (see vt_synth_images.h). Test code: simple over fast. */
#include "vt_synth_images.h"

#include <errno.h>
#include <math.h>
#include <png.h>
#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <tiffio.h>

#include <jerror.h>
#include <jpeglib.h>

#include <OpenEXR/openexr.h>

#include "vt_error.h"
#include "vts.h"

/* ---- the pattern ---- */

static uint32_t synth_hash(uint32_t seed, uint32_t x, uint32_t y, uint32_t c)
{
    uint64_t h = (uint64_t)seed * 0x9e3779b97f4a7c15ull ^ ((uint64_t)x << 32 | y) ^
                 (uint64_t)c * 0xd6e8feb86659fd93ull;
    h ^= h >> 30;
    h *= 0xbf58476d1ce4e5b9ull;
    h ^= h >> 27;
    h *= 0x94d049bb133111ebull;
    h ^= h >> 31;
    return (uint32_t)h;
}

static uint32_t synth_bits(const struct vt_synth_image_options *o)
{
    return o->bits ? o->bits : 8;
}

/* Palette size: 2^bits, except 200 colours at 8 bits (a palette shorter than the index range). */
static uint32_t synth_colours(const struct vt_synth_image_options *o)
{
    return synth_bits(o) == 8 ? 200 : 1u << synth_bits(o);
}

/* Palette entry i, channel c (3 = alpha from tRNS: only the first half of the entries have one). */
static uint8_t synth_palette(const struct vt_synth_image_options *o, uint32_t i, uint32_t c)
{
    if (c == 3 && i >= (synth_colours(o) + 1) / 2)
        return 255;
    return (uint8_t)synth_hash(o->seed ^ 0x5a5a5a5au, i, 7, c);
}

/* The stored integer of a low-bit grey or palette index texel. */
static uint32_t synth_index(const struct vt_synth_image_options *o, uint32_t x, uint32_t y)
{
    uint32_t h = synth_hash(o->seed, x, y, 0);
    return o->palette ? h % synth_colours(o) : h & ((1u << synth_bits(o)) - 1);
}

static uint16_t synth_half(uint32_t h)
{
    uint32_t sign = (h >> 31) & 1, exponent = 10 + (h >> 16) % 11, mantissa = h & 0x3ff;
    return (uint16_t)(sign << 15 | exponent << 10 | mantissa);
}

static float synth_float(uint32_t h)
{
    return (float)(h & 0xffffff) / 2097152.0f - 2.0f;
}

/* Alpha in 0..1 of texel (x, y) for a shaped alpha channel. */
static double synth_alpha(const struct vt_synth_image_options *o, uint32_t x, uint32_t y)
{
    double cx = o->width / 2.0, cy = o->height / 2.0;
    double r = 0.4 * (o->width < o->height ? o->width : o->height);
    double dx = x + 0.5 - cx, dy = y + 0.5 - cy, d = sqrt(dx * dx + dy * dy);
    switch (o->alpha_shape) {
    case VT_SYNTH_ALPHA_CUTOUT:
        return d < r - 0.5 ? 1 : d > r + 0.5 ? 0 : 0.5;
    case VT_SYNTH_ALPHA_SMOOTH:
        return (x + 0.5) / o->width;
    case VT_SYNTH_ALPHA_BINARY:
        return x < o->width / 2 ? 0 : 1;
    case VT_SYNTH_ALPHA_SPARSE:
        return x == 0 && y == 0 ? 0 : 1;
    default:
        return 1;
    }
}

/* Writes the expected sample of channel c of texel (x, y) at p. */
static void synth_sample(const struct vt_synth_image_options *o, uint32_t x, uint32_t y, uint32_t c,
                         unsigned char *p)
{
    if (o->alpha_shape && !o->palette && o->sample == VTS_SAMPLE_U8 &&
        (o->channels == 2 || o->channels == 4) && c == o->channels - 1) {
        *p = (uint8_t)lround(synth_alpha(o, x, y) * 255);
        return;
    }
    /* EXR: pairs of equal texels, so that ZIP chunks shrink: OpenEXRCore 3.1.5 writes a corrupt
     * chunk when ZIP makes it bigger (the readers decode such files as OpenImageIO does) */
    uint32_t h = synth_hash(o->seed, o->format == VT_SYNTH_EXR ? x / 2 : x, y, c);
    if (o->palette) {
        *p = synth_palette(o, synth_index(o, x, y), c);
    } else if (synth_bits(o) < 8) {
        uint32_t max = (1u << synth_bits(o)) - 1;
        *p = (uint8_t)(synth_index(o, x, y) * 255 / max);
    } else if (o->sample == VTS_SAMPLE_U8) {
        *p = (uint8_t)h;
    } else if (o->sample == VTS_SAMPLE_U16) {
        uint16_t v = (uint16_t)h;
        memcpy(p, &v, 2);
    } else if (o->sample == VTS_SAMPLE_F16) {
        uint16_t v = synth_half(h);
        memcpy(p, &v, 2);
    } else {
        float v = synth_float(h);
        memcpy(p, &v, 4);
    }
}

void vt_synth_image_expected(const struct vt_synth_image_options *o, uint32_t x, uint32_t y,
                             struct vt_image *dst)
{
    size_t sb = vts_sample_bytes(o->sample);
    for (uint32_t r = 0; r < dst->height; r++)
        for (uint32_t i = 0; i < dst->width; i++)
            for (uint32_t c = 0; c < o->channels; c++)
                synth_sample(o, x + i, y + r, c, (unsigned char *)vt_image_at(dst, i, r) + c * sb);
}

void vt_synth_image_defaults(struct vt_synth_image_options *o)
{
    memset(o, 0, sizeof *o);
    o->format = VT_SYNTH_TIFF;
    o->width = 97;
    o->height = 61;
    o->channels = 4;
    o->sample = VTS_SAMPLE_U8;
    o->seed = 1;
    o->rows_per_strip = 16;
    o->compression = VT_SYNTH_TIFF_DEFLATE;
    o->quality = 90;
}

/* ---- TIFF ---- */

/* Packs n texels of row y from column x0 as stored: all channels (plane < 0) or one plane. */
static void synth_tiff_row(const struct vt_synth_image_options *o, uint32_t x0, uint32_t n,
                           uint32_t y, int plane, unsigned char *out)
{
    size_t sb = vts_sample_bytes(o->sample);
    if (o->palette || synth_bits(o) < 8) {
        uint32_t bits = synth_bits(o);
        for (uint32_t i = 0; i < n && x0 + i < o->width; i++) {
            uint32_t v = synth_index(o, x0 + i, y);
            if (o->min_is_white)
                v = (1u << bits) - 1 - v;
            uint32_t bit = i * bits;
            out[bit / 8] |= (uint8_t)(v << (8 - bits - bit % 8));
        }
        return;
    }
    uint32_t all = o->channels + o->extra_channels;
    uint32_t c0 = plane < 0 ? 0 : (uint32_t)plane, c1 = plane < 0 ? all : c0 + 1;
    size_t texel = (c1 - c0) * sb;
    for (uint32_t i = 0; i < n && x0 + i < o->width; i++) {
        for (uint32_t c = c0; c < c1; c++) {
            unsigned char *p = out + i * texel + (c - c0) * sb;
            synth_sample(o, x0 + i, y, c, p);
            if (o->min_is_white && c == 0) {
                if (sb == 1) {
                    *p = (uint8_t)(255 - *p);
                } else {
                    uint16_t v;
                    memcpy(&v, p, 2);
                    v = (uint16_t)(65535 - v);
                    memcpy(p, &v, 2);
                }
            }
        }
    }
}

static void synth_tiff_fields(TIFF *tif, const struct vt_synth_image_options *o)
{
    uint32_t bits =
        (o->palette || synth_bits(o) < 8) ? synth_bits(o) : 8 * vts_sample_bytes(o->sample);
    uint16_t spp = o->palette ? 1 : (uint16_t)(o->channels + o->extra_channels);
    TIFFSetField(tif, TIFFTAG_IMAGEWIDTH, o->width);
    TIFFSetField(tif, TIFFTAG_IMAGELENGTH, o->height);
    TIFFSetField(tif, TIFFTAG_SAMPLESPERPIXEL, spp);
    TIFFSetField(tif, TIFFTAG_BITSPERSAMPLE, bits);
    TIFFSetField(tif, TIFFTAG_SAMPLEFORMAT,
                 o->sample == VTS_SAMPLE_F16 || o->sample == VTS_SAMPLE_F32 ? SAMPLEFORMAT_IEEEFP
                                                                            : SAMPLEFORMAT_UINT);
    uint16_t photometric = o->palette         ? PHOTOMETRIC_PALETTE
                           : o->channels >= 3 ? PHOTOMETRIC_RGB
                           : o->min_is_white  ? PHOTOMETRIC_MINISWHITE
                                              : PHOTOMETRIC_MINISBLACK;
    TIFFSetField(tif, TIFFTAG_PHOTOMETRIC, photometric);
    TIFFSetField(tif, TIFFTAG_PLANARCONFIG,
                 o->separate_planes ? PLANARCONFIG_SEPARATE : PLANARCONFIG_CONTIG);
    TIFFSetField(tif, TIFFTAG_COMPRESSION, o->compression ? o->compression : COMPRESSION_NONE);
    uint16_t extra[8] = {0}; /* EXTRASAMPLE_UNSPECIFIED but for the alpha channel */
    uint16_t extra_count = (uint16_t)(spp - (o->channels >= 3 ? 3 : 1));
    if (!o->palette && (o->channels == 2 || o->channels == 4))
        extra[0] = EXTRASAMPLE_UNASSALPHA;
    if (!o->palette && extra_count > 0 && extra_count <= 8)
        TIFFSetField(tif, TIFFTAG_EXTRASAMPLES, extra_count, extra);
    if (o->palette) {
        uint16_t map[3][256];
        for (uint32_t i = 0; i < 256; i++)
            for (uint32_t c = 0; c < 3; c++)
                map[c][i] = (uint16_t)(i < synth_colours(o) ? synth_palette(o, i, c) * 257 : 0);
        TIFFSetField(tif, TIFFTAG_COLORMAP, map[0], map[1], map[2]);
    }
    if (o->tile_w) {
        TIFFSetField(tif, TIFFTAG_TILEWIDTH, o->tile_w);
        TIFFSetField(tif, TIFFTAG_TILELENGTH, o->tile_h);
    } else {
        TIFFSetField(tif, TIFFTAG_ROWSPERSTRIP, o->rows_per_strip ? o->rows_per_strip : 16);
    }
}

/* Writes every tile or strip of every plane. */
static int synth_tiff_pixels(TIFF *tif, const struct vt_synth_image_options *o)
{
    uint32_t planes = o->separate_planes && !o->palette ? o->channels + o->extra_channels : 1;
    uint32_t cw = o->tile_w ? o->tile_w : o->width;
    uint32_t ch = o->tile_w ? o->tile_h : (o->rows_per_strip ? o->rows_per_strip : 16);
    size_t row_bytes = (size_t)(o->tile_w ? TIFFTileRowSize64(tif) : TIFFScanlineSize64(tif));
    size_t chunk_bytes = row_bytes * ch;
    unsigned char *buf = malloc(chunk_bytes);
    if (!buf)
        return -1;
    int rc = 0;
    for (uint32_t s = 0; s < planes && rc == 0; s++) {
        for (uint32_t py = 0; py < o->height && rc == 0; py += ch) {
            for (uint32_t px = 0; px < o->width && rc == 0; px += cw) {
                uint32_t rows = o->tile_w || o->height - py >= ch ? ch : o->height - py;
                memset(buf, 0, chunk_bytes);
                for (uint32_t r = 0; r < rows && py + r < o->height; r++)
                    synth_tiff_row(o, px, cw, py + r, o->separate_planes ? (int)s : -1,
                                   buf + r * row_bytes);
                tmsize_t n = (tmsize_t)(rows * row_bytes);
                if (o->tile_w)
                    rc = TIFFWriteEncodedTile(tif, TIFFComputeTile(tif, px, py, 0, (uint16_t)s),
                                              buf, n) < 0;
                else
                    rc = TIFFWriteEncodedStrip(tif, TIFFComputeStrip(tif, py, (uint16_t)s), buf,
                                               n) < 0;
            }
        }
    }
    free(buf);
    return rc ? -1 : 0;
}

static int synth_write_tiff(const char *path, const struct vt_synth_image_options *o,
                            struct vts_error *err)
{
    TIFF *tif = TIFFOpen(path, o->bigtiff ? "w8" : "w");
    if (!tif)
        return vt_error_set(err, VTS_ERR_IO, "cannot create '%s'", path);
    synth_tiff_fields(tif, o);
    int rc = synth_tiff_pixels(tif, o);
    TIFFClose(tif);
    if (rc < 0)
        return vt_error_set(err, VTS_ERR_IO, "cannot write '%s'", path);
    return 0;
}

/* ---- PNG ---- */

struct synth_png {
    FILE *file;
    png_structp png;
    png_infop info;
    unsigned char *row;
};

static void synth_png_row(const struct vt_synth_image_options *o, uint32_t y, unsigned char *row)
{
    if (o->palette || synth_bits(o) < 8) {
        memset(row, 0, (o->width * synth_bits(o) + 7) / 8);
        synth_tiff_row(o, 0, o->width, y, -1, row); /* same packing: MSB first */
        return;
    }
    size_t sb = vts_sample_bytes(o->sample);
    for (uint32_t x = 0; x < o->width; x++) {
        for (uint32_t c = 0; c < o->channels; c++) {
            unsigned char *p = row + ((size_t)x * o->channels + c) * sb;
            synth_sample(o, x, y, c, p);
            if (sb == 2) { /* PNG is big-endian */
                unsigned char t = p[0];
                p[0] = p[1];
                p[1] = t;
            }
        }
    }
}

static void synth_png_header(struct synth_png *s, const struct vt_synth_image_options *o)
{
    static const int types[] = {PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA, PNG_COLOR_TYPE_RGB,
                                PNG_COLOR_TYPE_RGB_ALPHA};
    int bits = (o->palette || synth_bits(o) < 8) ? (int)synth_bits(o)
                                                 : 8 * (int)vts_sample_bytes(o->sample);
    png_set_IHDR(s->png, s->info, o->width, o->height, bits,
                 o->palette ? PNG_COLOR_TYPE_PALETTE : types[o->channels - 1],
                 o->interlaced ? PNG_INTERLACE_ADAM7 : PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_BASE, PNG_FILTER_TYPE_BASE);
    if (o->palette) {
        png_color colours[256];
        png_byte alpha[256];
        uint32_t n = synth_colours(o);
        for (uint32_t i = 0; i < n; i++) {
            colours[i].red = synth_palette(o, i, 0);
            colours[i].green = synth_palette(o, i, 1);
            colours[i].blue = synth_palette(o, i, 2);
            alpha[i] = synth_palette(o, i, 3);
        }
        png_set_PLTE(s->png, s->info, colours, (int)n);
        if (o->channels == 4)
            png_set_tRNS(s->png, s->info, alpha, (int)(n + 1) / 2, NULL);
    }
}

static int synth_png_run(struct synth_png *s, const struct vt_synth_image_options *o)
{
    if (setjmp(png_jmpbuf(s->png)))
        return -1;
    png_init_io(s->png, s->file);
    synth_png_header(s, o);
    png_write_info(s->png, s->info);
    int passes = o->interlaced ? png_set_interlace_handling(s->png) : 1;
    for (int p = 0; p < passes; p++)
        for (uint32_t y = 0; y < o->height; y++) {
            synth_png_row(o, y, s->row);
            png_write_row(s->png, s->row);
        }
    png_write_end(s->png, NULL);
    return 0;
}

static int synth_write_png(const char *path, const struct vt_synth_image_options *o,
                           struct vts_error *err)
{
    struct synth_png s = {0};
    s.file = fopen(path, "wb");
    if (!s.file)
        return vt_error_set(err, VTS_ERR_IO, "cannot create '%s': %s", path, strerror(errno));
    s.row = calloc((size_t)o->width * 8, 1);
    s.png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    s.info = s.png ? png_create_info_struct(s.png) : NULL;
    int rc = s.info && s.row ? synth_png_run(&s, o) : -1;
    png_destroy_write_struct(&s.png, &s.info);
    free(s.row);
    if (fclose(s.file) != 0 || rc < 0)
        return vt_error_set(err, VTS_ERR_IO, "cannot write '%s'", path);
    return 0;
}

/* ---- JPEG ---- */

struct synth_jpeg_error {
    struct jpeg_error_mgr mgr;
    jmp_buf jump;
};

static void synth_jpeg_error_exit(j_common_ptr cinfo)
{
    longjmp(((struct synth_jpeg_error *)cinfo->err)->jump, 1);
}

struct synth_jpeg {
    FILE *file;
    struct jpeg_compress_struct c;
    struct synth_jpeg_error jerr;
    unsigned char *row;
};

static int synth_jpeg_run(struct synth_jpeg *s, const struct vt_synth_image_options *o)
{
    if (setjmp(s->jerr.jump))
        return -1;
    jpeg_create_compress(&s->c);
    jpeg_stdio_dest(&s->c, s->file);
    s->c.image_width = o->width;
    s->c.image_height = o->height;
    s->c.input_components = (int)o->channels;
    s->c.in_color_space = o->channels == 1 ? JCS_GRAYSCALE : JCS_RGB;
    jpeg_set_defaults(&s->c);
    jpeg_set_quality(&s->c, (int)o->quality, TRUE);
    if (o->channels == 3) {
        s->c.comp_info[0].h_samp_factor = o->jpeg_420 ? 2 : 1;
        s->c.comp_info[0].v_samp_factor = o->jpeg_420 ? 2 : 1;
    }
    if (o->progressive)
        jpeg_simple_progression(&s->c);
    jpeg_start_compress(&s->c, TRUE);
    for (uint32_t y = 0; y < o->height; y++) {
        for (uint32_t x = 0; x < o->width; x++)
            for (uint32_t c = 0; c < o->channels; c++) /* smooth-ish content with noise */
                s->row[x * o->channels + c] =
                    (uint8_t)((x * 3 + y * 2 + c * 60) + (synth_hash(o->seed, x, y, c) & 31));
        JSAMPROW row = s->row;
        jpeg_write_scanlines(&s->c, &row, 1);
    }
    jpeg_finish_compress(&s->c);
    return 0;
}

static int synth_write_jpeg(const char *path, const struct vt_synth_image_options *o,
                            struct vts_error *err)
{
    if (o->channels != 1 && o->channels != 3)
        return vt_error_set(err, VTS_ERR_ARG, "JPEG needs 1 or 3 channels");
    struct synth_jpeg *s = calloc(1, sizeof *s);
    if (!s)
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
    s->file = fopen(path, "wb");
    s->row = malloc((size_t)o->width * o->channels);
    s->c.err = jpeg_std_error(&s->jerr.mgr);
    s->jerr.mgr.error_exit = synth_jpeg_error_exit;
    int rc = s->file && s->row ? synth_jpeg_run(s, o) : -1;
    jpeg_destroy_compress(&s->c);
    if (s->file && fclose(s->file) != 0)
        rc = -1;
    free(s->row);
    free(s);
    return rc < 0 ? vt_error_set(err, VTS_ERR_IO, "cannot write '%s'", path) : 0;
}

struct synth_jpeg_dec {
    FILE *file;
    struct jpeg_decompress_struct d;
    struct synth_jpeg_error jerr;
};

static int synth_jpeg_decode_run(struct synth_jpeg_dec *s, struct vt_image *out)
{
    if (setjmp(s->jerr.jump))
        return -1;
    jpeg_create_decompress(&s->d);
    jpeg_stdio_src(&s->d, s->file);
    jpeg_read_header(&s->d, TRUE);
    s->d.out_color_space = s->d.num_components == 1 ? JCS_GRAYSCALE : JCS_RGB;
    jpeg_start_decompress(&s->d);
    if (vt_image_alloc(out, s->d.output_width, s->d.output_height, (uint32_t)s->d.output_components,
                       VTS_SAMPLE_U8, NULL) < 0)
        return -1;
    while (s->d.output_scanline < s->d.output_height) {
        JSAMPROW row = vt_image_at(out, 0, s->d.output_scanline);
        jpeg_read_scanlines(&s->d, &row, 1);
    }
    jpeg_finish_decompress(&s->d);
    return 0;
}

int vt_synth_jpeg_decode(const char *path, struct vt_image *out, struct vts_error *err)
{
    memset(out, 0, sizeof *out);
    struct synth_jpeg_dec *s = calloc(1, sizeof *s);
    if (!s)
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
    s->file = fopen(path, "rb");
    s->d.err = jpeg_std_error(&s->jerr.mgr);
    s->jerr.mgr.error_exit = synth_jpeg_error_exit;
    int rc = s->file ? synth_jpeg_decode_run(s, out) : -1;
    jpeg_destroy_decompress(&s->d);
    if (s->file)
        fclose(s->file);
    free(s);
    if (rc < 0) {
        vt_image_release(out);
        return vt_error_set(err, VTS_ERR_BAD_INPUT, "cannot decode '%s'", path);
    }
    return 0;
}

/* ---- OpenEXR ---- */

#define SYNTH_EXR_MAX_CHANNELS 8

struct synth_exr {
    char names[SYNTH_EXR_MAX_CHANNELS][16];
    int out[SYNTH_EXR_MAX_CHANNELS]; /* output channel of each named channel, -1 = ignored */
    int count;
};

static int synth_exr_find(const struct synth_exr *e, const char *name)
{
    for (int i = 0; i < e->count; i++)
        if (strcmp(e->names[i], name) == 0)
            return i;
    return -1;
}

/* Parses the names and maps them to output channels as the reader does. */
static int synth_exr_channels(const struct vt_synth_image_options *o, struct synth_exr *e)
{
    static const char *defaults[] = {"Y", "Y,A", "R,G,B", "R,G,B,A"};
    const char *list = o->exr_channels ? o->exr_channels : defaults[o->channels - 1];
    memset(e, 0, sizeof *e);
    for (const char *p = list; *p && e->count < SYNTH_EXR_MAX_CHANNELS;) {
        size_t n = strcspn(p, ",");
        snprintf(e->names[e->count++], 16, "%.*s", (int)n, p);
        p += n + (p[n] == ',');
    }
    int r = synth_exr_find(e, "R"), g = synth_exr_find(e, "G"), b = synth_exr_find(e, "B");
    int y = synth_exr_find(e, "Y"), a = synth_exr_find(e, "A");
    int next = 0;
    for (int i = 0; i < e->count; i++)
        e->out[i] = -1;
    if (r >= 0 && g >= 0 && b >= 0) {
        e->out[r] = next++, e->out[g] = next++, e->out[b] = next++;
    } else if (y >= 0) {
        e->out[y] = next++;
    } else { /* all but A, in the file's (alphabetical) order */
        for (char first = 0x21; first < 0x7f; first++)
            for (int i = 0; i < e->count; i++)
                if (i != a && e->names[i][0] == first)
                    e->out[i] = next++;
    }
    if (a >= 0)
        e->out[a] = next++;
    return 0; /* next != channels: a file the reader refuses or reads differently */
}

/* Fills plane (w x h samples from texel (x0, y0)) with output channel c, or junk if c < 0. */
static void synth_exr_plane(const struct vt_synth_image_options *o, int c, uint32_t x0, uint32_t y0,
                            int32_t w, int32_t h, unsigned char *plane)
{
    size_t sb = vts_sample_bytes(o->sample);
    for (int32_t r = 0; r < h; r++)
        for (int32_t i = 0; i < w; i++) {
            unsigned char *p = plane + ((size_t)r * (size_t)w + (size_t)i) * sb;
            if (c >= 0) {
                synth_sample(o, x0 + (uint32_t)i, y0 + (uint32_t)r, (uint32_t)c, p);
            } else {
                struct vt_synth_image_options junk = *o;
                junk.seed ^= 0xdeadbeefu;
                synth_sample(&junk, x0 + (uint32_t)i, y0 + (uint32_t)r, 0, p);
            }
        }
}

/* Encodes one chunk whose texels start at (x0, y0). */
static exr_result_t synth_exr_chunk(exr_context_t ctx, const struct vt_synth_image_options *o,
                                    const struct synth_exr *e, exr_chunk_info_t *ci, uint32_t x0,
                                    uint32_t y0, exr_encode_pipeline_t *enc, bool *started,
                                    unsigned char *planes, size_t plane_bytes)
{
    exr_result_t rv =
        *started ? exr_encoding_update(ctx, 0, ci, enc) : exr_encoding_initialize(ctx, 0, ci, enc);
    if (rv != EXR_ERR_SUCCESS)
        return rv;
    *started = true;
    size_t sb = vts_sample_bytes(o->sample);
    for (int i = 0; i < enc->channel_count; i++) {
        exr_coding_channel_info_t *ch = &enc->channels[i];
        int k = synth_exr_find(e, ch->channel_name);
        unsigned char *plane = planes + (size_t)i * plane_bytes;
        synth_exr_plane(o, k >= 0 ? e->out[k] : -1, x0, y0, ci->width, ci->height, plane);
        ch->encode_from_ptr = plane;
        ch->user_pixel_stride = (int32_t)sb;
        ch->user_line_stride = (int32_t)(sb * (size_t)ci->width);
        ch->user_bytes_per_element = (int16_t)sb;
        ch->user_data_type = o->sample == VTS_SAMPLE_F16 ? EXR_PIXEL_HALF : EXR_PIXEL_FLOAT;
    }
    rv = exr_encoding_choose_default_routines(ctx, 0, enc);
    return rv == EXR_ERR_SUCCESS ? exr_encoding_run(ctx, 0, enc) : rv;
}

static exr_result_t synth_exr_header(exr_context_t ctx, const struct vt_synth_image_options *o,
                                     const struct synth_exr *e)
{
    int part;
    exr_result_t rv =
        exr_add_part(ctx, NULL, o->tile_w ? EXR_STORAGE_TILED : EXR_STORAGE_SCANLINE, &part);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_initialize_required_attr_simple(ctx, 0, (int32_t)o->width, (int32_t)o->height,
                                                 (exr_compression_t)o->compression);
    exr_attr_box2i_t dw;
    dw.min.x = o->exr_origin_x;
    dw.min.y = o->exr_origin_y;
    dw.max.x = o->exr_origin_x + (int32_t)o->width - 1;
    dw.max.y = o->exr_origin_y + (int32_t)o->height - 1;
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_set_data_window(ctx, 0, &dw);
    for (int i = 0; i < e->count && rv == EXR_ERR_SUCCESS; i++)
        rv = exr_add_channel(ctx, 0, e->names[i],
                             o->sample == VTS_SAMPLE_F16 ? EXR_PIXEL_HALF : EXR_PIXEL_FLOAT,
                             EXR_PERCEPTUALLY_LOGARITHMIC, 1, 1);
    if (rv == EXR_ERR_SUCCESS && o->tile_w)
        rv = exr_set_tile_descriptor(ctx, 0, o->tile_w, o->tile_h, EXR_TILE_ONE_LEVEL,
                                     EXR_TILE_ROUND_DOWN);
    return rv == EXR_ERR_SUCCESS ? exr_write_header(ctx) : rv;
}

static exr_result_t synth_exr_pixels(exr_context_t ctx, const struct vt_synth_image_options *o,
                                     const struct synth_exr *e)
{
    int32_t lines = 1;
    exr_result_t rv = o->tile_w ? EXR_ERR_SUCCESS : exr_get_scanlines_per_chunk(ctx, 0, &lines);
    if (rv != EXR_ERR_SUCCESS)
        return rv;
    uint32_t cw = o->tile_w ? o->tile_w : o->width, ch = o->tile_w ? o->tile_h : (uint32_t)lines;
    size_t plane_bytes = (size_t)cw * ch * vts_sample_bytes(o->sample);
    unsigned char *planes = malloc(plane_bytes * SYNTH_EXR_MAX_CHANNELS);
    if (!planes)
        return EXR_ERR_OUT_OF_MEMORY;
    exr_encode_pipeline_t enc = EXR_ENCODE_PIPELINE_INITIALIZER;
    bool started = false;
    for (uint32_t y = 0; y < o->height && rv == EXR_ERR_SUCCESS; y += ch) {
        for (uint32_t x = 0; x < o->width && rv == EXR_ERR_SUCCESS; x += cw) {
            exr_chunk_info_t ci;
            if (o->tile_w)
                rv = exr_write_tile_chunk_info(ctx, 0, (int)(x / cw), (int)(y / ch), 0, 0, &ci);
            else
                rv = exr_write_scanline_chunk_info(ctx, 0, o->exr_origin_y + (int)y, &ci);
            if (rv == EXR_ERR_SUCCESS)
                rv = synth_exr_chunk(ctx, o, e, &ci, x, y, &enc, &started, planes, plane_bytes);
        }
    }
    if (started)
        exr_encoding_destroy(ctx, &enc);
    free(planes);
    return rv;
}

static void synth_exr_quiet(exr_const_context_t ctx, exr_result_t code, const char *msg)
{
    (void)ctx, (void)code, (void)msg;
}

static int synth_write_exr(const char *path, const struct vt_synth_image_options *o,
                           struct vts_error *err)
{
    struct synth_exr e;
    if ((o->sample != VTS_SAMPLE_F16 && o->sample != VTS_SAMPLE_F32) ||
        synth_exr_channels(o, &e) < 0)
        return vt_error_set(err, VTS_ERR_ARG, "EXR channel names do not give %u channels",
                            o->channels);
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = synth_exr_quiet;
    exr_context_t ctx = NULL;
    exr_result_t rv = exr_start_write(&ctx, path, EXR_WRITE_FILE_DIRECTLY, &init);
    if (rv == EXR_ERR_SUCCESS)
        rv = synth_exr_header(ctx, o, &e);
    if (rv == EXR_ERR_SUCCESS)
        rv = synth_exr_pixels(ctx, o, &e);
    exr_result_t fin = ctx ? exr_finish(&ctx) : EXR_ERR_SUCCESS;
    if (rv != EXR_ERR_SUCCESS || fin != EXR_ERR_SUCCESS)
        return vt_error_set(err, VTS_ERR_IO, "cannot write '%s': %s", path,
                            exr_get_default_error_message(rv != EXR_ERR_SUCCESS ? rv : fin));
    return 0;
}

/* ---- TGA (uncompressed, top-left origin) ---- */

static int synth_write_tga(const char *path, const struct vt_synth_image_options *o,
                           struct vts_error *err)
{
    if (o->channels == 2 || o->sample != VTS_SAMPLE_U8)
        return vt_error_set(err, VTS_ERR_ARG, "TGA needs 1, 3 or 4 channels of 8 bits");
    FILE *f = fopen(path, "wb");
    if (!f)
        return vt_error_set(err, VTS_ERR_IO, "cannot create '%s': %s", path, strerror(errno));
    unsigned char h[18] = {0};
    h[2] = o->channels == 1 ? 3 : 2; /* uncompressed grey / true colour */
    h[12] = (unsigned char)o->width, h[13] = (unsigned char)(o->width >> 8);
    h[14] = (unsigned char)o->height, h[15] = (unsigned char)(o->height >> 8);
    h[16] = (unsigned char)(8 * o->channels);
    h[17] = (unsigned char)(0x20 | (o->channels == 4 ? 8 : 0)); /* top-left, alpha bits */
    fwrite(h, 1, sizeof h, f);
    for (uint32_t y = 0; y < o->height; y++)
        for (uint32_t x = 0; x < o->width; x++) {
            unsigned char t[4];
            for (uint32_t c = 0; c < o->channels; c++)
                synth_sample(o, x, y, c, &t[c]);
            if (o->channels >= 3) { /* stored BGR(A) */
                unsigned char r = t[0];
                t[0] = t[2];
                t[2] = r;
            }
            fwrite(t, 1, o->channels, f);
        }
    if (fclose(f) != 0)
        return vt_error_set(err, VTS_ERR_IO, "cannot write '%s'", path);
    return 0;
}

int vt_synth_image_write(const char *path, const struct vt_synth_image_options *o,
                         struct vts_error *err)
{
    if (o->width == 0 || o->height == 0 || o->channels < 1 || o->channels > 4 ||
        vts_sample_bytes(o->sample) == 0)
        return vt_error_set(err, VTS_ERR_ARG, "bad synthetic image shape");
    switch (o->format) {
    case VT_SYNTH_TIFF:
        return synth_write_tiff(path, o, err);
    case VT_SYNTH_PNG:
        return synth_write_png(path, o, err);
    case VT_SYNTH_JPEG:
        return synth_write_jpeg(path, o, err);
    case VT_SYNTH_EXR:
        return synth_write_exr(path, o, err);
    case VT_SYNTH_TGA:
        return synth_write_tga(path, o, err);
    default:
        return vt_error_set(err, VTS_ERR_ARG, "unknown synthetic format %u", o->format);
    }
}
