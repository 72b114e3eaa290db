#include "tiles_check.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>

#include "vt_codec.h"
#include "vt_png_file.h"

const char *tiles_tool;
const char *tiles_info;
char tiles_dir[256];

int tiles_start(int argc, char **argv, const char *name)
{
    if (argc != 3)
        return 2;
    tiles_tool = argv[1];
    tiles_info = argv[2];
    snprintf(tiles_dir, sizeof tiles_dir, "%s/%s.XXXXXX",
             getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp", name);
    return mkdtemp(tiles_dir) ? 0 : 1;
}

void tiles_finish(bool keep)
{
    char cmd[400];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", tiles_dir);
    if (!keep && system(cmd) != 0)
        fprintf(stderr, "could not remove %s\n", tiles_dir);
}

const char *tiles_path(const char *name)
{
    static char paths[8][512];
    static int next;
    char *p = paths[next++ % 8];
    snprintf(p, 512, "%s/%s", tiles_dir, name);
    return p;
}

int tiles_write_png(const char *path, const struct vt_image *img)
{
    struct vts_error err;
    uint32_t depth = img->sample == VTS_SAMPLE_U16 ? 16 : 8;
    struct vt_png_file_writer *w =
        vt_png_file_writer_create(path, img->width, img->height, img->channels, depth, &err);
    int rc = w ? vt_png_file_writer_rows(w, img->pixels, img->height, img->stride, &err) : -1;
    if (rc == 0)
        rc = vt_png_file_writer_finish(w, &err);
    vt_png_file_writer_destroy(w);
    if (rc)
        fprintf(stderr, "cannot write %s: %s\n", path, err.message);
    return rc ? -1 : 0;
}

int tiles_run(const char *input, const char *output, const char *args)
{
    char cmd[2048];
    snprintf(cmd, sizeof cmd, "'%s' '%s' -o '%s' -q %s 2>'%s'", tiles_tool, input, output, args,
             tiles_path("stderr"));
    int st = system(cmd);
    int rc = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
    if (rc == 0 && tiles_info) {
        snprintf(cmd, sizeof cmd, "'%s' --verify -q '%s'", tiles_info, output);
        st = system(cmd);
        if (!WIFEXITED(st) || WEXITSTATUS(st) != 0) {
            fprintf(stderr, "vt-info --verify failed on %s\n", output);
            return 99;
        }
    }
    return rc;
}

const char *tiles_stderr(void)
{
    static char line[1024];
    line[0] = '\0';
    FILE *f = fopen(tiles_path("stderr"), "r");
    if (f) {
        if (!fgets(line, sizeof line, f))
            line[0] = '\0';
        fclose(f);
    }
    return line;
}

int tiles_read_payload(const struct vts_store *s, uint32_t level, uint32_t tx, uint32_t ty,
                       struct vt_image *out, bool *empty)
{
    const struct vts_geometry *g = vts_store_geometry(s);
    const struct vts_layer *L = vts_store_layer(s, 0);
    struct vts_error err;
    if (vt_image_alloc(out, g->tile_payload_px, g->tile_payload_px, L->channels, L->sample, &err))
        return -1;
    size_t cap = vts_store_max_payload(s) + 1, len;
    unsigned char *buf = malloc(cap);
    int rc = buf ? vts_store_read(s, 0, level, tx, ty, buf, cap, &len, 0, &err) : -1;
    *empty = rc == 0 && len == 0;
    if (rc == 0 && len > 0) {
        const struct vt_codec *c = vt_codec_by_fourcc(L->codec);
        rc = c ? c->decode(buf, len, out, &err) : -1;
    }
    if (rc)
        fprintf(stderr, "tile %u,%u of level %u: %s\n", tx, ty, level, err.message);
    free(buf);
    return rc ? -1 : 0;
}

int tiles_read_level(const struct vts_store *s, uint32_t level, struct vt_image *out)
{
    const struct vts_geometry *g = vts_store_geometry(s);
    const struct vts_layer *L = vts_store_layer(s, 0);
    struct vts_level lv;
    vts_store_level(s, level, &lv);
    if (vt_image_alloc(out, lv.width, lv.height, L->channels, L->sample, NULL))
        return -1;
    size_t tb = vt_image_texel_bytes(out);
    uint32_t c = g->tile_content_px, b = g->border_px;
    for (uint32_t ty = 0; ty < lv.tiles_y; ty++)
        for (uint32_t tx = 0; tx < lv.tiles_x; tx++) {
            struct vt_image t;
            bool empty;
            if (tiles_read_payload(s, level, tx, ty, &t, &empty))
                return -1;
            for (uint32_t y = 0; y < c && ty * c + y < lv.height; y++) {
                uint32_t w = lv.width - tx * c < c ? lv.width - tx * c : c;
                memcpy(vt_image_at(out, tx * c, ty * c + y), vt_image_at(&t, b, b + y), w * tb);
            }
            vt_image_release(&t);
        }
    return 0;
}

bool tiles_same_file(const char *a, const char *b)
{
    FILE *fa = fopen(a, "rb"), *fb = fopen(b, "rb");
    bool same = fa && fb;
    while (same) {
        int ca = fgetc(fa), cb = fgetc(fb);
        same = ca == cb;
        if (ca == EOF || cb == EOF)
            break;
    }
    if (fa)
        fclose(fa);
    if (fb)
        fclose(fb);
    return same;
}
