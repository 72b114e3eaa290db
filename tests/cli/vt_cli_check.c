/* vt-cli-check: assertions for the CLI tests (tests/cli/<tool>/<case>.sh), so that the cases need
 * only bash and coreutils. Exit 0 when every check holds, 1 when one fails, 2 on bad usage.
 *
 *   vt-cli-check png OUT.png --layer N --level L [--at X,Y] [vt-synth options]
 *       OUT.png is what `vt-info --extract L [--tile X,Y] --layer N` wrote from a store that
 *       `vt-synth` made with the same options: checks its size, channels, bit depth and every
 *       sample against vt_synth_texel() (0 in empty tiles). Prints one "ok" line.
 *   vt-cli-check tile-offset STORE LAYER LEVEL TX TY
 *       prints "OFFSET LENGTH" of the tile's payload.
 *   vt-cli-check junk-tile IN.vts OUT.vts LAYER LEVEL TX TY
 *       copies IN.vts to OUT.vts with that tile's payload replaced by bytes no codec decodes, under
 *       a correct CRC: only decoding the tile can find it.
 *   vt-cli-check empty-store OUT.vts WIDTH HEIGHT TILE BORDER
 *       writes a store of one RGBA8 raw layer whose tiles are all empty (a few hundred bytes even
 *       for a huge size).
 *   vt-cli-check json FILE PATH=VALUE...
 *       PATH: keys and array indices separated by '.', VALUE: the compact JSON of the element
 *       (strings in double quotes). Prints "ok PATH=VALUE" or the mismatch for each. */
#include <getopt.h>
#include <jansson.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vt_png_file.h"
#include "vt_synth.h"
#include "vts.h"
#include "vts_writer.h"

struct png_check {
    struct vt_synth_options synth;
    uint32_t layer, level;
    bool one_tile;
    uint32_t tx, ty;
};

static int parse_png_check(int argc, char **argv, struct png_check *c)
{
    static const struct option opts[] = {
        {"size", required_argument, 0, 's'},   {"tile", required_argument, 0, 't'},
        {"border", required_argument, 0, 'b'}, {"layers", required_argument, 0, 'l'},
        {"codec", required_argument, 0, 'c'},  {"channels", required_argument, 0, 'n'},
        {"sample", required_argument, 0, 'S'}, {"seed", required_argument, 0, 'r'},
        {"empty", no_argument, 0, 'e'},        {"flat", no_argument, 0, 'f'},
        {"layer", required_argument, 0, 'L'},  {"level", required_argument, 0, 'V'},
        {"at", required_argument, 0, 'a'},     {0, 0, 0, 0}};
    struct vt_synth_options *o = &c->synth;
    int opt, bad = 0;
    vt_synth_defaults(o);
    while ((opt = getopt_long(argc, argv, "", opts, NULL)) != -1) {
        if (opt == 's')
            bad |= sscanf(optarg, "%ux%u", &o->width, &o->height) != 2;
        else if (opt == 't')
            bad |= sscanf(optarg, "%u", &o->tile_content_px) != 1;
        else if (opt == 'b')
            bad |= sscanf(optarg, "%u", &o->border_px) != 1;
        else if (opt == 'l')
            bad |= sscanf(optarg, "%u", &o->layer_count) != 1;
        else if (opt == 'n')
            bad |= sscanf(optarg, "%u", &o->channels) != 1;
        else if (opt == 'S')
            o->sample = strcmp(optarg, "u16") == 0   ? VTS_SAMPLE_U16
                        : strcmp(optarg, "f16") == 0 ? VTS_SAMPLE_F16
                        : strcmp(optarg, "f32") == 0 ? VTS_SAMPLE_F32
                                                     : VTS_SAMPLE_U8;
        else if (opt == 'r')
            bad |= sscanf(optarg, "%u", &o->seed) != 1;
        else if (opt == 'e')
            o->empty_tiles = true;
        else if (opt == 'f')
            o->flat_left = true;
        else if (opt == 'L')
            bad |= sscanf(optarg, "%u", &c->layer) != 1;
        else if (opt == 'V')
            bad |= sscanf(optarg, "%u", &c->level) != 1;
        else if (opt == 'a' && sscanf(optarg, "%u,%u", &c->tx, &c->ty) == 2)
            c->one_tile = true;
        else if (opt != 'c') /* the codec does not change decoded values; 'a' unparsed */
            bad = 1;
    }
    return bad || optind != argc ? -1 : 0;
}

/* The PNG sample vt-info writes for a synth value v of a layer of the given sample type, and the
 * difference allowed (float conversions may round either way). */
static unsigned expected_sample(double v, uint32_t sample, unsigned *tolerance)
{
    float f = (float)v;
    *tolerance = sample == VTS_SAMPLE_F16 || sample == VTS_SAMPLE_F32;
    if (sample == VTS_SAMPLE_U8)
        return (unsigned)(v * 255.0 + 0.5);
    if (sample == VTS_SAMPLE_U16)
        return (unsigned)(v * 65535.0 + 0.5);
    if (sample == VTS_SAMPLE_F16) /* vt_synth stores half 0x3800 + m: 2^-1 * (1 + m / 1024) */
        f = 0.5f + (float)(uint16_t)(v * 1023.0) / 2048.0f;
    return f <= 0.0f ? 0 : f >= 1.0f ? 65535 : (unsigned)(f * 65535.0f + 0.5f);
}

static int check_png(const char *path, const struct png_check *c)
{
    const struct vt_synth_options *o = &c->synth;
    uint32_t edge = o->tile_content_px, border = o->border_px, payload = edge + 2 * border;
    uint32_t lw = (uint32_t)(((uint64_t)o->width + (1ull << c->level) - 1) >> c->level);
    uint32_t lh = (uint32_t)(((uint64_t)o->height + (1ull << c->level) - 1) >> c->level);
    uint32_t w = c->one_tile ? payload : lw, h = c->one_tile ? payload : lh;
    uint32_t sample = o->sample == VTS_SAMPLE_U8 ? VTS_SAMPLE_U8 : VTS_SAMPLE_U16;
    struct vts_error err = {0};
    struct vt_image img;
    if (vt_png_file_read(path, &img, &err) != 0) {
        fprintf(stderr, "vt-cli-check: %s\n", err.message);
        return 1;
    }
    uint64_t bad = 0, checked = 0;
    if (img.width != w || img.height != h || img.channels != o->channels || img.sample != sample) {
        fprintf(stderr, "vt-cli-check: '%s' is %ux%u, %u channels, %s; expected %ux%u, %u, %s\n",
                path, img.width, img.height, img.channels, vts_sample_name(img.sample), w, h,
                o->channels, vts_sample_name(sample));
        bad = 1;
    }
    for (uint32_t y = 0; y < h && !bad; y++)
        for (uint32_t x = 0; x < w; x++) {
            int64_t lx = c->one_tile ? (int64_t)c->tx * edge - border + x : x;
            int64_t ly = c->one_tile ? (int64_t)c->ty * edge - border + y : y;
            bool empty = c->one_tile ? vt_synth_tile_is_empty(o, c->level, c->tx, c->ty)
                                     : vt_synth_tile_is_empty(o, c->level, x / edge, y / edge);
            const unsigned char *p = vt_image_at(&img, x, y);
            for (uint32_t ch = 0; ch < img.channels; ch++) {
                unsigned tol = 0, want = 0, got;
                if (!empty)
                    want = expected_sample(vt_synth_texel(o, c->layer, c->level, lx, ly, ch),
                                           o->sample, &tol);
                if (sample == VTS_SAMPLE_U8) {
                    got = p[ch];
                } else {
                    uint16_t s;
                    memcpy(&s, p + 2 * ch, 2);
                    got = s;
                }
                checked++;
                if ((got > want ? got - want : want - got) > tol && bad++ < 5)
                    fprintf(stderr, "vt-cli-check: '%s' texel %u,%u channel %u: %u, expected %u\n",
                            path, x, y, ch, got, want);
            }
        }
    vt_image_release(&img);
    if (bad)
        return 1;
    printf("ok %s: %ux%u, %u channels, %s, %llu samples match\n", path, w, h, o->channels,
           vts_sample_name(sample), (unsigned long long)checked);
    return 0;
}

static int tile_offset(char **argv)
{
    struct vts_error err = {0};
    struct vts_tile_entry e;
    uint32_t v[4];
    for (int i = 0; i < 4; i++)
        v[i] = (uint32_t)strtoul(argv[i + 1], NULL, 10);
    struct vts_store *s = vts_open(argv[0], &err);
    if (!s || vts_store_tile(s, v[0], v[1], v[2], v[3], &e, &err) != 0) {
        fprintf(stderr, "vt-cli-check: %s\n", err.message);
        vts_close(s);
        return 1;
    }
    printf("%llu %u\n", (unsigned long long)e.offset, e.length);
    vts_close(s);
    return 0;
}

static int junk_tile(char **argv)
{
    static const char junk[] = "not a tile payload";
    struct vts_error err = {0};
    struct vts_layer layers[VTS_MAX_LAYERS];
    struct vts_writer *w = NULL;
    unsigned char *buf = NULL;
    uint32_t at[4];
    for (int i = 0; i < 4; i++)
        at[i] = (uint32_t)strtoul(argv[i + 2], NULL, 10);
    struct vts_store *s = vts_open(argv[0], &err);
    if (!s) {
        fprintf(stderr, "vt-cli-check: %s\n", err.message);
        return 1;
    }
    const struct vts_geometry *g = vts_store_geometry(s);
    for (uint32_t i = 0; i < g->layer_count; i++)
        layers[i] = *vts_store_layer(s, i);
    int rc = -1;
    if ((w = vts_writer_create(argv[1], g, layers, &err)) &&
        (buf = malloc(vts_store_max_payload(s) + 1u)))
        rc = 0;
    for (uint32_t layer = 0; rc == 0 && layer < g->layer_count; layer++)
        for (uint32_t level = 0; rc == 0 && level < g->level_count; level++) {
            struct vts_level L;
            vts_store_level(s, level, &L);
            for (uint32_t t = 0; rc == 0 && t < L.tiles_x * L.tiles_y; t++) {
                uint32_t tx = t % L.tiles_x, ty = t / L.tiles_x;
                bool bad = layer == at[0] && level == at[1] && tx == at[2] && ty == at[3];
                size_t len = 0;
                rc = vts_store_read(s, layer, level, tx, ty, buf, vts_store_max_payload(s), &len, 0,
                                    &err);
                const void *payload = bad ? (const void *)junk : buf;
                if (rc == 0)
                    rc = vts_writer_put(w, layer, level, tx, ty, payload, bad ? sizeof junk : len,
                                        &err);
            }
        }
    for (uint32_t i = 0; rc == 0 && i < vts_store_meta_count(s); i++)
        rc = vts_writer_set_meta(w, vts_store_meta_key(s, i), vts_store_meta_value(s, i), &err);
    if (rc == 0)
        rc = vts_writer_finish(w, &err);
    if (rc != 0)
        fprintf(stderr, "vt-cli-check: %s\n", err.message[0] ? err.message : "out of memory");
    vts_writer_destroy(w);
    free(buf);
    vts_close(s);
    return rc ? 1 : 0;
}

static int empty_store(char **argv)
{
    struct vts_error err = {0};
    struct vts_geometry g = {0};
    g.width = (uint32_t)strtoul(argv[1], NULL, 10);
    g.height = (uint32_t)strtoul(argv[2], NULL, 10);
    g.tile_content_px = (uint32_t)strtoul(argv[3], NULL, 10);
    g.border_px = (uint32_t)strtoul(argv[4], NULL, 10);
    g.tile_payload_px = g.tile_content_px + 2 * g.border_px;
    g.level_count = vts_full_level_count(g.width, g.height, g.tile_content_px);
    g.layer_count = 1;
    struct vts_layer layer = {VTS_CODEC_RAW, 4, VTS_SAMPLE_U8, VTS_COLOUR_SRGB, 0, 0, "empty"};
    struct vts_writer *w = vts_writer_create(argv[0], &g, &layer, &err);
    int rc = w ? vts_writer_finish(w, &err) : -1;
    vts_writer_destroy(w);
    if (rc != 0)
        fprintf(stderr, "vt-cli-check: %s\n", err.message);
    return rc ? 1 : 0;
}

/* Follows a '.'-separated path of keys and array indices from root; NULL when absent. */
static json_t *json_path(json_t *root, const char *path, size_t len)
{
    json_t *j = root;
    while (j && len > 0) {
        size_t n = strcspn(path, ".");
        n = n < len ? n : len;
        char key[128];
        snprintf(key, sizeof key, "%.*s", (int)n, path);
        j = json_is_array(j) ? json_array_get(j, strtoul(key, NULL, 10)) : json_object_get(j, key);
        path += n < len ? n + 1 : n;
        len -= n < len ? n + 1 : n;
    }
    return j;
}

static int check_json(const char *file, int count, char **checks)
{
    json_error_t jerr;
    json_t *root = json_load_file(file, 0, &jerr);
    int bad = 0;
    if (!root) {
        fprintf(stderr, "vt-cli-check: '%s' is not JSON: line %d: %s\n", file, jerr.line,
                jerr.text);
        return 1;
    }
    for (int i = 0; i < count; i++) {
        const char *eq = strchr(checks[i], '=');
        size_t path_len = eq ? (size_t)(eq - checks[i]) : strlen(checks[i]);
        json_t *j = json_path(root, checks[i], path_len);
        char *got =
            j ? json_dumps(j, JSON_ENCODE_ANY | JSON_COMPACT | JSON_REAL_PRECISION(6)) : NULL;
        if (eq && got && strcmp(got, eq + 1) == 0) {
            printf("ok %s\n", checks[i]);
        } else {
            printf("FAIL %.*s: got %s, expected %s\n", (int)path_len, checks[i],
                   got ? got : "(absent)", eq ? eq + 1 : "(no =VALUE)");
            bad = 1;
        }
        free(got);
    }
    json_decref(root);
    return bad;
}

int main(int argc, char **argv)
{
    struct png_check c = {0};
    if (argc >= 3 && strcmp(argv[1], "png") == 0) {
        if (parse_png_check(argc - 2, argv + 2, &c) != 0) {
            fprintf(stderr, "vt-cli-check: bad png arguments\n");
            return 2;
        }
        return check_png(argv[2], &c);
    }
    if (argc == 7 && strcmp(argv[1], "tile-offset") == 0)
        return tile_offset(argv + 2);
    if (argc == 7 && strcmp(argv[1], "empty-store") == 0)
        return empty_store(argv + 2);
    if (argc == 8 && strcmp(argv[1], "junk-tile") == 0)
        return junk_tile(argv + 2);
    if (argc >= 3 && strcmp(argv[1], "json") == 0)
        return check_json(argv[2], argc - 3, argv + 3);
    fprintf(
        stderr,
        "usage: vt-cli-check png|tile-offset|junk-tile|empty-store|json ... (see tests/cli/vt_cli_check.c)\n");
    return 2;
}
