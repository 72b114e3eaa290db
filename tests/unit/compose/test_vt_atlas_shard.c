/* lib/compose's sharded atlas builds (vt_atlas_shard.c): over 1 to 16 parts, the shards and the
 * merge emit every tile of the single build exactly once with the same bytes; a shard decodes no
 * texture whose cell is away from its part; the merge refuses a carried payload that is short,
 * long or names another part's entry; a changed carried float changes the merge's tiles. */
#include <stdlib.h>
#include <string.h>

#include "internal/vt_atlas_build_impl.h"
#include "vt_atlas_build.h"
#include "vt_layout.h"
#include "vt_test.h"

#define NTEX 4
#include "compose_test_util.h"

/* e0: 256 aligned at 256 (owns texels above the carried level), e1: wraps, e2: odd size in a
 * wide cell aligned at 4 (mixed above level 2), e3: alpha */
static const uint32_t tex_w[NTEX] = {256, 128, 200, 64}, tex_h[NTEX] = {256, 128, 100, 64};
static const uint32_t ent_x[NTEX] = {0, 512, 768, 256}, ent_y[NTEX] = {0, 0, 256, 384};
static const uint32_t cell_w[NTEX] = {256, 128, 256, 64}, cell_h[NTEX] = {256, 128, 128, 64};
static const uint32_t align[NTEX] = {256, 128, 4, 64};

/* Every tile of both layers: a hash of its payload (1 for an empty tile), and how often emitted. */
#define MAX_TILES 4096
struct tiles {
    uint64_t hash[2][MAX_TILES];
    uint32_t count[2][MAX_TILES];
    uint32_t first[VTS_MAX_LEVELS + 1], tx[VTS_MAX_LEVELS];
};

static void tiles_geometry(struct tiles *t, uint32_t w, uint32_t h, uint32_t c, uint32_t levels)
{
    memset(t, 0, sizeof *t);
    for (uint32_t l = 0; l < levels; l++) {
        uint32_t lw = (w + (1u << l) - 1) >> l, lh = (h + (1u << l) - 1) >> l;
        t->tx[l] = (lw + c - 1) / c;
        t->first[l + 1] = t->first[l] + t->tx[l] * ((lh + c - 1) / c);
    }
}

static int keep_tile(void *user, unsigned worker, uint32_t slot, uint32_t level, uint32_t tx,
                     uint32_t ty, const struct vt_image *payload, struct vts_error *err)
{
    struct tiles *t = user;
    uint32_t i = t->first[level] + ty * t->tx[level] + tx;
    uint64_t h = 1;
    (void)worker, (void)err;
    if (payload) {
        h = 1469598103934665603ull;
        for (uint32_t y = 0; y < payload->height; y++) {
            const uint8_t *p = vt_image_at(payload, 0, y);
            for (size_t k = 0; k < (size_t)payload->width * payload->channels; k++)
                h = (h ^ p[k]) * 1099511628211ull;
        }
    }
    t->hash[slot][i] = h;
    __atomic_fetch_add(&t->count[slot][i], 1, __ATOMIC_RELAXED);
    return 0;
}

static struct vt_layout lay;
static uint32_t layers[2] = {0, 1};

static struct vt_atlas_build *make(uint32_t index, uint32_t count, bool merge,
                                   const struct vt_atlas_layer_format *formats, unsigned threads)
{
    struct vt_atlas_build_options o = {.layout = &lay,
                                       .layers = layers,
                                       .layer_count = 2,
                                       .threads = threads,
                                       .filter = VT_FILTER_LANCZOS3,
                                       .open = open_mem,
                                       .part = {index, count, merge, formats}};
    struct vts_error err = {0};
    struct vt_atlas_build *b = vt_atlas_build_create(&o, &err);
    if (!b)
        VT_CHECK_STR_EQ(err.message, "");
    return b;
}

static void read_layout(void)
{
    char json[4096];
    int n = snprintf(json, sizeof json,
                     "{\"format\": \"vtpipe-atlas\", \"version\": 1, \"width\": 1024, \"height\": "
                     "512, \"tile_content\": 32, \"border\": 2, \"layers\": [{\"name\": \"d\", "
                     "\"map\": \"map_Kd\", \"colour\": \"srgb\"}, {\"name\": \"a\", \"map\": "
                     "\"map_d\", \"colour\": \"data\"}], \"entries\": [");
    for (int i = 0; i < NTEX; i++) {
        fill_texture(&textures[i], tex_w[i], tex_h[i], i == 3 ? 4 : 3, (uint32_t)i + 5, 31);
        n += snprintf(json + n, sizeof json - (size_t)n,
                      "%s{\"name\": \"e%d\", \"x\": %u, \"y\": %u, \"width\": %u, \"height\": %u, "
                      "\"cell_width\": %u, \"cell_height\": %u, \"alignment\": %u, %s"
                      "\"textures\": [{\"path\": \"%d.png\", \"width\": %u, \"height\": %u}, "
                      "{\"path\": \"%d.png\", \"width\": %u, \"height\": %u}]}",
                      i ? ", " : "", i, ent_x[i], ent_y[i], tex_w[i], tex_h[i], cell_w[i],
                      cell_h[i], align[i], i == 1 ? "\"wrap\": true, " : "", i, tex_w[i], tex_h[i],
                      i, tex_w[i], tex_h[i]);
    }
    snprintf(json + n, sizeof json - (size_t)n, "]}");
    VT_CHECK_INT_EQ(vt_layout_parse_memory(json, strlen(json), "/m/atlas.json", NULL, &lay, NULL),
                    0);
}

/* The shards of count parts then their merge, into got; the carried payloads kept in carry[]. */
static void sharded(uint32_t count, struct tiles *got, unsigned char **carry, size_t *len,
                    uint64_t decoded[][NTEX])
{
    struct vt_atlas_layer_format formats[2];
    for (uint32_t i = 0; i < count; i++) {
        memset(rows_read, 0, sizeof rows_read);
        struct vt_atlas_build *b = make(i, count, false, NULL, 1 + i % 2);
        struct vts_error err = {0};
        VT_CHECK_INT_EQ(b ? vt_atlas_build_tiles(b, keep_tile, got, &err) : -1, 0);
        VT_CHECK_INT_EQ(b ? vt_atlas_build_carry(b, &carry[i], &len[i], &err) : -1, 0);
        for (uint32_t s = 0; b && s < 2; s++)
            vt_atlas_build_format(b, s, &formats[s]);
        memcpy(decoded[i], rows_read, sizeof rows_read);
        vt_atlas_build_destroy(b);
    }
    struct vt_atlas_build *m = make(0, count, true, formats, 2);
    struct vts_error err = {0};
    for (uint32_t i = 0; m && i < count; i++)
        VT_CHECK_INT_EQ(vt_atlas_build_put_carry(m, i, carry[i], len[i], &err), 0);
    VT_CHECK_INT_EQ(m ? vt_atlas_build_tiles(m, keep_tile, got, &err) : -1, 0);
    vt_atlas_build_destroy(m);
}

static uint32_t differences(const struct tiles *a, const struct tiles *b, uint32_t n)
{
    uint32_t d = 0;
    for (uint32_t s = 0; s < 2; s++)
        for (uint32_t i = 0; i < n; i++)
            d += a->hash[s][i] != b->hash[s][i] || b->count[s][i] != 1;
    return d;
}

static void shards_and_merge_equal_the_single_build(void)
{
    static struct tiles single, got;
    read_layout();
    struct vt_atlas_build *b = make(0, 0, false, NULL, 2);
    uint32_t levels = b ? vt_atlas_build_level_count(b) : 0;
    uint32_t n = b ? (uint32_t)vt_atlas_build_tile_count(b) : 0;
    VT_CHECK(n <= MAX_TILES);
    tiles_geometry(&single, 1024, 512, 32, levels);
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(b ? vt_atlas_build_tiles(b, keep_tile, &single, &err) : -1, 0);
    vt_atlas_build_destroy(b);
    for (uint32_t count = 1; count <= 16; count *= 2) {
        unsigned char *carry[16] = {0};
        size_t len[16] = {0};
        uint64_t decoded[16][NTEX];
        tiles_geometry(&got, 1024, 512, 32, levels);
        sharded(count, &got, carry, len, decoded);
        VT_CHECK_INT_EQ(differences(&single, &got, n), 0);
        if (count == 8) {
            /* 1024x512 in tiles of 32: a 4x2 grid of 8x8-tile parts (256 texels), carried level
             * 3. Part 7 (x 768..1023, y 256..511, plus a border of 2 x 8 texels) meets only e2,
             * part 0 only e0; e3 has alpha: every shard decodes it for the layer's format */
            VT_CHECK(decoded[7][0] == 0 && decoded[7][1] == 0);
            VT_CHECK_INT_EQ(decoded[7][2], 100);
            VT_CHECK_INT_EQ(decoded[7][3], 64);
            VT_CHECK(decoded[0][1] == 0 && decoded[0][2] == 0);
            VT_CHECK_INT_EQ(decoded[0][0], 256);
            /* a payload one byte short or long, or carrying another part's entry, is refused */
            struct vt_atlas_layer_format formats[2];
            struct vt_atlas_build *probe = make(0, 8, false, NULL, 1);
            for (uint32_t s = 0; probe && s < 2; s++)
                vt_atlas_build_format(probe, s, &formats[s]);
            vt_atlas_build_destroy(probe);
            struct vt_atlas_build *m = make(0, 8, true, formats, 1);
            unsigned char *longer = malloc(len[0] + 1);
            memcpy(longer, carry[0], len[0]);
            longer[len[0]] = 0;
            VT_CHECK_INT_EQ(m ? vt_atlas_build_put_carry(m, 0, carry[0], len[0] - 1, &err) : 0,
                            VTS_ERR_BAD_INPUT);
            VT_CHECK_INT_EQ(m ? vt_atlas_build_put_carry(m, 0, longer, len[0] + 1, &err) : 0,
                            VTS_ERR_BAD_INPUT);
            /* part 0 carries e0's chains above level 3; as part 1's they are refused */
            VT_CHECK(len[0] > len[1]);
            VT_CHECK_INT_EQ(m ? vt_atlas_build_put_carry(m, 1, carry[0], len[0], &err) : 0,
                            VTS_ERR_BAD_INPUT);
            VT_CHECK(strstr(err.message, "entr") != NULL);
            vt_atlas_build_destroy(m);
            free(longer);
            /* a deliberately wrong carried float is seen: part 7's first texel value (e2's
             * mixed texels, whose parents of level 4 are mixed too: not e0's, whose level 4 is
             * read from its carried chain) */
            carry[7][3] ^= 0x40;
            tiles_geometry(&got, 1024, 512, 32, levels);
            m = make(0, 8, true, formats, 1);
            for (uint32_t i = 0; m && i < 8; i++)
                VT_CHECK_INT_EQ(vt_atlas_build_put_carry(m, i, carry[i], len[i], &err), 0);
            VT_CHECK_INT_EQ(m ? vt_atlas_build_tiles(m, keep_tile, &got, &err) : -1, 0);
            vt_atlas_build_destroy(m);
            uint32_t d = 0;
            for (uint32_t s = 0; s < 2; s++)
                for (uint32_t i = 0; i < n; i++)
                    d += got.count[s][i] && got.hash[s][i] != single.hash[s][i];
            VT_CHECK(d > 0);
        }
        for (uint32_t i = 0; i < count; i++)
            free(carry[i]);
    }
    vt_layout_release(&lay);
    for (int i = 0; i < NTEX; i++)
        vt_image_release(&textures[i]);
}

int main(void)
{
    VT_RUN(shards_and_merge_equal_the_single_build);
    return vt_test_main_result();
}
