/* Writes N generated PNG textures (sizes 64..1024, some odd, some with alpha) and an atlas.json
 * that shelf-packs them (cells rounded up to a power-of-two alignment), for timing
 * `vt-tiles --layout`. Usage: gen_atlas_bench DIR N [SEED] */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "vt_layout.h"
#include "vt_png_file.h"

static uint32_t rng(uint32_t *s)
{
    *s ^= *s << 13;
    *s ^= *s >> 17;
    *s ^= *s << 5;
    return *s;
}

static char *xstrdup(const char *s)
{
    char *d = malloc(strlen(s) + 1);
    strcpy(d, s);
    return d;
}

static int write_png(const char *path, uint32_t w, uint32_t h, uint32_t ch, uint32_t seed)
{
    struct vts_error err;
    struct vt_png_file_writer *pw = vt_png_file_writer_create(path, w, h, ch, 8, &err);
    if (!pw) {
        fprintf(stderr, "%s\n", err.message);
        return 1;
    }
    uint8_t *row = malloc((size_t)w * ch);
    int rc = 0;
    for (uint32_t y = 0; y < h && rc == 0; y++) {
        for (uint32_t x = 0; x < w; x++) {
            uint8_t *p = row + (size_t)x * ch;
            p[0] = (uint8_t)(x * 255 / w);
            p[1] = (uint8_t)(y * 255 / h);
            p[2] = (uint8_t)(seed * 37 + ((x / 16 + y / 16) & 1) * 90);
            if (ch == 4)
                p[3] = (uint8_t)(128 + (x & 127));
        }
        rc = vt_png_file_writer_rows(pw, row, 1, (size_t)w * ch, &err);
    }
    if (rc == 0)
        rc = vt_png_file_writer_finish(pw, &err);
    if (rc)
        fprintf(stderr, "%s\n", err.message);
    vt_png_file_writer_destroy(pw);
    free(row);
    return rc != 0;
}

static uint32_t pow2_at_least(uint32_t v)
{
    uint32_t p = 1;
    while (p < v)
        p <<= 1;
    return p;
}

int main(int argc, char **argv)
{
    if (argc < 3) {
        fprintf(stderr, "usage: gen_atlas_bench DIR N [SEED]\n");
        return 2;
    }
    const char *dir = argv[1];
    uint32_t n = (uint32_t)atoi(argv[2]), seed = argc > 3 ? (uint32_t)atoi(argv[3]) : 1;
    mkdir(dir, 0777);
    struct vt_layout l;
    struct vts_error err;
    if (vt_layout_alloc(&l, 1, n, &err))
        return 1;
    l.tile_content = 256, l.border = 4;
    l.layers[0] = (struct vt_layout_layer){xstrdup("diffuse"), xstrdup("map_Kd"), 1};
    const uint32_t atlas_w = 8192;
    uint32_t x = 0, y = 0, shelf = 0;
    for (uint32_t i = 0; i < n; i++) {
        uint32_t w = 64u << (rng(&seed) % 5), h = 64u << (rng(&seed) % 5);
        if (rng(&seed) % 4 == 0)
            w -= rng(&seed) % 37, h -= rng(&seed) % 23; /* odd sizes */
        uint32_t ch = rng(&seed) % 8 == 0 ? 4 : 3;
        uint32_t cw = pow2_at_least(w), chh = pow2_at_least(h);
        uint32_t align = cw < chh ? cw : chh;
        align = align > 256 ? 256 : align;
        cw = (cw + align - 1) / align * align;
        x = (x + align - 1) / align * align;
        if (x + cw > atlas_w) {
            x = 0;
            y += shelf;
            shelf = 0;
        }
        /* keep y aligned for this entry */
        uint32_t yy = (y + align - 1) / align * align;
        struct vt_layout_entry *e = &l.entries[i];
        char name[32], path[512];
        snprintf(name, sizeof name, "t%04u", i);
        snprintf(path, sizeof path, "%s/%s.png", dir, name);
        if (write_png(path, w, h, ch, i))
            return 1;
        e->name = xstrdup(name);
        e->x = x, e->y = yy, e->width = w, e->height = h;
        e->cell_width = cw, e->cell_height = chh, e->alignment = align;
        snprintf(path, sizeof path, "%s.png", name);
        e->textures[0].path = xstrdup(path);
        e->textures[0].width = w, e->textures[0].height = h;
        x += cw;
        shelf = shelf > chh + (yy - y) ? shelf : chh + (yy - y);
    }
    l.width = atlas_w;
    l.height = (y + shelf + 255) / 256 * 256;
    char out[512];
    snprintf(out, sizeof out, "%s/atlas.json", dir);
    if (vt_layout_write(out, &l, &err)) {
        fprintf(stderr, "%s\n", err.message);
        return 1;
    }
    printf("%u textures, atlas %ux%u\n", n, l.width, l.height);
    vt_layout_release(&l);
    return 0;
}
