/* Shared fixture of the vt-tiles --layout tests (atlas_build_fixture.h). Setup failures abort:
 * a fixture that cannot be built fails the test outright. */
#include "atlas_build_fixture.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>

#include "vt_codec.h"
#include "vt_filter.h"
#include "vt_png_file.h"

#define REQUIRE(cond)                                                                              \
    do {                                                                                           \
        if (!(cond)) {                                                                             \
            fprintf(stderr, "%s:%d: fixture: %s failed\n", __FILE__, __LINE__, #cond);             \
            abort();                                                                               \
        }                                                                                          \
    } while (0)
#define REQUIRE_ZERO(a, b) REQUIRE((a) == (b))

const char *abuild_tool, *abuild_dir;
char abuild_stderr[8192];

/* ---- textures ---- */

static uint32_t hash3(uint32_t a, uint32_t b, uint32_t c)
{
    uint32_t h = a * 0x9e3779b1u ^ (b + 0x7f4a7c15u) * 0x85ebca6bu ^ c * 0xc2b2ae35u;
    h ^= h >> 15;
    h *= 0x2c1b3c6du;
    h ^= h >> 12;
    return h;
}

/* A texture with smooth gradients plus noise (every texel distinct enough to catch offsets). */
void abuild_texture(struct abuild_tex *t, const char *name, uint32_t w, uint32_t h, uint32_t ch,
                    uint32_t seed)
{
    t->name = name;
    REQUIRE_ZERO(vt_image_alloc(&t->img, w, h, ch, VTS_SAMPLE_U8, NULL), 0);
    for (uint32_t y = 0; y < h; y++)
        for (uint32_t x = 0; x < w; x++) {
            uint8_t *p = vt_image_at(&t->img, x, y);
            uint32_t r = hash3(x, y, seed);
            p[0] = (uint8_t)(x * 255 / w ^ (r & 15));
            p[1] = (uint8_t)(y * 255 / h ^ ((r >> 4) & 15));
            p[2] = (uint8_t)(seed * 40 + (r >> 8));
            if (ch == 4)
                p[3] = (uint8_t)(x < w / 4 ? 0 : 64 + ((r >> 16) & 127));
        }
    snprintf(t->path, sizeof t->path, "%s/%s.png", abuild_dir, name);
    struct vts_error err;
    struct vt_png_file_writer *pw = vt_png_file_writer_create(t->path, w, h, ch, 8, &err);
    REQUIRE(pw != NULL);
    if (!pw)
        return;
    REQUIRE_ZERO(vt_png_file_writer_rows(pw, t->img.pixels, h, t->img.stride, &err), 0);
    REQUIRE_ZERO(vt_png_file_writer_finish(pw, &err), 0);
    vt_png_file_writer_destroy(pw);
}

/* ---- running the tool ---- */

int abuild_run(const char *args)
{
    char cmd[4096], errfile[600];
    snprintf(errfile, sizeof errfile, "%s/stderr.txt", abuild_dir);
    snprintf(cmd, sizeof cmd, "%s %s 2>%s", abuild_tool, args, errfile);
    int rc = system(cmd);
    abuild_stderr[0] = 0;
    FILE *f = fopen(errfile, "r");
    if (f) {
        size_t n = fread(abuild_stderr, 1, sizeof abuild_stderr - 1, f);
        abuild_stderr[n] = 0;
        fclose(f);
    }
    return rc == -1 ? -1 : WEXITSTATUS(rc);
}

/* ---- reading the store ---- */

bool abuild_reader_open(struct abuild_reader *r, const char *path, uint32_t layer)
{
    memset(r, 0, sizeof *r);
    struct vts_error err;
    r->s = vts_open(path, &err);
    if (!r->s) {
        fprintf(stderr, "%s\n", err.message);
        return false;
    }
    r->g = *vts_store_geometry(r->s);
    r->layer = layer;
    const struct vts_layer *l = vts_store_layer(r->s, layer);
    vt_image_alloc(&r->tile, r->g.tile_payload_px, r->g.tile_payload_px, l->channels, l->sample,
                   NULL);
    r->buf = malloc(vts_store_max_payload(r->s) + 1);
    return true;
}

void abuild_reader_close(struct abuild_reader *r)
{
    vts_close(r->s);
    vt_image_release(&r->tile);
    free(r->buf);
}

/* The payload of a tile (NULL when empty). */
const struct vt_image *abuild_reader_tile(struct abuild_reader *r, uint32_t level, uint32_t tx,
                                          uint32_t ty)
{
    if (r->valid && r->level == level && r->tx == tx && r->ty == ty)
        return r->empty ? NULL : &r->tile;
    struct vts_error err;
    size_t len;
    r->valid = false;
    if (vts_store_read(r->s, r->layer, level, tx, ty, r->buf, vts_store_max_payload(r->s) + 1, &len,
                       0, &err))
        return NULL;
    r->level = level, r->tx = tx, r->ty = ty, r->valid = true, r->empty = len == 0;
    if (len == 0)
        return NULL;
    const struct vt_codec *c = vt_codec_by_fourcc(vts_store_layer(r->s, r->layer)->codec);
    if (c->decode(r->buf, len, &r->tile, &err)) {
        r->valid = false;
        return NULL;
    }
    return &r->tile;
}

/* Texel (X, Y) of a level, from the tile that owns it; NULL when that tile is empty. */
const uint8_t *abuild_reader_texel(struct abuild_reader *r, uint32_t level, uint32_t X, uint32_t Y)
{
    uint32_t c = r->g.tile_content_px, b = r->g.border_px;
    const struct vt_image *t = abuild_reader_tile(r, level, X / c, Y / c);
    return t ? vt_image_at(t, b + X % c, b + Y % c) : NULL;
}

char *abuild_strdup(const char *s)
{
    char *d = malloc(strlen(s) + 1);
    REQUIRE(d != NULL);
    strcpy(d, s);
    return d;
}

/* A texture reduced k times with the box filter in linear light, as 8-bit sRGB. */
void abuild_reduce(const struct vt_image *src, uint32_t k, struct vt_image *out)
{
    struct vt_pixel_mode m = {3, VTS_COLOUR_SRGB, false};
    struct vt_kernel kern;
    vt_kernel_init(&kern, VT_FILTER_BOX);
    uint32_t w = src->width, h = src->height;
    float *cur = malloc((size_t)w * h * 3 * sizeof(float));
    for (uint32_t y = 0; y < h; y++)
        vt_filter_to_working(&m, VTS_SAMPLE_U8, vt_image_at(src, 0, y), cur + (size_t)y * w * 3, w);
    for (uint32_t i = 0; i < k; i++) {
        uint32_t dw = (w + 1) / 2, dh = (h + 1) / 2;
        struct vt_fregion s = {0, 0, w, h, 3, cur}, d = {0, 0, dw, dh, 3, NULL};
        d.px = malloc((size_t)dw * dh * 3 * sizeof(float));
        size_t sn = vt_filter_reduce_scratch(&kern, &s, &d);
        float *scratch = malloc((sn + 1) * sizeof(float));
        struct vt_edges edges = {w, h, false, false};
        REQUIRE_ZERO(vt_filter_reduce(&kern, &edges, &s, &d, scratch, sn, NULL), 0);
        free(scratch);
        free(cur);
        cur = d.px, w = dw, h = dh;
    }
    vt_image_alloc(out, w, h, 3, VTS_SAMPLE_U8, NULL);
    for (uint32_t y = 0; y < h; y++)
        vt_filter_from_working(&m, VTS_SAMPLE_U8, cur + (size_t)y * w * 3, vt_image_at(out, 0, y),
                               w);
    free(cur);
}
