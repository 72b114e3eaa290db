/* Atlas layout: JSON round trip, every validation rule, lookup by name, and the UV mapping with
 * its V-axis convention. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vt_layout.h"
#include "vt_test.h"
#include "vts.h"

static char *xstrdup(const char *s)
{
    char *d = malloc(strlen(s) + 1);
    strcpy(d, s);
    return d;
}

/* Two layers, three entries: a 300x200 texture in a 512x256 cell, a 100x60 sub-tile texture with
 * a fill for its normal layer (also used by the materials 'tiny' and 'little': aliases), and a
 * 64x64 texture replicated 3x2 from origin (-1, 0). */
static void make_layout(struct vt_layout *l)
{
    VT_CHECK_INT_EQ(vt_layout_alloc(l, 2, 3, NULL), 0);
    l->width = 1024, l->height = 512, l->tile_content = 256, l->border = 4;
    l->generator = xstrdup("test");
    l->layers[0] = (struct vt_layout_layer){xstrdup("diffuse"), xstrdup("map_Kd"), VTS_COLOUR_SRGB};
    l->layers[1] = (struct vt_layout_layer){xstrdup("normal"), xstrdup("norm"), VTS_COLOUR_NORMAL};
    struct vt_layout_entry *e = l->entries;
    e[0].name = xstrdup("brick");
    e[0].width = 300, e[0].height = 200, e[0].cell_width = 512, e[0].cell_height = 256;
    e[0].alignment = 256;
    e[1].name = xstrdup("small");
    e[1].x = 512, e[1].width = 100, e[1].height = 60, e[1].cell_width = 128, e[1].cell_height = 64,
    e[1].alignment = 64, e[1].scale = 0.5;
    e[1].aliases = malloc(2 * sizeof *e[1].aliases);
    e[1].aliases[0] = xstrdup("tiny"), e[1].aliases[1] = xstrdup("little");
    e[1].alias_count = 2;
    e[2].name = xstrdup("ground");
    e[2].y = 256, e[2].width = 64, e[2].height = 64, e[2].repeat_u = 3, e[2].repeat_v = 2;
    e[2].origin_u = -1, e[2].cell_width = 256, e[2].cell_height = 128, e[2].alignment = 128;
    e[2].group = 7;
    for (int i = 0; i < 3; i++) {
        char p[32];
        snprintf(p, sizeof p, "tex/%s.png", e[i].name);
        e[i].textures[0].path = xstrdup(p);
        e[i].textures[0].width = e[i].width, e[i].textures[0].height = e[i].height;
    }
    e[0].textures[1].path = xstrdup("tex/brick n.png");
    e[0].textures[1].width = 300, e[0].textures[1].height = 200;
    e[1].textures[1].fill[0] = 0.5, e[1].textures[1].fill[1] = 0.5;
    e[1].textures[1].fill[2] = 1, e[1].textures[1].fill[3] = 1;
    e[2].textures[1].fill[3] = 0.25;
}

static void test_round_trip(void)
{
    struct vt_layout l, r;
    struct vts_error err;
    make_layout(&l);
    VT_CHECK_INT_EQ(vt_layout_write("layout_rt.json", &l, &err), 0);
    VT_CHECK_INT_EQ(vt_layout_read("layout_rt.json", NULL, &r, &err), 0);
    VT_CHECK_INT_EQ(r.width, 1024);
    VT_CHECK_INT_EQ(r.height, 512);
    VT_CHECK_INT_EQ(r.tile_content, 256);
    VT_CHECK_INT_EQ(r.border, 4);
    VT_CHECK_INT_EQ(r.layer_count, 2);
    VT_CHECK_INT_EQ(r.entry_count, 3);
    VT_CHECK(strcmp(r.layers[1].name, "normal") == 0 && r.layers[1].colour == VTS_COLOUR_NORMAL);
    VT_CHECK(strcmp(r.generator, "test") == 0);
    for (uint32_t i = 0; i < 3; i++) {
        const struct vt_layout_entry *a = &l.entries[i], *b = &r.entries[i];
        VT_CHECK(strcmp(a->name, b->name) == 0);
        VT_CHECK(a->x == b->x && a->y == b->y && a->width == b->width && a->height == b->height);
        VT_CHECK(a->repeat_u == b->repeat_u && a->repeat_v == b->repeat_v);
        VT_CHECK(a->origin_u == b->origin_u && a->origin_v == b->origin_v);
        VT_CHECK(a->cell_width == b->cell_width && a->cell_height == b->cell_height);
        VT_CHECK(a->alignment == b->alignment && a->scale == b->scale && a->group == b->group);
        VT_CHECK_INT_EQ(b->alias_count, a->alias_count);
        for (uint32_t k = 0; k < a->alias_count && k < b->alias_count; k++)
            VT_CHECK(strcmp(a->aliases[k], b->aliases[k]) == 0);
        for (uint32_t k = 0; k < 2; k++) {
            const struct vt_layout_texture *ta = &a->textures[k], *tb = &b->textures[k];
            VT_CHECK(!ta->path == !tb->path);
            if (ta->path) {
                VT_CHECK(strcmp(ta->path, tb->path) == 0);
                VT_CHECK(ta->width == tb->width && ta->height == tb->height);
            } else {
                for (int c = 0; c < 4; c++)
                    VT_CHECK(ta->fill[c] == tb->fill[c]);
            }
        }
    }
    /* Relative paths resolve against the layout's directory. */
    VT_CHECK(strcmp(r.entries[0].textures[1].resolved, "tex/brick n.png") == 0);
    VT_CHECK(vt_layout_find(&r, "ground") == &r.entries[2]);
    VT_CHECK(vt_layout_find(&r, "brick") == &r.entries[0]);
    VT_CHECK(vt_layout_find(&r, "nope") == NULL);
    /* Aliases find their entry; the entry's own name too. */
    VT_CHECK(vt_layout_find(&r, "small") == &r.entries[1]);
    VT_CHECK(vt_layout_find(&r, "tiny") == &r.entries[1]);
    VT_CHECK(vt_layout_find(&r, "little") == &r.entries[1]);
    VT_CHECK(vt_layout_find(&r, "littl") == NULL);
    VT_CHECK_INT_EQ(r.name_count, 5);
    /* "aliases" is written for the entry that has some only, right after its name. */
    FILE *f = fopen("layout_rt.json", "r");
    char text[8192];
    size_t len = f ? fread(text, 1, sizeof text - 1, f) : 0;
    text[len] = 0;
    if (f)
        fclose(f);
    const char *first = strstr(text, "\"aliases\"");
    VT_CHECK(first != NULL && strstr(first + 1, "\"aliases\"") == NULL);
    VT_CHECK(
        strstr(text,
               "\"name\": \"small\",\n   \"aliases\": [\n    \"tiny\",\n    \"little\"\n   ],") !=
        NULL);
    VT_CHECK_INT_EQ(vt_layout_layer_index(&r, "normal"), 1);
    VT_CHECK_INT_EQ(vt_layout_layer_index(&r, "specular"), -1);
    vt_layout_release(&r);
    vt_layout_release(&l);
    vt_layout_release(&l); /* twice is harmless */
    if (!getenv("KEEP"))
        remove("layout_rt.json");
}

static void test_resolve_against_directory(void)
{
    const char *text =
        "{\"format\":\"vtpipe-atlas\",\"version\":1,\"width\":256,\"height\":256,\"tile_content\":256,\"border\":2,\"layers\":[{\"name\":\"diffuse\",\"map\":\"map_Kd\",\"colour\":\"srgb\"}],\"entries\":[{\"name\":\"a\",\"x\":0,\"y\":0,\"width\":10,\"height\":10,\"cell_width\":16,\"cell_height\":16,\"alignment\":16,\"textures\":[{\"path\":\"t/a.png\",\"width\":10,\"height\":10}]}]}";
    struct vt_layout l;
    VT_CHECK_INT_EQ(
        vt_layout_parse_memory(text, strlen(text), "out/dir/atlas.json", NULL, &l, NULL), 0);
    VT_CHECK(strcmp(l.entries[0].textures[0].resolved, "out/dir/t/a.png") == 0);
    /* Defaults of the optional fields. */
    VT_CHECK(l.entries[0].repeat_u == 1 && l.entries[0].origin_v == 0 && l.entries[0].scale == 1);
    vt_layout_release(&l);
}

/* Applies edit to a valid layout and expects vt_layout_index() to refuse it with message part. */
static void expect_invalid(void (*edit)(struct vt_layout *), const char *part)
{
    struct vt_layout l;
    struct vts_error err;
    make_layout(&l);
    edit(&l);
    int rc = vt_layout_check(&l, "x.json", &err);
    VT_CHECK_INT_EQ(rc, VTS_ERR_BAD_INPUT);
    VT_CHECK_STR_CONTAINS(err.message, part);
    vt_layout_release(&l);
}

static void overlap(struct vt_layout *l)
{
    l->entries[1].x = 256; /* inside brick's 512-wide cell */
}
static void outside(struct vt_layout *l)
{
    l->entries[2].y = 512 - 64; /* cell 128 high ends past 512 */
    l->entries[2].alignment = 64;
}
static void misaligned(struct vt_layout *l)
{
    l->entries[1].x = 512 + 32;
}
static void too_big(struct vt_layout *l)
{
    l->entries[2].repeat_u = 5; /* 5 * 64 > 256 */
}
static void bad_scale(struct vt_layout *l)
{
    l->entries[0].scale = 0.75;
}
static void dup_name(struct vt_layout *l)
{
    free(l->entries[2].name);
    l->entries[2].name = xstrdup("brick");
}
static void alias_is_name(struct vt_layout *l)
{
    free(l->entries[1].aliases[1]);
    l->entries[1].aliases[1] = xstrdup("brick");
}
static void alias_is_own_name(struct vt_layout *l)
{
    free(l->entries[1].aliases[0]);
    l->entries[1].aliases[0] = xstrdup("small");
}
static void alias_twice(struct vt_layout *l)
{
    struct vt_layout_entry *e = &l->entries[2];
    e->aliases = malloc(sizeof *e->aliases);
    e->aliases[0] = xstrdup("tiny");
    e->alias_count = 1;
}
static void alias_empty(struct vt_layout *l)
{
    l->entries[1].aliases[1][0] = 0;
}
static void alias_null(struct vt_layout *l)
{
    free(l->entries[1].aliases[0]);
    l->entries[1].aliases[0] = NULL;
}
static void dup_layer(struct vt_layout *l)
{
    free(l->layers[1].name);
    l->layers[1].name = xstrdup("diffuse");
}
static void bad_tile(struct vt_layout *l)
{
    l->tile_content = 248;
}
static void bad_fill(struct vt_layout *l)
{
    l->entries[1].textures[1].fill[0] = NAN;
}

static void test_validation(void)
{
    expect_invalid(overlap, "the cells of 'brick' and 'small' overlap");
    expect_invalid(outside, "entry 2 ('ground') has a cell outside the atlas");
    expect_invalid(misaligned, "('small') has an alignment that is not a power of two dividing");
    expect_invalid(too_big, "('ground') does not fit in its cell");
    expect_invalid(bad_scale, "('brick') has a scale that is not a power of two");
    expect_invalid(dup_name, "entry 'brick' given twice");
    expect_invalid(alias_is_name,
                   "'x.json': name 'brick' given twice (entries 'brick' and 'small')");
    expect_invalid(alias_is_own_name, "name 'small' given twice (entries 'small' and 'small')");
    expect_invalid(alias_twice, "name 'tiny' given twice (entries 'small' and 'ground')");
    expect_invalid(alias_empty, "'x.json': entry 'small' has an empty alias");
    expect_invalid(alias_null, "'x.json': entry 'small' has an empty alias");
    expect_invalid(dup_layer, "layer 'diffuse' given twice");
    expect_invalid(bad_tile, "content must be a power of two");
    expect_invalid(bad_fill, "fill outside 0..1");
}

/* Many touching cells (a 64x64 grid of 16x16 cells) are not overlaps; one more that overlaps the
 * last row is. Exercises the sweep with many active cells. */
static void test_overlap_sweep(void)
{
    struct vt_layout l;
    struct vts_error err;
    VT_CHECK_INT_EQ(vt_layout_alloc(&l, 1, 64 * 64 + 1, NULL), 0);
    l.width = l.height = 1024, l.tile_content = 256;
    l.layers[0] = (struct vt_layout_layer){xstrdup("diffuse"), xstrdup("map_Kd"), VTS_COLOUR_SRGB};
    for (uint32_t i = 0; i <= 64 * 64; i++) {
        struct vt_layout_entry *e = &l.entries[i];
        char name[32];
        snprintf(name, sizeof name, "e%u", i);
        e->name = xstrdup(name);
        e->x = (i % 64) * 16, e->y = (i / 64) * 16;
        e->width = e->height = e->cell_width = e->cell_height = e->alignment = 16;
        e->textures[0].fill[3] = 1;
    }
    l.entry_count = 64 * 64;
    VT_CHECK_INT_EQ(vt_layout_check(&l, "grid", &err), 0);
    l.entry_count = 64 * 64 + 1;
    l.entries[4096].x = 1024 - 32, l.entries[4096].y = 1024 - 32;
    l.entries[4096].cell_width = l.entries[4096].cell_height = 32;
    l.entries[4096].alignment = 32;
    VT_CHECK_INT_EQ(vt_layout_check(&l, "grid", &err), VTS_ERR_BAD_INPUT);
    VT_CHECK_STR_CONTAINS(err.message, "overlap");
    vt_layout_release(&l);
}

/* 4096 entries with 3 aliases each: every name and alias is found (binary search over the sorted
 * names), names between them are not. */
static void test_find_many_aliases(void)
{
    struct vt_layout l;
    struct vts_error err;
    const uint32_t n = 4096;
    VT_CHECK_INT_EQ(vt_layout_alloc(&l, 1, n, NULL), 0);
    l.width = l.height = 1024, l.tile_content = 256;
    l.layers[0] = (struct vt_layout_layer){xstrdup("diffuse"), xstrdup("map_Kd"), VTS_COLOUR_SRGB};
    for (uint32_t i = 0; i < n; i++) {
        struct vt_layout_entry *e = &l.entries[i];
        char name[32];
        snprintf(name, sizeof name, "m%u", (i * 40503u) % 65536u); /* a permutation */
        e->name = xstrdup(name);
        e->aliases = malloc(3 * sizeof *e->aliases);
        for (uint32_t a = 0; a < 3; a++) {
            snprintf(name, sizeof name, "a%u_%u", i, a);
            e->aliases[a] = xstrdup(name);
        }
        e->alias_count = 3;
        e->x = (i % 64) * 16, e->y = (i / 64) * 16;
        e->width = e->height = e->cell_width = e->cell_height = e->alignment = 16;
        e->textures[0].fill[3] = 1;
    }
    VT_CHECK_INT_EQ(vt_layout_check(&l, "many", &err), 0);
    VT_CHECK_INT_EQ(l.name_count, 4 * n);
    uint32_t found = 0;
    for (uint32_t i = 0; i < n; i++) {
        found += vt_layout_find(&l, l.entries[i].name) == &l.entries[i];
        for (uint32_t a = 0; a < 3; a++)
            found += vt_layout_find(&l, l.entries[i].aliases[a]) == &l.entries[i];
    }
    VT_CHECK_INT_EQ(found, 4 * n);
    VT_CHECK(vt_layout_find(&l, "a0_3") == NULL && vt_layout_find(&l, "a") == NULL &&
             vt_layout_find(&l, "m") == NULL && vt_layout_find(&l, "zz") == NULL);
    vt_layout_release(&l);
}

static void expect_parse_error(const char *text, const char *part)
{
    struct vt_layout l;
    struct vts_error err;
    int rc = vt_layout_parse_memory(text, strlen(text), "bad.json", NULL, &l, &err);
    VT_CHECK(rc < 0);
    VT_CHECK_STR_CONTAINS(err.message, part);
    VT_CHECK(strchr(err.message, '\n') == NULL);
    vt_layout_release(&l);
}

static void test_parse_errors(void)
{
    expect_parse_error("{", "'bad.json':1:");
    expect_parse_error("[]", "top level: expected an object");
    expect_parse_error("{\"format\":\"other\"}", "format: not \"vtpipe-atlas\"");
    expect_parse_error("{\"format\":\"vtpipe-atlas\",\"version\":2}", "layout version 2");
    expect_parse_error("{\"format\":\"vtpipe-atlas\",\"version\":1,\"entries\":[]}",
                       "layers: expected an array");
    const char *head =
        "{\"format\":\"vtpipe-atlas\",\"version\":1,\"width\":256,\"height\":256,\"tile_content\":256,\"border\":2,\"layers\":[{\"name\":\"diffuse\",\"map\":\"map_Kd\",\"colour\":\"srgb\"}],\"entries\":[";
    char buf[1024];
    snprintf(buf, sizeof buf, "%s{\"name\":\"a\",\"x\":-1}]}", head);
    expect_parse_error(buf, "entries[0].x: expected an integer 0..4294967295");
    snprintf(
        buf, sizeof buf,
        "%s{\"name\":\"a\",\"x\":0,\"y\":0,\"width\":4,\"height\":4,\"cell_width\":4,\"cell_height\":4,\"alignment\":4,\"textures\":[]}]}",
        head);
    expect_parse_error(buf, "entries[0]: textures must be an array with one item per layer");
    snprintf(
        buf, sizeof buf,
        "%s{\"name\":\"a\",\"x\":0,\"y\":0,\"width\":4,\"height\":4,\"cell_width\":4,\"cell_height\":4,\"alignment\":4,\"textures\":[{\"fill\":[0,0,0,2]}]}]}",
        head);
    expect_parse_error(buf, "entries[0].textures[0]: fill values must be numbers in 0..1");
    snprintf(buf, sizeof buf,
             "{\"format\":\"vtpipe-atlas\",\"version\":1,\"width\":1,\"width\":2}");
    expect_parse_error(buf, "duplicate object key");
    struct vt_layout_limits lim;
    vt_layout_limits_default(&lim);
    lim.max_entries = 0;
    struct vt_layout l;
    struct vts_error err;
    snprintf(buf, sizeof buf, "%s{}]}", head);
    VT_CHECK_INT_EQ(vt_layout_parse_memory(buf, strlen(buf), "lim.json", &lim, &l, &err),
                    VTS_ERR_LIMIT);
    VT_CHECK_STR_CONTAINS(err.message, "1 entries, more than the limit 0");
    vt_layout_release(&l);
    /* aliases: an array of non-empty strings, counted against the entry limit. */
    const char *entry =
        "{\"name\":\"a\",\"x\":0,\"y\":0,\"width\":4,\"height\":4,\"cell_width\":4,\"cell_height\":4,\"alignment\":4,\"textures\":[{\"fill\":[0,0,0,1]}],";
    snprintf(buf, sizeof buf, "%s%s\"aliases\":\"b\"}]}", head, entry);
    expect_parse_error(buf, "'bad.json': entries[0].aliases: expected an array of names");
    snprintf(buf, sizeof buf, "%s%s\"aliases\":[\"b\",1]}]}", head, entry);
    expect_parse_error(buf, "entries[0].aliases: expected non-empty strings without NUL");
    snprintf(buf, sizeof buf, "%s%s\"aliases\":[\"\"]}]}", head, entry);
    expect_parse_error(buf, "entries[0].aliases: expected non-empty strings without NUL");
    snprintf(buf, sizeof buf, "%s%s\"aliases\":[\"b\\u0000c\"]}]}", head, entry);
    expect_parse_error(buf, "u0000 is not allowed");
    snprintf(buf, sizeof buf, "%s%s\"aliases\":[\"a\"]}]}", head, entry);
    expect_parse_error(buf, "'bad.json': name 'a' given twice (entries 'a' and 'a')");
    snprintf(buf, sizeof buf, "%s%s\"aliases\":[\"b\",\"c\"]}]}", head, entry);
    lim.max_entries = 2;
    VT_CHECK_INT_EQ(vt_layout_parse_memory(buf, strlen(buf), "lim.json", &lim, &l, &err),
                    VTS_ERR_LIMIT);
    VT_CHECK_STR_CONTAINS(
        err.message, "'lim.json': 3 material names (entries and aliases), more than the limit 2");
    vt_layout_release(&l);
    lim.max_entries = 3;
    VT_CHECK_INT_EQ(vt_layout_parse_memory(buf, strlen(buf), "lim.json", &lim, &l, &err), 0);
    VT_CHECK(vt_layout_find(&l, "c") == &l.entries[0] && l.entries[0].alias_count == 2);
    vt_layout_release(&l);
    snprintf(buf, sizeof buf, "%s%s\"aliases\":[]}]}", head, entry); /* empty: none */
    VT_CHECK_INT_EQ(vt_layout_parse_memory(buf, strlen(buf), "e.json", NULL, &l, &err), 0);
    VT_CHECK(l.entries[0].alias_count == 0 && l.entries[0].aliases == NULL);
    vt_layout_release(&l);
    VT_CHECK_INT_EQ(vt_layout_read("does/not/exist.json", NULL, &l, &err), VTS_ERR_IO);
    VT_CHECK_STR_CONTAINS(err.message, "cannot open 'does/not/exist.json'");
}

/* Texel (i, j) of a texture (j from the top) at its centre UV lands on the centre of atlas texel
 * (x + i, y + j); u = 0 / v = 1 is the rect's top-left corner; wrapped copies start at origin. */
static void test_map_uv(void)
{
    struct vt_layout l;
    make_layout(&l);
    VT_CHECK_INT_EQ(vt_layout_index(&l, NULL), 0);
    const struct vt_layout_entry *e = &l.entries[0]; /* 300x200 at (0, 0) */
    double au, av;
    vt_layout_map_uv(&l, e, (7 + 0.5) / 300, 1 - (3 + 0.5) / 200, &au, &av);
    VT_CHECK(fabs(au * 1024 - 7.5) < 1e-9);
    VT_CHECK(fabs((1 - av) * 512 - 3.5) < 1e-9); /* row 3 from the top of the atlas */
    vt_layout_map_uv(&l, e, 0, 1, &au, &av);
    VT_CHECK(au == 0 && av == 1);
    vt_layout_map_uv(&l, e, 1, 0, &au, &av);
    VT_CHECK(fabs(au * 1024 - 300) < 1e-9 && fabs((1 - av) * 512 - 200) < 1e-9);
    /* ground: 64x64 copies, 3x2 from (0, 256), origin u -1: u in [-1, 2], v in [0, 2]. */
    e = &l.entries[2];
    vt_layout_map_uv(&l, e, -1, 2, &au, &av);
    VT_CHECK(fabs(au * 1024 - 0) < 1e-9 && fabs((1 - av) * 512 - 256) < 1e-9);
    vt_layout_map_uv(&l, e, 2, 0, &au, &av);
    VT_CHECK(fabs(au * 1024 - 192) < 1e-9 && fabs((1 - av) * 512 - 384) < 1e-9);
    /* u = 0.25, v = 0.75 in the second copy along u and the lower copy along v. */
    vt_layout_map_uv(&l, e, 0.25, 0.75, &au, &av);
    VT_CHECK(fabs(au * 1024 - (64 + 16)) < 1e-9);
    VT_CHECK(fabs((1 - av) * 512 - (256 + 64 + 16)) < 1e-9);
    VT_CHECK(vt_layout_uv_covered(e, -1, 0) && vt_layout_uv_covered(e, 2, 2));
    VT_CHECK(!vt_layout_uv_covered(e, 2.001, 1) && !vt_layout_uv_covered(e, 0, -0.001));
    vt_layout_release(&l);
}

/* Gutters: cell_left/cell_top round-trip as "cell_x"/"cell_y" (written only when non-zero), the
 * cell rectangle (not x, y) is what must stay inside the atlas and apart from other cells, the
 * copies must fit after the gutter, and the alignment must divide the gutter too. */
static void add_gutter(struct vt_layout *l)
{
    struct vt_layout_entry *e = &l->entries[1]; /* 100x60 at (512, 0), cell 128x64 */
    e->x = 516, e->y = 4, e->cell_left = 4, e->cell_top = 4, e->cell_width = 112,
    e->cell_height = 72, e->alignment = 4;
}
static void gutter_overlap(struct vt_layout *l)
{
    add_gutter(l);
    l->entries[1].x = 520, l->entries[1].cell_left = 12; /* cell from 508: inside brick's */
}
static void gutter_before_atlas(struct vt_layout *l)
{
    add_gutter(l);
    l->entries[1].y = 0; /* cell_top 4 > y */
}
static void gutter_too_small(struct vt_layout *l)
{
    add_gutter(l);
    l->entries[1].cell_width = 100 + 3; /* the copy ends past the cell */
}
static void gutter_misaligned(struct vt_layout *l)
{
    add_gutter(l);
    l->entries[1].alignment = 8; /* divides x 516? no */
    l->entries[1].x = 520, l->entries[1].cell_left = 8, l->entries[1].cell_top = 2,
    l->entries[1].y = 2;
}
static void gutter_outside(struct vt_layout *l)
{
    add_gutter(l);
    l->entries[1].cell_width = 1024 - 512 + 4; /* ends past the atlas */
}
static void test_gutter_fields(void)
{
    struct vt_layout l, r;
    struct vts_error err;
    make_layout(&l);
    add_gutter(&l);
    VT_CHECK_INT_EQ(vt_layout_check(&l, "g.json", &err), 0);
    VT_CHECK_INT_EQ(vt_layout_cell_x(&l.entries[1]), 512);
    VT_CHECK_INT_EQ(vt_layout_cell_y(&l.entries[1]), 0);
    VT_CHECK_INT_EQ(vt_layout_write("layout_gutter.json", &l, &err), 0);
    VT_CHECK_INT_EQ(vt_layout_read("layout_gutter.json", NULL, &r, &err), 0);
    for (uint32_t i = 0; i < 3; i++) {
        const struct vt_layout_entry *a = &l.entries[i], *b = &r.entries[i];
        VT_CHECK(a->x == b->x && a->y == b->y && a->cell_left == b->cell_left &&
                 a->cell_top == b->cell_top && a->cell_width == b->cell_width &&
                 a->cell_height == b->cell_height && a->alignment == b->alignment);
    }
    vt_layout_release(&r);
    /* Only the entry with a gutter carries cell_x/cell_y. */
    FILE *f = fopen("layout_gutter.json", "rb");
    char text[8192];
    size_t n = f ? fread(text, 1, sizeof text - 1, f) : 0;
    if (f)
        fclose(f);
    text[n] = 0;
    const char *p = strstr(text, "\"cell_x\": 512");
    VT_CHECK(p != NULL);
    VT_CHECK(p && strstr(p + 1, "\"cell_x\"") == NULL);
    VT_CHECK(strstr(text, "\"cell_y\": 0") != NULL);
    vt_layout_release(&l);
    expect_invalid(gutter_overlap, "the cells of 'brick' and 'small' overlap");
    expect_invalid(gutter_before_atlas, "('small') has a cell starting after its texture");
    expect_invalid(gutter_too_small, "('small') does not fit in its cell");
    expect_invalid(gutter_misaligned, "('small') has an alignment that is not a power of two");
    expect_invalid(gutter_outside, "('small') has a cell outside the atlas");
    /* Reader: cell_x defaults to x, must not exceed it. */
    const char *head =
        "{\"format\":\"vtpipe-atlas\",\"version\":1,\"width\":256,\"height\":256,\"tile_content\":256,\"border\":2,\"layers\":[{\"name\":\"diffuse\",\"map\":\"map_Kd\",\"colour\":\"srgb\"}],\"entries\":[";
    char buf[1024];
    snprintf(
        buf, sizeof buf,
        "%s{\"name\":\"a\",\"x\":4,\"y\":4,\"width\":4,\"height\":4,\"cell_width\":12,\"cell_height\":12,\"alignment\":4,\"cell_x\":8,\"textures\":[{\"fill\":[0,0,0,1]}]}]}",
        head);
    expect_parse_error(buf, "entries[0].cell_x: expected an integer 0..4");
    snprintf(
        buf, sizeof buf,
        "%s{\"name\":\"a\",\"x\":4,\"y\":4,\"width\":4,\"height\":4,\"cell_width\":12,\"cell_height\":12,\"alignment\":4,\"cell_x\":0,\"cell_y\":0,\"textures\":[{\"fill\":[0,0,0,1]}]}]}",
        head);
    VT_CHECK_INT_EQ(vt_layout_parse_memory(buf, strlen(buf), "g.json", NULL, &r, &err), 0);
    VT_CHECK(r.entries[0].cell_left == 4 && r.entries[0].cell_top == 4);
    vt_layout_release(&r);
    snprintf(
        buf, sizeof buf,
        "%s{\"name\":\"a\",\"x\":4,\"y\":4,\"width\":4,\"height\":4,\"cell_width\":8,\"cell_height\":8,\"alignment\":4,\"textures\":[{\"fill\":[0,0,0,1]}]}]}",
        head);
    VT_CHECK_INT_EQ(vt_layout_parse_memory(buf, strlen(buf), "g.json", NULL, &r, &err), 0);
    VT_CHECK(r.entries[0].cell_left == 0 && r.entries[0].cell_top == 0);
    vt_layout_release(&r);
}

int main(void)
{
    VT_RUN(test_round_trip);
    VT_RUN(test_resolve_against_directory);
    VT_RUN(test_validation);
    VT_RUN(test_overlap_sweep);
    VT_RUN(test_find_many_aliases);
    VT_RUN(test_parse_errors);
    VT_RUN(test_map_uv);
    VT_RUN(test_gutter_fields);
    return vt_test_main_result();
}
