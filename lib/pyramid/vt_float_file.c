#include "internal/vt_float_file.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "vt_checked.h"
#include "vt_error.h"

struct vt_float_file {
    int fd;
    uint32_t width, height, channels;
};

struct vt_float_file *vt_float_file_create(const char *dir, uint32_t width, uint32_t height,
                                           uint32_t channels, struct vts_error *err)
{
    char path[4096];
    int n = snprintf(path, sizeof path, "%s/.vt-pass-XXXXXX", dir ? dir : ".");
    if (n < 0 || (size_t)n >= sizeof path) {
        vt_error_set(err, VTS_ERR_ARG, "temporary directory path is too long");
        return NULL;
    }
    struct vt_float_file *f = calloc(1, sizeof *f);
    if (!f) {
        vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
        return NULL;
    }
    f->fd = mkstemp(path);
    if (f->fd < 0) {
        vt_error_set(err, VTS_ERR_IO, "cannot create a temporary file in '%s': %s", dir ? dir : ".",
                     strerror(errno));
        free(f);
        return NULL;
    }
    unlink(path); /* the data lives until the descriptor closes, even if the process is killed */
    f->width = width;
    f->height = height;
    f->channels = channels;
    return f;
}

static uint64_t texel_offset(const struct vt_float_file *f, uint32_t x, uint32_t y)
{
    return ((uint64_t)y * f->width + x) * f->channels * sizeof(float);
}

int vt_float_file_write(struct vt_float_file *f, uint32_t x, uint32_t y, const float *texels,
                        uint32_t count, struct vts_error *err)
{
    const char *p = (const char *)texels;
    size_t left = (size_t)count * f->channels * sizeof(float);
    uint64_t off = texel_offset(f, x, y);
    while (left > 0) {
        ssize_t n = pwrite(f->fd, p, left, (off_t)off);
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0)
            return vt_error_set(err, VTS_ERR_IO, "cannot write a temporary pass image: %s",
                                n < 0 ? strerror(errno) : "disk full");
        p += n;
        left -= (size_t)n;
        off += (uint64_t)n;
    }
    return 0;
}

static int float_read_region(void *ctx, uint32_t x, uint32_t y, struct vt_image *dst,
                             struct vts_error *err)
{
    const struct vt_float_file *f = ctx;
    size_t row_bytes = (size_t)dst->width * f->channels * sizeof(float);
    for (uint32_t r = 0; r < dst->height; r++) {
        char *p = (char *)dst->pixels + (size_t)r * dst->stride;
        size_t left = row_bytes;
        uint64_t off = texel_offset(f, x, y + r);
        while (left > 0) {
            ssize_t n = pread(f->fd, p, left, (off_t)off);
            if (n < 0 && errno == EINTR)
                continue;
            if (n < 0)
                return vt_error_set(err, VTS_ERR_IO, "cannot read a temporary pass image: %s",
                                    strerror(errno));
            if (n == 0) { /* never written (cannot happen for a complete pass): zeros */
                memset(p, 0, left);
                break;
            }
            p += n;
            left -= (size_t)n;
            off += (uint64_t)n;
        }
    }
    return 0;
}

static void float_close(void *ctx)
{
    (void)ctx; /* the file belongs to the vt_float_file */
}

static const struct vt_source_ops float_ops = {float_read_region, float_close};

int vt_float_file_source(struct vt_float_file *f, uint32_t colour, bool has_alpha,
                         struct vt_source *out, struct vts_error *err)
{
    (void)err;
    memset(out, 0, sizeof *out);
    out->info = (struct vt_source_info){.width = f->width,
                                        .height = f->height,
                                        .channels = f->channels,
                                        .sample = VTS_SAMPLE_F32,
                                        .colour = colour,
                                        .has_alpha = has_alpha};
    snprintf(out->info.format, sizeof out->info.format, "float-temp");
    snprintf(out->name, sizeof out->name, "(pass image)");
    out->ops = &float_ops;
    out->ctx = f;
    return 0;
}

void vt_float_file_destroy(struct vt_float_file *f)
{
    if (!f)
        return;
    close(f->fd);
    free(f);
}
