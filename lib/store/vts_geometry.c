/* Pure functions over store geometry and the stable names of on-disk enums (declared in vts.h). */
#include <stdio.h>
#include <string.h>

#include "vt_checked.h"
#include "vt_error.h"
#include "vt_image.h"
#include "vts.h"

/* Upper bound on index entries: keeps every product below 2^64 and the index within reason
 * (2^32 tiles of 16 bytes = 64 GiB of index). */
#define VTS_MAX_TILES (1ull << 32)

static uint32_t level_extent(uint32_t size, uint32_t level)
{
    return (uint32_t)(((uint64_t)size + (1ull << level) - 1) >> level);
}

uint32_t vts_full_level_count(uint32_t width, uint32_t height, uint32_t tile_content_px)
{
    if (width == 0 || height == 0 || tile_content_px == 0)
        return 0;
    uint32_t levels = 1;
    while (level_extent(width, levels - 1) > tile_content_px ||
           level_extent(height, levels - 1) > tile_content_px)
        levels++;
    return levels;
}

int vts_geometry_level(const struct vts_geometry *g, uint32_t level, struct vts_level *out)
{
    if (level >= g->level_count) {
        memset(out, 0, sizeof *out);
        return VTS_ERR_RANGE;
    }
    uint64_t first = 0;
    for (uint32_t l = 0; l <= level; l++) {
        out->width = level_extent(g->width, l);
        out->height = level_extent(g->height, l);
        out->tiles_x = (out->width + g->tile_content_px - 1) / g->tile_content_px;
        out->tiles_y = (out->height + g->tile_content_px - 1) / g->tile_content_px;
        out->first_tile = first;
        first += (uint64_t)out->tiles_x * out->tiles_y;
    }
    return 0;
}

uint64_t vts_geometry_tiles_per_layer(const struct vts_geometry *g)
{
    struct vts_level last;
    vts_geometry_level(g, g->level_count - 1, &last);
    return last.first_tile + (uint64_t)last.tiles_x * last.tiles_y;
}

int vts_geometry_check(const struct vts_geometry *g, struct vts_error *err)
{
    if (g->width == 0 || g->height == 0 || g->width > VTS_MAX_DIMENSION ||
        g->height > VTS_MAX_DIMENSION)
        return vt_error_set(err, VTS_ERR_LIMIT, "size %ux%u is outside 1..%u", g->width, g->height,
                            VTS_MAX_DIMENSION);
    if (g->tile_content_px == 0 || g->border_px > g->tile_content_px)
        return vt_error_set(err, VTS_ERR_ARG, "tile content %u px with border %u px is invalid",
                            g->tile_content_px, g->border_px);
    uint64_t payload = (uint64_t)g->tile_content_px + 2ull * g->border_px;
    if (payload != g->tile_payload_px)
        return vt_error_set(err, VTS_ERR_ARG, "tile payload %u px != content %u + 2 * border %u",
                            g->tile_payload_px, g->tile_content_px, g->border_px);
    if (payload > VTS_MAX_PAYLOAD_PX)
        return vt_error_set(err, VTS_ERR_LIMIT, "tile payload %u px is above the limit %u",
                            g->tile_payload_px, VTS_MAX_PAYLOAD_PX);
    uint32_t full = vts_full_level_count(g->width, g->height, g->tile_content_px);
    if (g->level_count == 0 || g->level_count > full)
        return vt_error_set(err, VTS_ERR_ARG,
                            "%u levels requested, %ux%u with %u px tiles has 1..%u", g->level_count,
                            g->width, g->height, g->tile_content_px, full);
    if (g->layer_count == 0 || g->layer_count > VTS_MAX_LAYERS)
        return vt_error_set(err, VTS_ERR_LIMIT, "%u layers is outside 1..%u", g->layer_count,
                            VTS_MAX_LAYERS);
    uint64_t tiles;
    if (!vt_u64_mul(vts_geometry_tiles_per_layer(g), g->layer_count, &tiles) ||
        tiles > VTS_MAX_TILES)
        return vt_error_set(err, VTS_ERR_LIMIT,
                            "%ux%u with %u px tiles and %u layers has too many tiles (limit %llu)",
                            g->width, g->height, g->tile_content_px, g->layer_count,
                            (unsigned long long)VTS_MAX_TILES);
    return 0;
}

unsigned vts_sample_bytes(uint32_t sample)
{
    return vt_sample_bytes(sample);
}

size_t vts_layer_tile_bytes(const struct vts_geometry *g, const struct vts_layer *layer)
{
    return (size_t)g->tile_payload_px * g->tile_payload_px * layer->channels *
           vts_sample_bytes(layer->sample);
}

const char *vts_sample_name(uint32_t sample)
{
    static const char *const names[] = {"?", "u8", "u16", "f16", "f32"};
    return sample < sizeof names / sizeof names[0] ? names[sample] : "?";
}

const char *vts_colour_name(uint32_t colour)
{
    static const char *const names[] = {"?", "srgb", "linear", "normal", "data"};
    return colour < sizeof names / sizeof names[0] ? names[colour] : "?";
}

void vts_codec_name(uint32_t fourcc, char out[5])
{
    int n = 0;
    for (int i = 0; i < 4; i++) {
        unsigned char c = (unsigned char)(fourcc >> (8 * i));
        if (c == ' ' || c == '\0')
            break;
        out[n++] =
            (char)(c >= 'A' && c <= 'Z' ? c + ('a' - 'A') : (c >= 0x20 && c < 0x7f ? c : '?'));
    }
    out[n] = '\0';
}
