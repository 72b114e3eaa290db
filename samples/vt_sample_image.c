/* Pixel buffers of the sample scene generator (see vt_sample_image.h). */
#include "vt_sample_image.h"

#include <stdlib.h>
#include <string.h>

#include "vt_png_file.h"

int vt_sample_image_alloc(struct vt_sample_image *im, uint32_t w, uint32_t h, uint32_t ch)
{
    im->w = w;
    im->h = h;
    im->ch = ch;
    im->px = calloc((size_t)w * h, ch); /* sizes are ours (at most 2000x1000x4) */
    return im->px ? 0 : -1;
}

uint8_t *vt_sample_image_at(struct vt_sample_image *im, uint32_t x, uint32_t y)
{
    return im->px + ((size_t)y * im->w + x) * im->ch;
}

void vt_sample_image_set(struct vt_sample_image *im, int64_t x, int64_t y, const uint8_t *value)
{
    if (x < 0 || y < 0 || x >= im->w || y >= im->h)
        return;
    memcpy(vt_sample_image_at(im, (uint32_t)x, (uint32_t)y), value, im->ch);
}

void vt_sample_image_fill_rect(struct vt_sample_image *im, int64_t x0, int64_t y0, int64_t w,
                               int64_t h, const uint8_t *value)
{
    for (int64_t y = y0; y < y0 + h; y++)
        for (int64_t x = x0; x < x0 + w; x++)
            vt_sample_image_set(im, x, y, value);
}

int vt_sample_image_write_png(const char *path, struct vt_sample_image *im, struct vts_error *err)
{
    struct vt_png_file_writer *w = vt_png_file_writer_create(path, im->w, im->h, im->ch, 8, err);
    if (!w)
        return err->status;
    int rc = vt_png_file_writer_rows(w, im->px, im->h, (size_t)im->w * im->ch, err);
    if (rc == 0)
        rc = vt_png_file_writer_finish(w, err);
    vt_png_file_writer_destroy(w);
    return rc;
}
