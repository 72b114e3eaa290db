/* formats/output/vt_georef_file: the transform of a level and of a tile's payload, the world file's
 * name and numbers, the .aux.xml's content (escaped WKT, per-band nodata), nothing written without
 * georeferencing, a wrong transform caught. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "output_fixture.h"
#include "vt_georef_file.h"
#include "vt_test.h"

static const double utm[6] = {500000, 10, 0, 4000000, 0, -10};

/* The whole file, NUL-terminated (static buffer), or "" when missing. */
static const char *slurp(const char *path)
{
    static char buf[8192];
    buf[0] = '\0';
    FILE *f = fopen(path, "rb");
    if (!f)
        return buf;
    size_t n = fread(buf, 1, sizeof buf - 1, f);
    buf[n] = '\0';
    fclose(f);
    return buf;
}

static bool same6(const double a[6], const double b[6])
{
    for (int i = 0; i < 6; i++)
        if (a[i] != b[i])
            return false;
    return true;
}

static void region_scales_and_moves(void)
{
    double t[6];
    vt_georef_region(utm, 0, 0, 0, t);
    VT_CHECK(same6(t, utm));
    vt_georef_region(utm, 2, 0, 0, t); /* level 2: 40 m texels, same origin */
    const double l2[6] = {500000, 40, 0, 4000000, 0, -40};
    VT_CHECK(same6(t, l2));
    vt_georef_region(utm, 1, -2, 62, t); /* a tile's payload starting in its border */
    const double tile[6] = {500000 - 2 * 20, 20, 0, 4000000 - 62 * 20, 0, -20};
    VT_CHECK(same6(t, tile));
    VT_CHECK(!same6(t, l2));                       /* the comparison fails on a wrong transform */
    const double rot[6] = {100, 2, 1, 200, 1, -2}; /* rotation terms move both axes */
    vt_georef_region(rot, 1, 3, 5, t);
    const double rot_moved[6] = {100 + 6 * 2 + 10 * 1, 4, 2, 200 + 6 * 1 + 10 * -2, 2, -4};
    VT_CHECK(same6(t, rot_moved));
}

static void writes_aux_xml_and_world_file(void)
{
    const char *wkt = "PROJCRS[\"A & <B>\",UNIT[\"metre\",1]]";
    struct vt_georef g = {true, {0}, wkt, "-9999", 2};
    memcpy(g.transform, utm, sizeof utm);
    char image[512], world[512];
    snprintf(image, sizeof image, "%s", test_path("x.tiff"));
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(vt_georef_file_write(image, &g, world, sizeof world, &err), 0);
    VT_CHECK_STR_EQ(world, test_path("x.tfw"));
    VT_CHECK_STR_EQ(slurp(world), "10\n0\n0\n-10\n500005\n3999995\n");
    char aux[600];
    snprintf(aux, sizeof aux, "%s.aux.xml", image);
    const char *x = slurp(aux);
    VT_CHECK_STR_CONTAINS(x, "<SRS dataAxisToSRSAxisMapping=\"1,2\">PROJCRS[\"A &amp; &lt;B&gt;\"");
    VT_CHECK_STR_CONTAINS(x, "<GeoTransform>500000, 10, 0, 4000000, 0, -10</GeoTransform>");
    VT_CHECK_STR_CONTAINS(x, "<PAMRasterBand band=\"2\">\n    <NoDataValue>-9999</NoDataValue>");
    VT_CHECK(!strstr(x, "band=\"3\""));
    VT_CHECK(!strstr(x, "A & <B>")); /* unescaped WKT would not be XML */
    unlink(world);
    unlink(aux);
    /* PNG: .pgw; no extension: .wld */
    snprintf(image, sizeof image, "%s", test_path("y.png"));
    VT_CHECK_INT_EQ(vt_georef_file_write(image, &g, world, sizeof world, &err), 0);
    VT_CHECK_STR_EQ(world, test_path("y.pgw"));
    unlink(world);
    snprintf(aux, sizeof aux, "%s.aux.xml", image);
    unlink(aux);
    snprintf(image, sizeof image, "%s", test_path("noext"));
    VT_CHECK_INT_EQ(vt_georef_file_write(image, &g, world, sizeof world, &err), 0);
    VT_CHECK_STR_EQ(world, test_path("noext.wld"));
    unlink(world);
    snprintf(aux, sizeof aux, "%s.aux.xml", image);
    unlink(aux);
    VT_CHECK_INT_EQ(dir_entry_count(), 0);
}

static void nothing_without_georeferencing(void)
{
    struct vt_georef g = {false, {0}, NULL, "0", 1};
    char world[512] = "x";
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(vt_georef_file_write(test_path("z.png"), &g, world, sizeof world, &err), 0);
    VT_CHECK_STR_EQ(world, "");
    VT_CHECK_INT_EQ(dir_entry_count(), 0);
    /* a CRS alone: .aux.xml, no world file */
    g.crs_wkt = "GEOGCRS[\"WGS 84\"]";
    VT_CHECK_INT_EQ(vt_georef_file_write(test_path("z.png"), &g, world, sizeof world, &err), 0);
    VT_CHECK_STR_EQ(world, "");
    VT_CHECK(file_exists(test_path("z.png.aux.xml")));
    VT_CHECK(!strstr(slurp(test_path("z.png.aux.xml")), "GeoTransform"));
    unlink(test_path("z.png.aux.xml"));
}

static void missing_directory_fails_with_path(void)
{
    struct vt_georef g = {true, {0}, NULL, NULL, 1};
    memcpy(g.transform, utm, sizeof utm);
    char image[512], world[512];
    snprintf(image, sizeof image, "%s/no-such-dir/a.png", test_dir);
    struct vts_error err = {0};
    VT_CHECK(vt_georef_file_write(image, &g, world, sizeof world, &err) < 0);
    VT_CHECK_STR_CONTAINS(err.message, "no-such-dir/a.png.aux.xml");
}

int main(void)
{
    const char *tmp = getenv("TMPDIR");
    snprintf(test_dir, sizeof test_dir, "%s/test_vt_georef_file.XXXXXX",
             tmp && *tmp ? tmp : "/tmp");
    if (!mkdtemp(test_dir)) {
        perror("mkdtemp");
        return 1;
    }
    VT_RUN(region_scales_and_moves);
    VT_RUN(writes_aux_xml_and_world_file);
    VT_RUN(nothing_without_georeferencing);
    VT_RUN(missing_directory_fails_with_path);
    if (rmdir(test_dir) != 0)
        fprintf(stderr, "cannot remove %s: %s\n", test_dir, strerror(errno));
    return vt_test_main_result();
}
