/* Checks and bookkeeping shared by the readers (internal/vt_input_util.h). */
#include "internal/vt_input_util.h"

#include <stdio.h>
#include <string.h>

#include "vt_checked.h"

int vt_input_check_size(const char *path, uint64_t width, uint64_t height, uint64_t max_pixels,
                        struct vts_error *err)
{
    if (width == 0 || height == 0)
        return vt_error_set(err, VTS_ERR_BAD_INPUT, "cannot read '%s': image size %llux%llu", path,
                            (unsigned long long)width, (unsigned long long)height);
    uint64_t pixels;
    if (width > UINT32_MAX || height > UINT32_MAX || !vt_u64_mul(width, height, &pixels) ||
        pixels > max_pixels)
        return vt_error_set(err, VTS_ERR_LIMIT, "'%s': %llux%llu texels exceeds --max-pixels %llu",
                            path, (unsigned long long)width, (unsigned long long)height,
                            (unsigned long long)max_pixels);
    return 0;
}

void vt_input_copy_name(char *dst, size_t dst_size, const char *path)
{
    snprintf(dst, dst_size, "%s", path);
}

void vt_input_set_info(struct vt_source_info *info, uint32_t width, uint32_t height,
                       uint32_t channels, uint32_t sample, bool sequential, uint32_t tile_w,
                       uint32_t tile_h, const char *format)
{
    memset(info, 0, sizeof *info);
    info->width = width;
    info->height = height;
    info->channels = channels;
    info->sample = sample;
    info->colour = (sample == VTS_SAMPLE_F16 || sample == VTS_SAMPLE_F32) ? VTS_COLOUR_LINEAR
                                                                          : VTS_COLOUR_SRGB;
    info->has_alpha = channels == 2 || channels == 4;
    info->sequential = sequential;
    info->tile_w = tile_w;
    info->tile_h = tile_h;
    snprintf(info->format, sizeof info->format, "%s", format);
}
