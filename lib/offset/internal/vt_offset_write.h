/* Pass 2 of vt-offset (internal to lib/vt_offset*.c): copies the OBJ text line by line to the
 * output, replacing used vt by their atlas coordinates (one more vt line per extra material),
 * renumbering the texture indices of f and l lines and renaming usemtl and mtllib (see
 * vt_offset.h). */
#ifndef VT_OFFSET_WRITE_H
#define VT_OFFSET_WRITE_H

#include <stddef.h>

#include "vt_error.h"
#include "vt_offset_run.h"

/* Writes the rewrite of one raw logical line. Returns 0 or a negative status. */
int vt_offset_write_line(struct vt_offset_run *r, const unsigned char *line, size_t n,
                         struct vts_error *err);

#endif
