/* Atlas layout: entries holding a crop of their block of copies ("crop") and entries that wrap
 * ("wrap"): round trip, every refusal (in memory and from the file), the UV mapping and the covered
 * UV range with a crop, and layouts without them written as before. */
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

/* One layer, three entries in a 256x128 atlas:
 *   0 'tiles': a 40x30 texture copied 3x2 from origin (-1, 0) (a 120x60 block), holding the crop
 *     (27, 13, 70, 40) (it starts in the middle of the first copy and ends in the third) at
 *     (128, 64) in a 96x64 cell: too small for the block, large enough for the crop;
 *   1 'sky': a 64x48 wrap entry at (0, 0) in a 64x64 cell;
 *   2 'plain': a 50x20 texture at (64, 0), no crop, no wrap. */
static void make_layout(struct vt_layout *l)
{
    VT_CHECK_INT_EQ(vt_layout_alloc(l, 1, 3, NULL), 0);
    l->width = 256, l->height = 128, l->tile_content = 64, l->border = 2;
    l->layers[0] = (struct vt_layout_layer){xstrdup("diffuse"), xstrdup("map_Kd"), VTS_COLOUR_SRGB};
    struct vt_layout_entry *e = l->entries;
    e[0].name = xstrdup("tiles");
    e[0].x = 128, e[0].y = 64, e[0].width = 40, e[0].height = 30;
    e[0].repeat_u = 3, e[0].repeat_v = 2, e[0].origin_u = -1;
    e[0].crop_x = 27, e[0].crop_y = 13, e[0].crop_width = 70, e[0].crop_height = 40;
    e[0].cell_width = 96, e[0].cell_height = 64, e[0].alignment = 32;
    e[1].name = xstrdup("sky");
    e[1].width = 64, e[1].height = 48, e[1].wrap = true;
    e[1].cell_width = 64, e[1].cell_height = 64, e[1].alignment = 64;
    e[2].name = xstrdup("plain");
    e[2].x = 64, e[2].width = 50, e[2].height = 20;
    e[2].cell_width = 64, e[2].cell_height = 32, e[2].alignment = 32;
    for (int i = 0; i < 3; i++) {
        char p[32];
        snprintf(p, sizeof p, "tex/%s.png", e[i].name);
        e[i].textures[0].path = xstrdup(p);
        e[i].textures[0].width = e[i].width, e[i].textures[0].height = e[i].height;
    }
}

static size_t read_text(const char *path, char *text, size_t cap)
{
    FILE *f = fopen(path, "rb");
    size_t n = f ? fread(text, 1, cap - 1, f) : 0;
    if (f)
        fclose(f);
    text[n] = 0;
    return n;
}

static size_t count(const char *text, const char *what)
{
    size_t n = 0;
    for (const char *p = strstr(text, what); p; p = strstr(p + 1, what))
        n++;
    return n;
}

static void test_round_trip(void)
{
    struct vt_layout l, r;
    struct vts_error err;
    make_layout(&l);
    VT_CHECK_INT_EQ(vt_layout_write("layout_crop.json", &l, &err), 0);
    /* the in-memory layout got its missing crops filled in: the whole block */
    VT_CHECK(l.entries[1].crop_width == 64 && l.entries[1].crop_height == 48);
    VT_CHECK(l.entries[2].crop_width == 50 && l.entries[2].crop_height == 20);
    VT_CHECK_INT_EQ(vt_layout_read("layout_crop.json", NULL, &r, &err), 0);
    for (uint32_t i = 0; i < 3; i++) {
        const struct vt_layout_entry *a = &l.entries[i], *b = &r.entries[i];
        VT_CHECK(a->crop_x == b->crop_x && a->crop_y == b->crop_y);
        VT_CHECK(a->crop_width == b->crop_width && a->crop_height == b->crop_height);
        VT_CHECK(a->wrap == b->wrap);
        VT_CHECK(a->repeat_u == b->repeat_u && a->origin_u == b->origin_u);
    }
    VT_CHECK(r.entries[0].crop_x == 27 && r.entries[0].crop_height == 40);
    VT_CHECK(r.entries[1].wrap && !r.entries[0].wrap && !r.entries[2].wrap);
    /* "crop" only for the cropped entry, "wrap" only for the wrap entry, after the other fields */
    char text[8192];
    read_text("layout_crop.json", text, sizeof text);
    VT_CHECK_INT_EQ(count(text, "\"crop\""), 1);
    VT_CHECK_INT_EQ(count(text, "\"wrap\""), 1);
    VT_CHECK(strstr(text, "\"crop\": [\n    27,\n    13,\n    70,\n    40\n   ]") != NULL);
    VT_CHECK(strstr(text, "\"wrap\": true") != NULL);
    const char *sky = strstr(text, "\"name\": \"sky\""),
               *plain = strstr(text, "\"name\": \"plain\"");
    const char *wrap = strstr(text, "\"wrap\"");
    VT_CHECK(sky && plain && wrap && sky < wrap && wrap < plain);
    vt_layout_release(&r);
    vt_layout_release(&l);
    if (!getenv("KEEP"))
        remove("layout_crop.json");
}

/* A crop that is the whole block and wrap false are not written: such a layout is written byte
 * for byte as one whose entries never had the fields. */
static void test_whole_block_written_as_before(void)
{
    struct vt_layout a, b;
    struct vts_error err;
    make_layout(&a);
    make_layout(&b);
    for (int k = 0; k < 2; k++) {
        struct vt_layout *l = k ? &b : &a;
        struct vt_layout_entry *e = &l->entries[0];
        e->crop_x = e->crop_y = 0;
        e->crop_width = k ? 120 : 0, e->crop_height = k ? 60 : 0; /* whole block, or unset */
        e->cell_width = 128;
        l->entries[1].wrap = false;
        l->entries[1].crop_width = k ? 64 : 0, l->entries[1].crop_height = k ? 48 : 0;
    }
    VT_CHECK_INT_EQ(vt_layout_write("layout_whole_a.json", &a, &err), 0);
    VT_CHECK_INT_EQ(vt_layout_write("layout_whole_b.json", &b, &err), 0);
    static char ta[8192], tb[8192];
    size_t na = read_text("layout_whole_a.json", ta, sizeof ta);
    size_t nb = read_text("layout_whole_b.json", tb, sizeof tb);
    VT_CHECK(na > 0 && na == nb && memcmp(ta, tb, na) == 0);
    VT_CHECK(!strstr(ta, "crop") && !strstr(ta, "wrap"));
    vt_layout_release(&a);
    vt_layout_release(&b);
    if (!getenv("KEEP")) {
        remove("layout_whole_a.json");
        remove("layout_whole_b.json");
    }
}

/* In memory: a crop of width or height 0 is the whole block; every rule is checked. */
static void expect_invalid(void (*edit)(struct vt_layout *), const char *part)
{
    struct vt_layout l;
    struct vts_error err;
    make_layout(&l);
    edit(&l);
    VT_CHECK_INT_EQ(vt_layout_check(&l, "c.json", &err), VTS_ERR_BAD_INPUT);
    VT_CHECK_STR_CONTAINS(err.message, part);
    vt_layout_release(&l);
}
static void crop_past_block(struct vt_layout *l)
{
    l->entries[0].crop_x = 51; /* 51 + 70 > 120 */
}
static void crop_past_block_v(struct vt_layout *l)
{
    l->entries[0].crop_y = 21; /* 21 + 40 > 60 */
}
static void crop_overflow(struct vt_layout *l)
{
    l->entries[0].crop_x = UINT32_MAX; /* wraps around in 32 bits */
}
static void cell_too_small(struct vt_layout *l)
{
    l->entries[0].crop_x = 23, l->entries[0].crop_width = 97; /* the cell is 96 wide */
}
static void cell_too_small_gutter(struct vt_layout *l)
{
    l->entries[0].x = 136, l->entries[0].cell_left = 8, l->entries[0].alignment = 8;
    l->entries[0].crop_x = 0, l->entries[0].crop_width = 89; /* 8 + 89 > 96 */
}
static void wrap_repeat(struct vt_layout *l)
{
    l->entries[1].repeat_u = 2; /* 128 wide: the cell is 64 */
    l->entries[1].cell_width = 128, l->entries[2].x = 128;
}
static void wrap_partial_crop(struct vt_layout *l)
{
    l->entries[1].crop_x = 1, l->entries[1].crop_width = 63, l->entries[1].crop_height = 48;
}
static void wrap_small_crop(struct vt_layout *l)
{
    l->entries[1].crop_width = 64, l->entries[1].crop_height = 47;
}
static void huge_block_no_crop(struct vt_layout *l)
{
    /* 2^20 x 65536 copies: more than 2^32 texels a side, no crop: cannot fit any cell */
    struct vt_layout_entry *e = &l->entries[2];
    e->width = 1u << 20, e->repeat_u = 65536;
}

static void test_refusals_in_memory(void)
{
    expect_invalid(crop_past_block, "entry 0 ('tiles') has a crop outside its block of copies");
    expect_invalid(crop_past_block_v, "entry 0 ('tiles') has a crop outside its block of copies");
    expect_invalid(crop_overflow, "entry 0 ('tiles') has a crop outside its block of copies");
    expect_invalid(cell_too_small, "entry 0 ('tiles') does not fit in its cell");
    expect_invalid(cell_too_small_gutter, "entry 0 ('tiles') does not fit in its cell");
    expect_invalid(wrap_repeat, "entry 1 ('sky') wraps but has a repeat other than [1, 1]");
    expect_invalid(wrap_partial_crop, "entry 1 ('sky') wraps but has a crop smaller than");
    expect_invalid(wrap_small_crop, "entry 1 ('sky') wraps but has a crop smaller than");
    expect_invalid(huge_block_no_crop, "entry 2 ('plain') does not fit in its cell");
    /* the same edits without the fault are accepted: the checks above are the crop's */
    struct vt_layout l;
    struct vts_error err;
    make_layout(&l);
    l.entries[0].crop_x = 50, l.entries[0].crop_y = 20; /* ends exactly at the block's end */
    l.entries[0].crop_width = 70, l.entries[0].crop_height = 40;
    l.entries[1].crop_width = 64, l.entries[1].crop_height = 0; /* 0: the whole block */
    l.entries[2].crop_width = 0, l.entries[2].crop_height = 7;
    VT_CHECK_INT_EQ(vt_layout_check(&l, "c.json", &err), 0);
    VT_CHECK(l.entries[1].crop_width == 64 && l.entries[1].crop_height == 48);
    VT_CHECK(l.entries[2].crop_width == 50 && l.entries[2].crop_height == 20);
    /* the cell must hold the crop, no longer the block: 96 < 120 holds 96 */
    l.entries[0].crop_x = 24, l.entries[0].crop_width = 96;
    VT_CHECK_INT_EQ(vt_layout_check(&l, "c.json", &err), 0);
    vt_layout_release(&l);
}

/* From the file: one line naming the file, the entry and the field. */
static void expect_parse_error(const char *fields, const char *part)
{
    static const char head[] =
        "{\"format\":\"vtpipe-atlas\",\"version\":1,\"width\":256,\"height\":256,\"tile_content\":64,\"border\":2,\"layers\":[{\"name\":\"diffuse\",\"map\":\"map_Kd\",\"colour\":\"srgb\"}],\"entries\":[{\"name\":\"a\",\"x\":0,\"y\":0,\"width\":40,\"height\":30,\"cell_width\":128,\"cell_height\":64,\"alignment\":64,\"textures\":[{\"fill\":[0,0,0,1]}]";
    char buf[2048];
    snprintf(buf, sizeof buf, "%s%s}]}", head, fields);
    struct vt_layout l;
    struct vts_error err;
    int rc = vt_layout_parse_memory(buf, strlen(buf), "atlas.json", NULL, &l, &err);
    if (part) {
        VT_CHECK_INT_EQ(rc, VTS_ERR_BAD_INPUT);
        VT_CHECK_STR_CONTAINS(err.message, part);
        VT_CHECK(strchr(err.message, '\n') == NULL);
    } else {
        VT_CHECK_INT_EQ(rc, 0);
        if (rc)
            fprintf(stderr, "%s\n", err.message);
    }
    vt_layout_release(&l);
}

static void test_refusals_from_file(void)
{
    const char *shape = "expected [x, y, width, height]: integers 0..4294967295";
    expect_parse_error(",\"crop\":[0,0,0,4]", "'atlas.json': entries[0].crop: expected [x, y,");
    expect_parse_error(",\"crop\":[0,0,4,0]", shape);
    expect_parse_error(",\"crop\":[0,0,4]", shape);
    expect_parse_error(",\"crop\":[0,0,4,4,4]", shape);
    expect_parse_error(",\"crop\":[-1,0,4,4]", shape);
    expect_parse_error(",\"crop\":[0,0.5,4,4]", shape);
    expect_parse_error(",\"crop\":\"all\"", shape);
    expect_parse_error(",\"crop\":[0,0,4294967296,4]", shape);
    expect_parse_error(",\"crop\":[1,0,40,30]",
                       "'atlas.json': entries[0].crop: [1, 0, 40, 30] is not inside the block of "
                       "copies (40x30)");
    expect_parse_error(",\"repeat\":[3,2],\"crop\":[80,31,40,30]",
                       "entries[0].crop: [80, 31, 40, 30] is not inside the block of copies "
                       "(120x60)");
    expect_parse_error(",\"crop\":[4294967295,0,4294967295,1]", "is not inside the block");
    /* the cell (128x64) holds the crop, not the block: refused by the cell check */
    expect_parse_error(",\"repeat\":[4,2],\"crop\":[0,0,129,30]", "entry 0 ('a') does not fit");
    expect_parse_error(",\"repeat\":[4,3],\"crop\":[3,5,128,64]", NULL);
    expect_parse_error(",\"wrap\":1", "'atlas.json': entries[0].wrap: expected true or false");
    expect_parse_error(",\"wrap\":\"yes\"", "entries[0].wrap: expected true or false");
    expect_parse_error(",\"wrap\":true,\"repeat\":[2,1]",
                       "'atlas.json': entries[0].wrap: a wrap entry holds one copy: repeat must "
                       "be [1, 1], not [2, 1]");
    expect_parse_error(",\"wrap\":true,\"repeat\":[1,2]", "repeat must be [1, 1], not [1, 2]");
    expect_parse_error(",\"wrap\":true,\"crop\":[0,0,40,29]",
                       "'atlas.json': entries[0].wrap: a wrap entry holds its whole texture: crop "
                       "must be absent or [0, 0, 40, 30], not [0, 0, 40, 29]");
    expect_parse_error(",\"wrap\":true,\"crop\":[1,0,39,30]", "holds its whole texture");
    expect_parse_error(",\"wrap\":true,\"crop\":[0,0,40,30]", NULL);
    expect_parse_error(",\"wrap\":true", NULL);
    expect_parse_error(",\"wrap\":false,\"repeat\":[2,2]", NULL);
}

/* The crop's texel (a, b) is texel (crop_x + a, crop_y + b) of the block, whose centre is at
 * u = origin_u + (crop_x + a + 0.5) / width, v = origin_v + repeat_v - (crop_y + b + 0.5) /
 * height: it lands on the centre of atlas texel (x + a, y + b). */
static void test_map_uv_crop(void)
{
    struct vt_layout l;
    make_layout(&l);
    VT_CHECK_INT_EQ(vt_layout_index(&l, NULL), 0);
    const struct vt_layout_entry *e = &l.entries[0]; /* crop (27, 13, 70, 40) at (128, 64) */
    static const uint32_t ab[][2] = {{0, 0}, {12, 16}, {13, 17}, {52, 30}, {69, 39}};
    for (size_t k = 0; k < sizeof ab / sizeof ab[0]; k++) {
        double u = -1 + (27 + ab[k][0] + 0.5) / 40, v = 0 + 2 - (13 + ab[k][1] + 0.5) / 30, au, av;
        vt_layout_map_uv(&l, e, u, v, &au, &av);
        VT_CHECK(fabs(au * 256 - (128 + ab[k][0] + 0.5)) < 1e-9);
        VT_CHECK(fabs((1 - av) * 128 - (64 + ab[k][1] + 0.5)) < 1e-9);
    }
    /* the corners of the crop: its top-left at (x, y), its bottom-right at (x + 70, y + 40) */
    double au, av;
    vt_layout_map_uv(&l, e, -1 + 27.0 / 40, 2 - 13.0 / 30, &au, &av);
    VT_CHECK(fabs(au * 256 - 128) < 1e-9 && fabs((1 - av) * 128 - 64) < 1e-9);
    vt_layout_map_uv(&l, e, -1 + 97.0 / 40, 2 - 53.0 / 30, &au, &av);
    VT_CHECK(fabs(au * 256 - 198) < 1e-9 && fabs((1 - av) * 128 - 104) < 1e-9);
    /* without a crop, the formula is the old one: texel (i, j) of the texture at (x + i, y + j) */
    e = &l.entries[2]; /* 50x20 at (64, 0) */
    vt_layout_map_uv(&l, e, (7 + 0.5) / 50, 1 - (3 + 0.5) / 20, &au, &av);
    VT_CHECK(fabs(au * 256 - 71.5) < 1e-9 && fabs((1 - av) * 128 - 3.5) < 1e-9);
    vt_layout_release(&l);
}

/* The covered range is the crop's, bounds included; one ulp outside is not covered. */
static void test_uv_covered_crop(void)
{
    struct vt_layout l;
    make_layout(&l);
    VT_CHECK_INT_EQ(vt_layout_index(&l, NULL), 0);
    const struct vt_layout_entry *e = &l.entries[0];
    double u0 = -1 + 27.0 / 40, u1 = -1 + 97.0 / 40, v0 = 2 - 53.0 / 30, v1 = 2 - 13.0 / 30;
    double um = (u0 + u1) / 2, vm = (v0 + v1) / 2;
    VT_CHECK(vt_layout_uv_covered(e, u0, vm) && vt_layout_uv_covered(e, u1, vm));
    VT_CHECK(vt_layout_uv_covered(e, um, v0) && vt_layout_uv_covered(e, um, v1));
    VT_CHECK(vt_layout_uv_covered(e, u0, v0) && vt_layout_uv_covered(e, u1, v1));
    VT_CHECK(!vt_layout_uv_covered(e, nextafter(u0, -INFINITY), vm));
    VT_CHECK(!vt_layout_uv_covered(e, nextafter(u1, INFINITY), vm));
    VT_CHECK(!vt_layout_uv_covered(e, um, nextafter(v0, -INFINITY)));
    VT_CHECK(!vt_layout_uv_covered(e, um, nextafter(v1, INFINITY)));
    /* inside the block but outside the crop */
    VT_CHECK(!vt_layout_uv_covered(e, -1, vm) && !vt_layout_uv_covered(e, 2, vm));
    VT_CHECK(!vt_layout_uv_covered(e, um, 0) && !vt_layout_uv_covered(e, um, 2));
    /* a crop of 0 x 0 (not checked yet) covers the whole block, as an entry without a crop */
    struct vt_layout_entry whole = *e;
    whole.crop_x = whole.crop_y = whole.crop_width = whole.crop_height = 0;
    VT_CHECK(vt_layout_uv_covered(&whole, -1, 0) && vt_layout_uv_covered(&whole, 2, 2));
    VT_CHECK(!vt_layout_uv_covered(&whole, nextafter(-1, -INFINITY), 1));
    VT_CHECK(!vt_layout_uv_covered(&whole, 0, nextafter(2, INFINITY)));
    /* an entry without a crop: exactly [origin, origin + repeat] */
    e = &l.entries[2];
    VT_CHECK(vt_layout_uv_covered(e, 0, 0) && vt_layout_uv_covered(e, 1, 1));
    VT_CHECK(!vt_layout_uv_covered(e, nextafter(1, 2), 0.5));
    VT_CHECK(!vt_layout_uv_covered(e, 0.5, nextafter(0, -1)));
    vt_layout_release(&l);
}

int main(void)
{
    VT_RUN(test_round_trip);
    VT_RUN(test_whole_block_written_as_before);
    VT_RUN(test_refusals_in_memory);
    VT_RUN(test_refusals_from_file);
    VT_RUN(test_map_uv_crop);
    VT_RUN(test_uv_covered_crop);
    return vt_test_main_result();
}
