/* Tool-side access to a Wang pack store (vt_wang_pack.h). */
#include "vt_wang_pack.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vt_png_file.h"
#include "vt_tile_reader.h"

bool vt_wang_pack_is(const struct vts_store *s)
{
    return vts_store_meta_find(s, VT_WANG_KEY_KIND) != NULL;
}

static const char *meta_of(void *user, const char *key)
{
    return vts_store_meta_find(user, key);
}

int vt_wang_pack_open(const struct vts_store *s, struct vt_wang_info *info, struct vts_error *err)
{
    const char *name = vts_store_name(s);
    int rc = vt_wang_info_parse(meta_of, (void *)(uintptr_t)s, info, err);
    if (rc) {
        char m[sizeof err->message];
        snprintf(m, sizeof m, "%s", err->message);
        return vt_error_set(err, rc, "'%s': %s", name, m);
    }
    const struct vts_geometry *g = vts_store_geometry(s);
    const struct vts_layer *L = vts_store_layer(s, 0);
    if (!L || L->sample != VTS_SAMPLE_U8 || (uint64_t)info->cols * info->tile_px != g->width ||
        (uint64_t)info->rows * info->tile_px != g->height)
        return vt_error_set(err, VTS_ERR_CORRUPT,
                            "'%s': the Wang pack metadata (%ux%u tiles of %u) does not match the "
                            "store (%ux%u texels, layer 0 of 8-bit samples)",
                            name, info->cols, info->rows, info->tile_px, g->width, g->height);
    return 0;
}

int vt_wang_pack_read_level(const struct vts_store *s, uint32_t level, struct vt_image *out,
                            struct vts_error *err)
{
    const struct vts_geometry *g = vts_store_geometry(s);
    struct vts_level L;
    struct vt_tile_reader r;
    memset(out, 0, sizeof *out);
    if (level >= g->level_count || vts_store_level(s, level, &L) != 0)
        return vt_error_set(err, VTS_ERR_RANGE, "'%s': no level %u", vts_store_name(s), level);
    int rc = vt_tile_reader_init(&r, s, 0, err);
    if (rc == 0)
        rc = vt_image_alloc(out, L.width, L.height, r.img.channels, VTS_SAMPLE_U8, err);
    uint32_t c = g->tile_content_px, b = g->border_px;
    size_t texel = r.img.channels;
    for (uint32_t ty = 0; rc == 0 && ty < L.tiles_y; ty++)
        for (uint32_t tx = 0; rc == 0 && tx < L.tiles_x; tx++) {
            bool stored;
            if ((rc = vt_tile_reader_read(&r, level, tx, ty, &stored, err)) != 0)
                break;
            uint32_t w = L.width - tx * c < c ? L.width - tx * c : c;
            uint32_t h = L.height - ty * c < c ? L.height - ty * c : c;
            for (uint32_t y = 0; y < h; y++)
                memcpy(vt_image_at(out, tx * c, ty * c + y), vt_image_at(&r.img, b, b + y),
                       w * texel);
        }
    vt_tile_reader_release(&r);
    if (rc)
        vt_image_release(out);
    return rc;
}

void vt_wang_pack_print(const struct vt_wang_info *info)
{
    uint64_t extent = (uint64_t)info->hash_n * info->tile_px;
    printf("wang pack:         %s tiles, %ux%u colours, %u tiles of %u texels in %ux%u%s\n",
           info->corners ? "corner" : "edge", info->kh, info->kv, info->cols * info->rows,
           info->tile_px, info->cols, info->rows, info->order ? " (shuffled order)" : "");
    printf("wang output:       hash of %u entries: repeats every %ux%u tiles (%llux%llu texels)\n",
           info->hash_n, info->hash_n, info->hash_n, (unsigned long long)extent,
           (unsigned long long)extent);
}

int vt_wang_pack_write_region(const struct vts_store *s, const struct vt_wang_info *info,
                              uint32_t level, uint64_t x, uint64_t y, uint32_t w, uint32_t h,
                              const char *path, struct vts_error *err)
{
    struct vt_image pack, region = {0};
    int rc = vt_wang_pack_read_level(s, level, &pack, err);
    if (rc)
        return rc;
    if ((info->tile_px >> level) == 0 || pack.width != info->cols * (info->tile_px >> level)) {
        vt_image_release(&pack);
        return vt_error_set(err, VTS_ERR_RANGE,
                            "'%s': level %u is coarser than one texel per Wang tile",
                            vts_store_name(s), level);
    }
    rc = vt_image_alloc(&region, w, h, pack.channels, VTS_SAMPLE_U8, err);
    struct vt_png_file_writer *pw = NULL;
    if (rc == 0) {
        vt_wang_assemble(info, &pack, level, x, y, &region);
        pw = vt_png_file_writer_create(path, w, h, pack.channels, 8, err);
        rc = pw ? vt_png_file_writer_rows(pw, region.pixels, h, region.stride, err) : err->status;
    }
    if (rc == 0)
        rc = vt_png_file_writer_finish(pw, err);
    vt_png_file_writer_destroy(pw);
    vt_image_release(&region);
    vt_image_release(&pack);
    return rc;
}
