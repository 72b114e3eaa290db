/* formats/export's plan: level counts, tile rectangles and file names of each layout, on sizes
 * with odd halvings, against values worked out by hand from the Deep Zoom, IIIF and XYZ rules. */
#include "internal/vt_export_impl.h"
#include "vt_test.h"

static struct vt_export_rect rect(const struct vt_export_plan *p, uint32_t j, uint32_t c,
                                  uint32_t r)
{
    return vt_export_tile_rect(p, j, c, r);
}

static const char *path(const struct vt_export_plan *p, uint32_t j, uint32_t c, uint32_t r)
{
    static char buf[256];
    return vt_export_tile_path(p, "img", j, c, r, buf, sizeof buf) < 0 ? NULL : buf;
}

static void dzi_levels_go_down_to_one_texel(void)
{
    struct vt_export_plan p;
    vt_export_plan_make(&p, VT_EXPORT_DZI, 1000, 700, 124, 1, "png");
    VT_CHECK_INT_EQ(p.level_count, 11); /* ceil(log2(1000)) = 10: levels 0..10 */
    VT_CHECK_INT_EQ(vt_export_level_number(&p, 0), 10);
    VT_CHECK_INT_EQ(vt_export_level_width(&p, 10), 1);
    VT_CHECK_INT_EQ(vt_export_level_height(&p, 10), 1);
    VT_CHECK_INT_EQ(vt_export_level_width(&p, 3), 125); /* ceil(1000 / 8) */
    VT_CHECK_INT_EQ(vt_export_level_height(&p, 3), 88); /* ceil(700 / 8) */
    vt_export_plan_make(&p, VT_EXPORT_DZI, 1024, 1, 256, 0, "png");
    VT_CHECK_INT_EQ(p.level_count, 11); /* 1024 = 2^10 exactly */
    vt_export_plan_make(&p, VT_EXPORT_DZI, 1, 1, 256, 0, "png");
    VT_CHECK_INT_EQ(p.level_count, 1);
}

static void dzi_tiles_overlap_on_inner_sides_only(void)
{
    struct vt_export_plan p;
    vt_export_plan_make(&p, VT_EXPORT_DZI, 1000, 700, 124, 2, "png");
    VT_CHECK_INT_EQ(vt_export_tiles_x(&p, 0), 9);
    VT_CHECK_INT_EQ(vt_export_tiles_y(&p, 0), 6);
    struct vt_export_rect a = rect(&p, 0, 0, 0), b = rect(&p, 0, 1, 1), e = rect(&p, 0, 8, 5);
    VT_CHECK(a.x0 == 0 && a.y0 == 0 && a.x1 == 126 && a.y1 == 126);
    VT_CHECK(b.x0 == 122 && b.y0 == 122 && b.x1 == 250 && b.y1 == 250);
    VT_CHECK(e.x0 == 990 && e.y0 == 618 && e.x1 == 1000 && e.y1 == 700);
    VT_CHECK_STR_EQ(path(&p, 0, 8, 5), "img_files/10/8_5.png");
    VT_CHECK_STR_EQ(path(&p, 10, 0, 0), "img_files/0/0_0.png");
}

static void iiif_paths_are_canonical(void)
{
    struct vt_export_plan p;
    vt_export_plan_make(&p, VT_EXPORT_IIIF, 1000, 700, 256, 9, "jpg");
    VT_CHECK_INT_EQ(p.overlap_px, 0);
    VT_CHECK_INT_EQ(p.level_count, 3); /* 1000 -> 500 -> 250 fits 256 */
    VT_CHECK_STR_EQ(path(&p, 0, 0, 0), "0,0,256,256/256,256/0/default.jpg");
    VT_CHECK_STR_EQ(path(&p, 0, 3, 2), "768,512,232,188/232,188/0/default.jpg");
    VT_CHECK_STR_EQ(path(&p, 1, 1, 0), "512,0,488,512/244,256/0/default.jpg");
    VT_CHECK_STR_EQ(path(&p, 2, 0, 0), "full/250,175/0/default.jpg");
    vt_export_plan_make(&p, VT_EXPORT_IIIF, 200, 100, 256, 0, "png");
    VT_CHECK_INT_EQ(p.level_count, 1);
    VT_CHECK_STR_EQ(path(&p, 0, 0, 0), "full/max/0/default.png");
}

static void xyz_zoom_zero_is_one_tile(void)
{
    struct vt_export_plan p;
    vt_export_plan_make(&p, VT_EXPORT_XYZ, 1000, 700, 100, 0, "png");
    VT_CHECK_INT_EQ(p.level_count, 5); /* 1000 / 16 = 62.5 -> 63 <= 100 */
    VT_CHECK_INT_EQ(vt_export_tiles_x(&p, 0), 10);
    VT_CHECK_INT_EQ(vt_export_tiles_y(&p, 0), 7);
    VT_CHECK_STR_EQ(path(&p, 0, 9, 6), "4/9/6.png");
    VT_CHECK_STR_EQ(path(&p, 4, 0, 0), "0/0/0.png");
    struct vt_export_rect e = rect(&p, 1, 4, 3);
    VT_CHECK(e.x0 == 400 && e.x1 == 500 && e.y0 == 300 && e.y1 == 350);
}

static void a_long_name_does_not_fit(void)
{
    struct vt_export_plan p;
    char small[8];
    vt_export_plan_make(&p, VT_EXPORT_DZI, 10, 10, 4, 0, "png");
    VT_CHECK_INT_EQ(vt_export_tile_path(&p, "image", 0, 0, 0, small, sizeof small), -1);
}

int main(void)
{
    VT_RUN(dzi_levels_go_down_to_one_texel);
    VT_RUN(dzi_tiles_overlap_on_inner_sides_only);
    VT_RUN(iiif_paths_are_canonical);
    VT_RUN(xyz_zoom_zero_is_one_tile);
    VT_RUN(a_long_name_does_not_fit);
    return vt_test_main_result();
}
