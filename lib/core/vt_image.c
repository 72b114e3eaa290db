#include "vt_image.h"

#include <stdlib.h>
#include <string.h>

#include "vt_checked.h"
#include "vt_error.h"

size_t vt_image_texel_bytes(const struct vt_image *img)
{
    return (size_t)img->channels * vt_sample_bytes(img->sample);
}

int vt_image_alloc(struct vt_image *img, uint32_t width, uint32_t height, uint32_t channels,
                   uint32_t sample, struct vts_error *err)
{
    memset(img, 0, sizeof *img);
    unsigned sb = vt_sample_bytes(sample);
    if (width == 0 || height == 0 || channels < 1 || channels > 4 || sb == 0)
        return vt_error_set(err, VTS_ERR_ARG, "invalid image shape %ux%u, %u channels, sample %u",
                            width, height, channels, sample);
    size_t stride, bytes;
    if (!vt_size_mul3(width, channels, sb, &stride) || !vt_size_mul(stride, height, &bytes))
        return vt_error_set(err, VTS_ERR_LIMIT, "image of %ux%u texels is too large", width,
                            height);
    void *p = calloc(1, bytes);
    if (!p)
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory for a %ux%u image", width, height);
    *img = (struct vt_image){width, height, channels, sample, stride, p};
    return 0;
}

void vt_image_release(struct vt_image *img)
{
    if (img) {
        free(img->pixels);
        memset(img, 0, sizeof *img);
    }
}
