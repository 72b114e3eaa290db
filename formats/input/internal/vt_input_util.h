/* Private to formats/input: checks and bookkeeping every reader does the same way. */
#ifndef VT_INPUT_UTIL_H
#define VT_INPUT_UTIL_H

#include <stddef.h>
#include <stdint.h>

#include <stdbool.h>

#include "vt_error.h"
#include "vt_image.h"
#include "vt_source.h"

/* Bytes above which a single decode buffer (a TIFF strip or tile, a de-interlaced PNG) is
 * refused: hostile headers can declare huge tiles. */
#define VT_INPUT_MAX_BUFFER_BYTES (1ull << 30)

/* Checks a header's size: 0 in either direction is VTS_ERR_BAD_INPUT, more than max_pixels texels
 * VTS_ERR_LIMIT ("'x.tif': 200000x200000 texels exceeds --max-pixels 17179869184"). */
int vt_input_check_size(const char *path, uint64_t width, uint64_t height, uint64_t max_pixels,
                        struct vts_error *err);

/* Copies path into a reader's name buffer (for messages), truncating if needed. */
void vt_input_copy_name(char *dst, size_t dst_size, const char *path);

/* Fills the parts of info every reader sets the same way (colour from the sample type, has_alpha
 * from the channel count, tiling, format name). */
void vt_input_set_info(struct vt_source_info *info, uint32_t width, uint32_t height,
                       uint32_t channels, uint32_t sample, bool sequential, uint32_t tile_w,
                       uint32_t tile_h, const char *format);

#endif
