/* Atlas layout materials: the "materials" array of atlas.json (round trip, layouts without it,
 * every refusal) and its store metadata form (vt_layout_materials_meta). */
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

/* Two layers (diffuse, alpha); entry 'fence' has both maps, entry 'glass' (alias 'bottle') a
 * diffuse map and an alpha fill. */
static void make_layout(struct vt_layout *l)
{
    VT_CHECK_INT_EQ(vt_layout_alloc(l, 2, 2, NULL), 0);
    l->width = 512, l->height = 256, l->tile_content = 256, l->border = 4;
    l->layers[0] = (struct vt_layout_layer){xstrdup("diffuse"), xstrdup("map_Kd"), VTS_COLOUR_SRGB};
    l->layers[1] = (struct vt_layout_layer){xstrdup("alpha"), xstrdup("map_d"), VTS_COLOUR_DATA};
    struct vt_layout_entry *e = l->entries;
    e[0].name = xstrdup("fence");
    e[1].name = xstrdup("glass");
    e[1].aliases = malloc(sizeof *e[1].aliases);
    e[1].aliases[0] = xstrdup("bottle");
    e[1].alias_count = 1;
    for (int i = 0; i < 2; i++) {
        e[i].x = 256 * (uint32_t)i, e[i].width = e[i].height = 64;
        e[i].cell_width = e[i].cell_height = 256, e[i].alignment = 256;
        e[i].textures[0].path = xstrdup(i ? "glass.png" : "fence.png");
        e[i].textures[0].width = e[i].textures[0].height = 64;
    }
    e[0].textures[1].path = xstrdup("fence_a.png");
    e[0].textures[1].width = e[0].textures[1].height = 64;
    e[1].textures[1].fill[0] = e[1].textures[1].fill[3] = 1;
}

/* The materials of make_layout, given in an unsorted order and sorted. */
static void add_materials(struct vt_layout *l)
{
    VT_CHECK_INT_EQ(vt_layout_alloc_materials(l, 3, NULL), 0);
    struct vt_layout_material *m = l->materials;
    m[0].name = xstrdup("glass"), m[0].entry = 1, m[0].layer_mask = 1;
    m[0].kd[0] = m[0].kd[1] = m[0].kd[2] = 1, m[0].ks[0] = 0.5, m[0].ns = 96, m[0].d = 0.5;
    m[0].illum = 4, m[0].alpha = VT_LAYOUT_ALPHA_BLEND;
    m[1].name = xstrdup("fence"), m[1].entry = 0, m[1].layer_mask = 3;
    m[1].kd[1] = 0.25, m[1].ke[2] = 2, m[1].illum = 1, m[1].alpha = VT_LAYOUT_ALPHA_TEST;
    m[2].name = xstrdup("bottle"), m[2].entry = 1, m[2].layer_mask = 1;
    m[2].ka[0] = 0.125, m[2].illum = 2; /* d 1 from the allocation, alpha none */
    vt_layout_sort_materials(l);
    VT_CHECK(strcmp(l->materials[0].name, "bottle") == 0);
    VT_CHECK(strcmp(l->materials[2].name, "glass") == 0);
}

static char *read_text(const char *path)
{
    FILE *f = fopen(path, "rb");
    static char text[16384];
    size_t len = f ? fread(text, 1, sizeof text - 1, f) : 0;
    text[len] = 0;
    if (f)
        fclose(f);
    return text;
}

static void materials_round_trip_with_their_constants(void)
{
    struct vt_layout l, r;
    struct vts_error err;
    make_layout(&l);
    add_materials(&l);
    VT_CHECK_INT_EQ(vt_layout_write("materials_rt.json", &l, &err), 0);
    VT_CHECK_INT_EQ(vt_layout_read("materials_rt.json", NULL, &r, &err), 0);
    VT_CHECK_INT_EQ(r.material_count, 3);
    for (uint32_t i = 0; i < 3 && r.material_count == 3; i++) {
        const struct vt_layout_material *a = &l.materials[i], *b = &r.materials[i];
        VT_CHECK_STR_EQ(a->name, b->name);
        VT_CHECK(a->entry == b->entry && a->layer_mask == b->layer_mask);
        VT_CHECK(memcmp(a->kd, b->kd, sizeof a->kd) == 0 &&
                 memcmp(a->ka, b->ka, sizeof a->ka) == 0);
        VT_CHECK(memcmp(a->ks, b->ks, sizeof a->ks) == 0 &&
                 memcmp(a->ke, b->ke, sizeof a->ke) == 0);
        VT_CHECK(a->ns == b->ns && a->d == b->d && a->illum == b->illum && a->alpha == b->alpha);
    }
    const struct vt_layout_material *g = vt_layout_material_find(&r, "glass");
    VT_CHECK(g && g->d == 0.5 && g->alpha == VT_LAYOUT_ALPHA_BLEND && g->ns == 96);
    const struct vt_layout_material *b = vt_layout_material_find(&r, "bottle");
    VT_CHECK(b && b->d == 1 && b->alpha == VT_LAYOUT_ALPHA_NONE && b->entry == 1);
    VT_CHECK(vt_layout_material_find(&r, "bottl") == NULL);
    const char *text = read_text("materials_rt.json");
    VT_CHECK(strstr(text,
                    "\"name\": \"fence\",\n   \"entry\": \"fence\",\n   \"layers\": [\n"
                    "    \"diffuse\",\n    \"alpha\"\n   ],\n   \"alpha\": \"test\",") != NULL);
    VT_CHECK(strstr(text, "\"name\": \"bottle\",\n   \"entry\": \"glass\",") != NULL);
    vt_layout_release(&r);
    vt_layout_release(&l);
    if (!getenv("KEEP"))
        remove("materials_rt.json");
}

static void layouts_without_materials_read_and_write_as_before(void)
{
    struct vt_layout l, r;
    struct vts_error err;
    make_layout(&l);
    VT_CHECK_INT_EQ(vt_layout_write("materials_none.json", &l, &err), 0);
    VT_CHECK(strstr(read_text("materials_none.json"), "materials") == NULL);
    VT_CHECK_INT_EQ(vt_layout_read("materials_none.json", NULL, &r, &err), 0);
    VT_CHECK_INT_EQ(r.material_count, 0);
    VT_CHECK(vt_layout_material_find(&r, "fence") == NULL);
    char *meta = vt_layout_materials_meta(&r, 1024, &err);
    VT_CHECK(meta && strcmp(meta, "[]") == 0);
    free(meta);
    vt_layout_release(&r);
    vt_layout_release(&l);
    if (!getenv("KEEP"))
        remove("materials_none.json");
}

static void metadata_is_one_compact_json_array(void)
{
    struct vt_layout l;
    struct vts_error err;
    make_layout(&l);
    add_materials(&l);
    VT_CHECK_INT_EQ(vt_layout_index(&l, &err), 0);
    char *meta = vt_layout_materials_meta(&l, 1 << 20, &err);
    VT_CHECK_STR_EQ(
        meta ? meta : "",
        "[{\"name\":\"bottle\",\"entry\":\"glass\",\"layers\":[\"diffuse\"],\"alpha\":\"none\","
        "\"Kd\":[0.0,0.0,0.0],\"Ka\":[0.125,0.0,0.0],\"Ks\":[0.0,0.0,0.0],\"Ke\":[0.0,0.0,0.0],"
        "\"Ns\":0.0,\"d\":1.0,\"illum\":2},"
        "{\"name\":\"fence\",\"entry\":\"fence\",\"layers\":[\"diffuse\",\"alpha\"],\"alpha\":"
        "\"test\",\"Kd\":[0.0,0.25,0.0],\"Ka\":[0.0,0.0,0.0],\"Ks\":[0.0,0.0,0.0],\"Ke\":[0.0,0.0,"
        "2.0],\"Ns\":0.0,\"d\":1.0,\"illum\":1},"
        "{\"name\":\"glass\",\"entry\":\"glass\",\"layers\":[\"diffuse\"],\"alpha\":\"blend\","
        "\"Kd\":[1.0,1.0,1.0],\"Ka\":[0.0,0.0,0.0],\"Ks\":[0.5,0.0,0.0],\"Ke\":[0.0,0.0,0.0],"
        "\"Ns\":96.0,\"d\":0.5,\"illum\":4}]");
    size_t n = meta ? strlen(meta) : 0;
    free(meta);
    /* what the store's metadata has left decides */
    VT_CHECK(vt_layout_materials_meta(&l, n - 1, &err) == NULL);
    VT_CHECK_INT_EQ(err.status, VTS_ERR_LIMIT);
    VT_CHECK_STR_CONTAINS(err.message, "more than the");
    meta = vt_layout_materials_meta(&l, n, &err);
    VT_CHECK(meta != NULL);
    free(meta);
    vt_layout_release(&l);
}

/* Each edit breaks one rule of the materials; vt_layout_check names it. */
static void expect_invalid(void (*edit)(struct vt_layout *), const char *part)
{
    struct vt_layout l;
    struct vts_error err;
    make_layout(&l);
    add_materials(&l);
    edit(&l);
    VT_CHECK(vt_layout_check(&l, "x.json", &err) < 0);
    VT_CHECK_STR_CONTAINS(err.message, part);
    vt_layout_release(&l);
}

static void one_missing(struct vt_layout *l)
{
    l->material_count = 2; /* the third is still freed: release goes by material_count */
    free(l->materials[2].name);
    l->materials[2].name = NULL;
}
static void renamed(struct vt_layout *l)
{
    l->materials[1].name[0] = 'g'; /* "gence" */
}
static void wrong_entry(struct vt_layout *l)
{
    l->materials[0].entry = 0;
}
static void fill_as_map(struct vt_layout *l)
{
    l->materials[2].layer_mask = 3;
}
static void past_layers(struct vt_layout *l)
{
    l->materials[1].layer_mask = 4;
}
static void bad_d(struct vt_layout *l)
{
    l->materials[2].d = 1.5;
}
static void negative_ks(struct vt_layout *l)
{
    l->materials[2].ks[1] = -0.1;
}
static void bad_alpha(struct vt_layout *l)
{
    l->materials[2].alpha = 3;
}

static void material_rules_are_checked(void)
{
    expect_invalid(one_missing, "'x.json': materials: 2 materials for 3 material names");
    expect_invalid(renamed, "materials[1] ('gence'): expected material 'fence'");
    expect_invalid(wrong_entry, "materials[0] ('bottle'): entry 0, but 'bottle' is a name of "
                                "entry 'glass'");
    expect_invalid(fill_as_map, "materials[2] ('glass'): layer 'alpha' is a fill of entry 'glass'");
    expect_invalid(past_layers, "materials[1] ('fence'): layers past the 2 of the layout");
    expect_invalid(bad_d, "materials[2] ('glass') has a d outside 0..1");
    expect_invalid(negative_ks, "materials[2] ('glass') has a colour");
    expect_invalid(bad_alpha, "materials[2] ('glass') has an unknown alpha mode");
}

/* A one-entry layout text with the given "materials" value. */
static void expect_parse_error(const char *materials, const char *part)
{
    char text[2048];
    snprintf(
        text, sizeof text,
        "{\"format\":\"vtpipe-atlas\",\"version\":1,\"width\":256,\"height\":256,"
        "\"tile_content\":256,\"border\":2,\"layers\":[{\"name\":\"diffuse\",\"map\":\"map_Kd\","
        "\"colour\":\"srgb\"}],\"entries\":[{\"name\":\"a\",\"aliases\":[\"b\"],\"x\":0,\"y\":0,"
        "\"width\":10,\"height\":10,\"cell_width\":16,\"cell_height\":16,\"alignment\":16,"
        "\"textures\":[{\"path\":\"t/a.png\",\"width\":10,\"height\":10}]}]%s%s}",
        materials ? ",\"materials\":" : "", materials ? materials : "");
    struct vt_layout l;
    struct vts_error err;
    int rc = vt_layout_parse_memory(text, strlen(text), "bad.json", NULL, &l, &err);
    if (part) {
        VT_CHECK(rc < 0);
        VT_CHECK_STR_CONTAINS(err.message, part);
        VT_CHECK(strchr(err.message, '\n') == NULL);
    } else {
        VT_CHECK_INT_EQ(rc, 0);
        VT_CHECK_INT_EQ(l.material_count, materials ? 2 : 0);
    }
    vt_layout_release(&l);
}

#define MAT(name, entry, rest)                                                                     \
    "{\"name\":\"" name "\",\"entry\":\"" entry "\",\"layers\":[\"diffuse\"],\"alpha\":\"none\","  \
    "\"Kd\":[1,1,1],\"Ka\":[0,0,0],\"Ks\":[0,0,0],\"Ke\":[0,0,0],\"Ns\":0,\"d\":1,"                \
    "\"illum\":2" rest "}"

static void reader_refuses_bad_materials_naming_the_field(void)
{
    expect_parse_error(NULL, NULL); /* older layouts have none */
    expect_parse_error("[" MAT("a", "a", "") "," MAT("b", "a", "") "]", NULL);
    expect_parse_error("{}", "'bad.json': materials: expected an array");
    expect_parse_error("[" MAT("a", "a", "") "]", "materials: 1 materials for 2 material names");
    expect_parse_error("[" MAT("b", "a", "") "," MAT("a", "a", "") "]",
                       "materials[0] ('b'): expected material 'a'");
    expect_parse_error("[" MAT("a", "a", "") "," MAT("b", "b", "") "]",
                       "materials[1].entry: not the name of an entry");
    expect_parse_error("[" MAT("a", "a", "") "," MAT("b", "z", "") "]",
                       "materials[1].entry: not the name of an entry");
    expect_parse_error("[" MAT("a", "a", ",\"alpha\":\"cutout\"") "," MAT("b", "a", "") "]",
                       "duplicate object key");
    expect_parse_error(
        "[{\"name\":\"a\",\"entry\":\"a\",\"layers\":[\"normal\"]}," MAT("b", "a", "") "]",
        "materials[0].layers: no layer 'normal' in the layout");
    expect_parse_error("[{\"name\":\"a\",\"entry\":\"a\",\"layers\":[\"diffuse\",\"diffuse\"]}]",
                       "materials: 1 materials");
    expect_parse_error("[{\"name\":\"a\",\"entry\":\"a\",\"layers\":[\"diffuse\",\"diffuse\"]},"
                       "{}]",
                       "materials[0].layers: layer 'diffuse' given twice");
    expect_parse_error("[{\"name\":\"a\",\"entry\":\"a\",\"layers\":[],\"Kd\":[1,1]},{}]",
                       "materials[0].Kd: expected [r, g, b]: three numbers >= 0");
    expect_parse_error("[{\"name\":\"a\",\"entry\":\"a\",\"layers\":[],\"Kd\":[1,1,1],"
                       "\"Ka\":[0,0,0],\"Ks\":[0,0,0],\"Ke\":[0,-1,0]},{}]",
                       "materials[0].Ke: expected [r, g, b]");
    expect_parse_error("[{\"name\":\"a\",\"entry\":\"a\",\"layers\":[],\"Kd\":[1,1,1],"
                       "\"Ka\":[0,0,0],\"Ks\":[0,0,0],\"Ke\":[0,0,0],\"Ns\":1,\"d\":2},{}]",
                       "materials[0].d: expected a number 0..1");
    expect_parse_error("[{\"name\":\"a\",\"entry\":\"a\",\"layers\":[],\"Kd\":[1,1,1],"
                       "\"Ka\":[0,0,0],\"Ks\":[0,0,0],\"Ke\":[0,0,0],\"Ns\":1,\"d\":1,"
                       "\"illum\":2.5},{}]",
                       "materials[0].illum: expected an integer 0..100");
    expect_parse_error("[{\"name\":\"a\",\"entry\":\"a\",\"layers\":[],\"Kd\":[1,1,1],"
                       "\"Ka\":[0,0,0],\"Ks\":[0,0,0],\"Ke\":[0,0,0],\"Ns\":1,\"d\":1,"
                       "\"illum\":2,\"alpha\":\"cutout\"},{}]",
                       "materials[0].alpha: expected \"none\", \"test\" or \"blend\"");
    expect_parse_error("[{\"name\":\"a\",\"entry\":\"a\",\"layers\":[],\"Kd\":[1,1,1],"
                       "\"Ka\":[0,0,0],\"Ks\":[0,0,0],\"Ke\":[0,0,0],\"Ns\":1,\"d\":1},{}]",
                       "materials[0].illum: missing");
}

int main(void)
{
    VT_RUN(materials_round_trip_with_their_constants);
    VT_RUN(layouts_without_materials_read_and_write_as_before);
    VT_RUN(metadata_is_one_compact_json_array);
    VT_RUN(material_rules_are_checked);
    VT_RUN(reader_refuses_bad_materials_naming_the_field);
    return vt_test_main_result();
}
