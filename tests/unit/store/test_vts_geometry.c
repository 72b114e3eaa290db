/* Geometry, CRC-32C and Hilbert order: pure functions with known answers. */
#include <stdlib.h>

#include "internal/vts_crc32c.h"
#include "internal/vts_order.h"
#include "vt_test.h"
#include "vts.h"

static void level_counts_match_halving_with_ceiling(void)
{
    /* content 64: 1x1 -> 1 level; 3x5 -> 1; 257x129 -> 257,129 / 129,65 / 65,33 / 33,17 */
    VT_CHECK_INT_EQ(vts_full_level_count(1, 1, 64), 1);
    VT_CHECK_INT_EQ(vts_full_level_count(3, 5, 64), 1);
    VT_CHECK_INT_EQ(vts_full_level_count(257, 129, 64), 4);
    VT_CHECK_INT_EQ(vts_full_level_count(4097, 3, 64), 8);
    VT_CHECK_INT_EQ(vts_full_level_count(1000, 600, 248), 4); /* 1000 500 250 125 */
    VT_CHECK_INT_EQ(vts_full_level_count(1u << 20, 1u << 20, 256), 13);
    VT_CHECK_INT_EQ(vts_full_level_count(0, 5, 64), 0);

    struct vts_geometry g = {257, 129, 64, 2, 68, 4, 1, 0};
    VT_CHECK_INT_EQ(vts_geometry_check(&g, NULL), 0);
    struct vts_level L;
    vts_geometry_level(&g, 1, &L);
    VT_CHECK_INT_EQ(L.width, 129);
    VT_CHECK_INT_EQ(L.height, 65);
    VT_CHECK_INT_EQ(L.tiles_x, 3);
    VT_CHECK_INT_EQ(L.tiles_y, 2);
    VT_CHECK_INT_EQ(L.first_tile, 5 * 3);
    vts_geometry_level(&g, 3, &L);
    VT_CHECK_INT_EQ(L.width, 33);
    VT_CHECK_INT_EQ(L.height, 17);
    VT_CHECK_INT_EQ(L.tiles_x * L.tiles_y, 1);
    VT_CHECK_INT_EQ(vts_geometry_tiles_per_layer(&g), 15 + 6 + 2 + 1);
}

static void geometry_check_rejects_each_bad_field(void)
{
    struct vts_geometry good = {1000, 600, 248, 4, 256, 3, 2, 0};
    struct vts_error err;
    VT_CHECK_INT_EQ(vts_geometry_check(&good, &err), 0);
    struct vts_geometry g = good;
    g.tile_payload_px = 255;
    VT_CHECK_INT_EQ(vts_geometry_check(&g, &err), VTS_ERR_ARG);
    VT_CHECK_STR_CONTAINS(err.message, "payload 255");
    g = good;
    g.level_count = 5;
    VT_CHECK_INT_EQ(vts_geometry_check(&g, &err), VTS_ERR_ARG);
    g = good;
    g.width = 0;
    VT_CHECK_INT_EQ(vts_geometry_check(&g, &err), VTS_ERR_LIMIT);
    g = good;
    g.layer_count = VTS_MAX_LAYERS + 1;
    VT_CHECK_INT_EQ(vts_geometry_check(&g, &err), VTS_ERR_LIMIT);
    g = good;
    g.border_px = 300;
    g.tile_payload_px = 848;
    VT_CHECK_INT_EQ(vts_geometry_check(&g, &err), VTS_ERR_ARG);
    /* 2^30 square with 1 px tiles: far more than 2^32 tiles */
    struct vts_geometry huge = {1u << 30, 1u << 30, 1, 0, 1, 31, 1, 0};
    VT_CHECK_INT_EQ(vts_geometry_check(&huge, &err), VTS_ERR_LIMIT);
}

static void crc32c_matches_published_check_values(void)
{
    VT_CHECK_INT_EQ(vts_crc32c(0, "123456789", 9), 0xE3069283u);
    VT_CHECK_INT_EQ(vts_crc32c(0, "", 0), 0);
    unsigned char zeros[32] = {0};
    VT_CHECK_INT_EQ(vts_crc32c(0, zeros, 32), 0x8A9136AAu); /* RFC 3720 B.4 */
    /* extending in pieces equals one pass, at every split point and odd alignment */
    unsigned char buf[300];
    for (int i = 0; i < 300; i++)
        buf[i] = (unsigned char)(i * 31 + 7);
    uint32_t whole = vts_crc32c(0, buf + 1, 299);
    for (int cut = 0; cut <= 299; cut += 13)
        VT_CHECK_INT_EQ(
            vts_crc32c(vts_crc32c(0, buf + 1, (size_t)cut), buf + 1 + cut, (size_t)(299 - cut)),
            whole);
}

static void hilbert_order_visits_neighbours(void)
{
    /* the 2x2 curve: (0,0) (0,1) (1,1) (1,0) */
    VT_CHECK_INT_EQ(vts_hilbert_index(1, 0, 0), 0);
    VT_CHECK_INT_EQ(vts_hilbert_index(1, 0, 1), 1);
    VT_CHECK_INT_EQ(vts_hilbert_index(1, 1, 1), 2);
    VT_CHECK_INT_EQ(vts_hilbert_index(1, 1, 0), 3);
    /* on a full 16x16 grid, consecutive tiles are edge neighbours and every tile appears once */
    uint64_t order[256];
    VT_CHECK_INT_EQ(vts_order_level(16, 16, order, NULL), 0);
    int seen[256] = {0};
    for (int i = 0; i < 256; i++) {
        seen[order[i]]++;
        if (i > 0) {
            int dx = (int)(order[i] % 16) - (int)(order[i - 1] % 16);
            int dy = (int)(order[i] / 16) - (int)(order[i - 1] / 16);
            VT_CHECK_INT_EQ(abs(dx) + abs(dy), 1);
        }
    }
    for (int i = 0; i < 256; i++)
        VT_CHECK_INT_EQ(seen[i], 1);
    /* non-square grids keep every tile exactly once */
    uint64_t odd[5 * 3];
    VT_CHECK_INT_EQ(vts_order_level(5, 3, odd, NULL), 0);
    int seen_odd[15] = {0};
    for (int i = 0; i < 15; i++)
        seen_odd[odd[i]]++;
    for (int i = 0; i < 15; i++)
        VT_CHECK_INT_EQ(seen_odd[i], 1);
}

int main(void)
{
    VT_RUN(level_counts_match_halving_with_ceiling);
    VT_RUN(geometry_check_rejects_each_bad_field);
    VT_RUN(crc32c_matches_published_check_values);
    VT_RUN(hilbert_order_visits_neighbours);
    return vt_test_main_result();
}
