#define _GNU_SOURCE /* preadv/pwritev */
#include "internal/vt_float_file.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/uio.h>
#include <unistd.h>

#include "vt_checked.h"
#include "vt_error.h"

#define ROWS_PER_CALL 64 /* rows of one tile moved by one vectored call */

struct vt_float_file {
    int fd;
    uint32_t width, height, channels, tile;
    char dir[256]; /* for messages */
};

struct vt_float_file *vt_float_file_create(const char *dir, uint32_t width, uint32_t height,
                                           uint32_t channels, uint32_t tile_px,
                                           struct vts_error *err)
{
    char path[4096];
    int n = snprintf(path, sizeof path, "%s/.vt-pass-XXXXXX", dir ? dir : ".");
    if (n < 0 || (size_t)n >= sizeof path) {
        vt_error_set(err, VTS_ERR_ARG, "temporary directory path is too long");
        return NULL;
    }
    if (tile_px == 0) {
        vt_error_set(err, VTS_ERR_ARG, "temporary pass image with tiles of 0 texels");
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
    f->tile = tile_px;
    snprintf(f->dir, sizeof f->dir, "%s", dir ? dir : ".");
    return f;
}

/* The stored tile holding texel (x, y): its first byte and its width (edge tiles are narrower and
 * lower: the file holds width x height texels, no padding). */
static void tile_of(const struct vt_float_file *f, uint32_t x, uint32_t y, uint64_t *first,
                    uint32_t *tile_w)
{
    uint32_t t = f->tile, x0 = x / t * t, y0 = y / t * t;
    uint32_t th = f->height - y0 < t ? f->height - y0 : t;
    *tile_w = f->width - x0 < t ? f->width - x0 : t;
    *first = ((uint64_t)y0 * f->width + (uint64_t)x0 * th) * f->channels * sizeof(float);
}

/* Moves every byte of iov[0..count) from or to the file at off. Reads past the end of the file
 * (texels never written, which a complete pass never reads) give zeros. */
static int move_all(const struct vt_float_file *f, bool write, struct iovec *iov, int count,
                    uint64_t off, struct vts_error *err)
{
    while (count > 0) {
        if (iov->iov_len == 0) {
            iov++;
            count--;
            continue;
        }
        ssize_t n =
            write ? pwritev(f->fd, iov, count, (off_t)off) : preadv(f->fd, iov, count, (off_t)off);
        if (n < 0 && errno == EINTR)
            continue;
        if (n < 0 || (n == 0 && write))
            return vt_error_set(err, VTS_ERR_IO, "cannot %s a temporary pass image in '%s': %s",
                                write ? "write" : "read", f->dir,
                                n < 0 ? strerror(errno) : "disk full");
        if (n == 0) {
            for (int i = 0; i < count; i++)
                memset(iov[i].iov_base, 0, iov[i].iov_len);
            return 0;
        }
        off += (uint64_t)n;
        for (size_t done = (size_t)n; done > 0;) {
            size_t step = done < iov->iov_len ? done : iov->iov_len;
            iov->iov_base = (char *)iov->iov_base + step;
            iov->iov_len -= step;
            done -= step;
            if (iov->iov_len == 0) {
                iov++;
                count--;
            }
        }
    }
    return 0;
}

/* Moves the width x height texels at (x, y), rows `stride_bytes` apart in memory at mem, from or to
 * the file: tile by tile, the rows of a tile's full width in one vectored call per ROWS_PER_CALL
 * rows (they are contiguous in the file), other rows one call each. */
static int move_rect(const struct vt_float_file *f, bool write, uint32_t x, uint32_t y,
                     uint32_t width, uint32_t height, char *mem, size_t stride_bytes,
                     struct vts_error *err)
{
    size_t tb = (size_t)f->channels * sizeof(float);
    int rc = 0;
    for (uint32_t py = y; rc == 0 && py < y + height;) {
        uint32_t ty_end = (py / f->tile + 1) * f->tile;
        uint32_t ph = (ty_end < y + height ? ty_end : y + height) - py;
        for (uint32_t px = x; rc == 0 && px < x + width;) {
            uint32_t tx_end = (px / f->tile + 1) * f->tile;
            uint32_t pw = (tx_end < x + width ? tx_end : x + width) - px, tile_w;
            uint64_t first;
            tile_of(f, px, py, &first, &tile_w);
            bool whole_rows = pw == tile_w;
            uint32_t per_call = whole_rows ? ROWS_PER_CALL : 1;
            for (uint32_t r = 0; rc == 0 && r < ph; r += per_call) {
                struct iovec iov[ROWS_PER_CALL];
                uint32_t n = ph - r < per_call ? ph - r : per_call;
                for (uint32_t i = 0; i < n; i++)
                    iov[i] = (struct iovec){mem + (size_t)(py - y + r + i) * stride_bytes +
                                                (size_t)(px - x) * tb,
                                            (size_t)pw * tb};
                uint64_t off =
                    first + ((uint64_t)((py + r) % f->tile) * tile_w + px % f->tile) * tb;
                rc = move_all(f, write, iov, (int)n, off, err);
            }
            px += pw;
        }
        py += ph;
    }
    return rc;
}

int vt_float_file_write(struct vt_float_file *f, uint32_t x, uint32_t y, uint32_t width,
                        uint32_t height, const float *texels, size_t stride, struct vts_error *err)
{
    /* pwritev only reads the memory: the cast drops a const the iovec cannot carry */
    char *mem = (char *)(uintptr_t)texels;
    return move_rect(f, true, x, y, width, height, mem, stride * sizeof(float), err);
}

static int float_read_region(void *ctx, uint32_t x, uint32_t y, struct vt_image *dst,
                             struct vts_error *err)
{
    const struct vt_float_file *f = ctx;
    return move_rect(f, false, x, y, dst->width, dst->height, dst->pixels, dst->stride, err);
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
