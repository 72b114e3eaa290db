/* PNG files on disk: a streaming writer for outputs too big to hold in memory (written through a
 * temporary file and renamed when complete), and a reader that loads a whole PNG of any colour type
 * into a vt_image. Both use libpng; its setjmp/longjmp never leaves vt_png_file.c. */
#ifndef VT_PNG_FILE_H
#define VT_PNG_FILE_H

#include <stddef.h>
#include <stdint.h>

#include "vt_error.h"
#include "vt_image.h"

/* vt_png_file_read() refuses images with more texels than this (VTS_ERR_LIMIT). */
#define VT_PNG_FILE_MAX_PIXELS (1ull << 30)

/* zlib level of the writer, with the SUB filter on every row: speed over size (on a 256x256 RGBA8
 * test image, level 6 with adaptive filters was ~7x slower for a file ~15% smaller). */
#define VT_PNG_FILE_LEVEL 1

struct vt_png_file_writer;

/* Starts a width x height PNG at path with channels 1..4 (gray, gray+alpha, RGB, RGBA) and
 * bit_depth 8 or 16. Rows go to a hidden temporary file next to path; nothing appears under path
 * before vt_png_file_writer_finish() succeeds. Returns NULL and fills err on failure (VTS_ERR_ARG,
 * VTS_ERR_IO naming the path, VTS_ERR_NOMEM). Free with vt_png_file_writer_destroy(). Not
 * thread-safe: one thread at a time per writer. */
struct vt_png_file_writer *vt_png_file_writer_create(const char *path, uint32_t width,
                                                     uint32_t height, uint32_t channels,
                                                     uint32_t bit_depth, struct vts_error *err);

/* Appends row_count rows, top to bottom; row i starts at (const char *)rows + i * stride and holds
 * width * channels samples, interleaved, 16-bit ones in host order. stride >= the row size unless
 * row_count <= 1. Returns 0, VTS_ERR_ARG (more rows than the height, short stride), VTS_ERR_IO
 * (with the path; ENOSPC included) or VTS_ERR_NOMEM. After an error other than VTS_ERR_ARG the
 * writer is stopped: every later call fails and only destroy is left. */
int vt_png_file_writer_rows(struct vt_png_file_writer *w, const void *rows, uint32_t row_count,
                            size_t stride, struct vts_error *err);

/* Ends the PNG, flushes it to disk and renames it over path (vt_atomic_file_commit). Every row must
 * have been given (VTS_ERR_ARG otherwise). Returns 0 or a negative status; on failure nothing is
 * left under path (a previous file there is intact). Call at most once; destroy the writer either
 * way. */
int vt_png_file_writer_finish(struct vt_png_file_writer *w, struct vts_error *err);

/* Frees the writer; without a successful finish, removes the temporary file so that no file
 * appears under path. Accepts NULL. */
void vt_png_file_writer_destroy(struct vt_png_file_writer *w);

/* Reads the whole PNG at path into *out, freshly allocated (free with vt_image_release()); any
 * colour type and bit depth, expanded: palette -> RGB or RGBA, gray below 8 bits -> 8 bits,
 * a tRNS chunk -> an alpha channel. 8-bit images give VTS_SAMPLE_U8, 16-bit ones VTS_SAMPLE_U16
 * in host order; interlaced images are de-interlaced. Returns 0, or VTS_ERR_IO, VTS_ERR_BAD_INPUT
 * ("cannot read 'x.png': not a PNG file", truncated or corrupt data), VTS_ERR_LIMIT (more than
 * VT_PNG_FILE_MAX_PIXELS texels) or VTS_ERR_NOMEM, with a message naming path; *out is then zeroed.
 * Thread-safe. */
int vt_png_file_read(const char *path, struct vt_image *out, struct vts_error *err);

#endif
