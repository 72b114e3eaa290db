/* Pack materials of atlas.json ("wang_materials", docs/atlas-format.md "Pack materials"): round
 * trip, lookup, layouts without them written as before, and every refusal naming the field. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vt_layout.h"
#include "vt_test.h"
#include "vts.h"

#define HEAD                                                                                       \
    "{\"format\":\"vtpipe-atlas\",\"version\":1,\"width\":256,\"height\":256,"                     \
    "\"tile_content\":256,\"border\":2,\"layers\":[{\"name\":\"diffuse\",\"map\":\"map_Kd\","      \
    "\"colour\":\"srgb\"}],\"entries\":[{\"name\":\"a\",\"aliases\":[\"b\"],\"x\":0,\"y\":0,"      \
    "\"width\":10,\"height\":10,\"cell_width\":16,\"cell_height\":16,\"alignment\":16,"            \
    "\"textures\":[{\"path\":\"t/a.png\",\"width\":10,\"height\":10}]}]"

#define WANG(name, rest)                                                                           \
    "{\"name\":\"" name "\",\"pack\":\"p/grass.vts\",\"scale\":4,\"alpha\":\"none\","              \
    "\"Kd\":[1,1,1],\"Ka\":[0,0,0],\"Ks\":[0.25,0.25,0.25],\"Ke\":[0,0,0],\"Ns\":0,\"d\":1,"       \
    "\"illum\":2" rest "}"

static int parse(const char *wangs, struct vt_layout *l, struct vts_error *err)
{
    char text[4096];
    snprintf(text, sizeof text, HEAD "%s%s}", wangs ? ",\"wang_materials\":" : "",
             wangs ? wangs : "");
    return vt_layout_parse_memory(text, strlen(text), "d/atlas.json", NULL, l, err);
}

static void expect_error(const char *wangs, const char *part)
{
    struct vt_layout l;
    struct vts_error err;
    VT_CHECK(parse(wangs, &l, &err) < 0);
    VT_CHECK_STR_CONTAINS(err.message, part);
    VT_CHECK(strchr(err.message, '\n') == NULL);
    vt_layout_release(&l);
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

static void pack_materials_read_find_and_round_trip(void)
{
    struct vt_layout l, r;
    struct vts_error err;
    VT_CHECK_INT_EQ(parse("[" WANG("grass", "") "," WANG("sand", "") "]", &l, &err), 0);
    VT_CHECK_INT_EQ(l.wang_count, 2);
    const struct vt_layout_wang *w = vt_layout_wang_find(&l, "sand");
    VT_CHECK(w && w->scale == 4 && strcmp(w->pack, "p/grass.vts") == 0);
    VT_CHECK(w && strcmp(w->resolved, "d/p/grass.vts") == 0); /* against atlas.json's folder */
    VT_CHECK(w && w->m.ks[1] == 0.25 && w->m.illum == 2 && w->m.d == 1);
    VT_CHECK(vt_layout_wang_find(&l, "gras") == NULL);
    VT_CHECK(vt_layout_wang_find(&l, "a") == NULL); /* an entry is not a pack material */
    VT_CHECK(vt_layout_find(&l, "grass") == NULL);  /* and a pack material has no entry */
    VT_CHECK_INT_EQ(vt_layout_write("wang_rt.json", &l, &err), 0);
    VT_CHECK(strstr(read_text("wang_rt.json"), "\"wang_materials\": [\n  {\n   \"name\": "
                                               "\"grass\",\n   \"pack\": \"p/grass.vts\",\n"
                                               "   \"scale\": 4.0,") != NULL);
    VT_CHECK_INT_EQ(vt_layout_read("wang_rt.json", NULL, &r, &err), 0);
    VT_CHECK_INT_EQ(r.wang_count, 2);
    for (uint32_t i = 0; i < 2 && r.wang_count == 2; i++) {
        VT_CHECK_STR_EQ(r.wangs[i].m.name, l.wangs[i].m.name);
        VT_CHECK_STR_EQ(r.wangs[i].pack, l.wangs[i].pack);
        VT_CHECK(r.wangs[i].scale == l.wangs[i].scale);
        VT_CHECK(memcmp(r.wangs[i].m.ks, l.wangs[i].m.ks, sizeof r.wangs[i].m.ks) == 0);
    }
    vt_layout_release(&r);
    /* built in memory in any order: sorted by vt_layout_sort_materials, checked by the writer */
    VT_CHECK_STR_EQ(l.wangs[0].m.name, "grass");
    char *t = l.wangs[0].m.name;
    l.wangs[0].m.name = l.wangs[1].m.name;
    l.wangs[1].m.name = t;
    VT_CHECK(vt_layout_write("wang_rt.json", &l, &err) < 0);
    VT_CHECK_STR_CONTAINS(err.message, "wang_materials[1] ('grass'): not sorted by name");
    vt_layout_sort_materials(&l);
    VT_CHECK_INT_EQ(vt_layout_write("wang_rt.json", &l, &err), 0);
    vt_layout_release(&l);
    /* without pack materials: no key written */
    VT_CHECK_INT_EQ(parse(NULL, &l, &err), 0);
    VT_CHECK_INT_EQ(l.wang_count, 0);
    VT_CHECK(vt_layout_wang_find(&l, "grass") == NULL);
    VT_CHECK_INT_EQ(vt_layout_write("wang_rt.json", &l, &err), 0);
    VT_CHECK(strstr(read_text("wang_rt.json"), "wang") == NULL);
    vt_layout_release(&l);
    if (!getenv("KEEP"))
        remove("wang_rt.json");
}

static void reader_refuses_bad_pack_materials(void)
{
    expect_error("{}", "'d/atlas.json': wang_materials: expected an array");
    expect_error("[1]", "wang_materials[0]: expected an object");
    expect_error("[{\"name\":\"g\"}]", "wang_materials[0].pack: missing");
    expect_error("[" WANG("a", "") "]", "wang_materials[0]: name 'a' is also an entry's name");
    expect_error("[" WANG("b", "") "]", "name 'b' is also an entry's name or alias");
    expect_error("[" WANG("g", "") "," WANG("g", "") "]",
                 "wang_materials[1] ('g'): not sorted by name, or given twice");
    expect_error("[" WANG("h", "") "," WANG("g", "") "]", "not sorted by name");
    expect_error("[" WANG("", "") "]", "wang_materials[0]: empty name or pack");
}

static void reader_refuses_bad_scale_and_constants(void)
{
    const char *bad_scale = "[{\"name\":\"g\",\"pack\":\"p.vts\",\"scale\":0,\"alpha\":\"none\","
                            "\"Kd\":[1,1,1],\"Ka\":[0,0,0],\"Ks\":[0,0,0],\"Ke\":[0,0,0],"
                            "\"Ns\":0,\"d\":1,\"illum\":2}]";
    expect_error(bad_scale, "wang_materials[0].scale: expected a number");
    const char *bad_d = "[{\"name\":\"g\",\"pack\":\"p.vts\",\"scale\":1,\"alpha\":\"none\","
                        "\"Kd\":[1,1,1],\"Ka\":[0,0,0],\"Ks\":[0,0,0],\"Ke\":[0,0,0],"
                        "\"Ns\":0,\"d\":2,\"illum\":2}]";
    expect_error(bad_d, "wang_materials[0].d: expected a number 0..1");
    const char *bad_alpha = "[{\"name\":\"g\",\"pack\":\"p.vts\",\"scale\":1,\"alpha\":\"x\","
                            "\"Kd\":[1,1,1],\"Ka\":[0,0,0],\"Ks\":[0,0,0],\"Ke\":[0,0,0],"
                            "\"Ns\":0,\"d\":1,\"illum\":2}]";
    expect_error(bad_alpha, "wang_materials[0].alpha: expected \"none\"");
    const char *no_kd = "[{\"name\":\"g\",\"pack\":\"p.vts\",\"scale\":1,\"alpha\":\"none\","
                        "\"Ka\":[0,0,0],\"Ks\":[0,0,0],\"Ke\":[0,0,0],\"Ns\":0,\"d\":1,"
                        "\"illum\":2}]";
    expect_error(no_kd, "wang_materials[0].Kd: missing");
    const char *empty_pack = "[{\"name\":\"g\",\"pack\":\"\",\"scale\":1,\"alpha\":\"none\","
                             "\"Kd\":[1,1,1],\"Ka\":[0,0,0],\"Ks\":[0,0,0],\"Ke\":[0,0,0],"
                             "\"Ns\":0,\"d\":1,\"illum\":2}]";
    expect_error(empty_pack, "wang_materials[0]: empty pack");
}

int main(void)
{
    VT_RUN(pack_materials_read_find_and_round_trip);
    VT_RUN(reader_refuses_bad_pack_materials);
    VT_RUN(reader_refuses_bad_scale_and_constants);
    return vt_test_main_result();
}
