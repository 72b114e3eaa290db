/* TIFF files on disk: a streaming writer of images too big to hold in memory (vt-tiles
 * --export-atlas, vt-info --extract), 8-bit, 16-bit or 32-bit float samples, written through a
 * temporary file and renamed when complete. Uses libtiff; its messages are caught into the writer's
 * error and never printed. */
#ifndef VT_TIFF_FILE_H
#define VT_TIFF_FILE_H

#include <stddef.h>
#include <stdint.h>

#include "vt_error.h"

/* Rows per strip; every strip is deflate-compressed (COMPRESSION_ADOBE_DEFLATE). */
#define VT_TIFF_FILE_ROWS_PER_STRIP 64u

struct vt_tiff_file_writer;

/* Starts a width x height TIFF at path with channels 1..4 of 8 bits (grey, grey + alpha, RGB,
 * RGBA; alpha as unassociated extra sample), contiguous, one strip per
 * VT_TIFF_FILE_ROWS_PER_STRIP rows; BigTIFF when width * height * channels exceeds 2^31 bytes.
 * Rows go to a hidden temporary file next to path; nothing appears under path before
 * vt_tiff_file_writer_finish() succeeds. Returns NULL and fills err on failure (VTS_ERR_ARG,
 * VTS_ERR_IO naming the path, VTS_ERR_NOMEM). Free with vt_tiff_file_writer_destroy(). Not
 * thread-safe: one thread at a time per writer. */
struct vt_tiff_file_writer *vt_tiff_file_writer_create(const char *path, uint32_t width,
                                                       uint32_t height, uint32_t channels,
                                                       struct vts_error *err);

/* Appends row_count rows, top to bottom; row i starts at (const char *)rows + i * stride and holds
 * width * channels samples, interleaved. Returns 0, VTS_ERR_ARG (more rows than the height) or
 * VTS_ERR_IO ("cannot write 'x.tif': <libtiff's reason>"). After VTS_ERR_IO the writer is
 * stopped: every later call fails and only destroy is left. */
int vt_tiff_file_writer_rows(struct vt_tiff_file_writer *w, const void *rows, uint32_t row_count,
                             size_t stride, struct vts_error *err);

/* Ends the TIFF (directory written, file closed), flushes it to disk and renames it over path
 * (vt_atomic_file_commit). Every row must have been given (VTS_ERR_ARG otherwise). Returns 0 or a
 * negative status; on failure nothing is left under path (a previous file there is intact). Call
 * at most once; destroy the writer either way. */
int vt_tiff_file_writer_finish(struct vt_tiff_file_writer *w, struct vts_error *err);

/* Frees the writer; without a successful finish, removes the temporary file so that no file
 * appears under path. Accepts NULL. */
void vt_tiff_file_writer_destroy(struct vt_tiff_file_writer *w);

/* As vt_tiff_file_writer_create(), with samples of type sample: VTS_SAMPLE_U8, VTS_SAMPLE_U16
 * (16-bit unsigned) or VTS_SAMPLE_F32 (32-bit IEEE float, SAMPLEFORMAT_IEEEFP); rows hold them in
 * the host's byte order. Other sample types: NULL with VTS_ERR_ARG. */
struct vt_tiff_file_writer *vt_tiff_file_writer_create_sample(const char *path, uint32_t width,
                                                              uint32_t height, uint32_t channels,
                                                              uint32_t sample,
                                                              struct vts_error *err);

#endif
