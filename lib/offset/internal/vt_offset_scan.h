/* Pass 1 of vt-offset (internal to lib/vt_offset*.c): counts v and vn, parses every vt and face,
 * checks each index, the material of each face with texture coordinates (it must be in the layout)
 * and that each coordinate lies in the UV range its material covers, and records for every vt the
 * materials of the faces that use it. */
#ifndef VT_OFFSET_SCAN_H
#define VT_OFFSET_SCAN_H

#include <stddef.h>

#include "vt_error.h"
#include "vt_offset_run.h"

/* Scans one raw logical line (r->src.line is its number). Returns 0 or a negative status. */
int vt_offset_scan_line(struct vt_offset_run *r, const unsigned char *line, size_t n,
                        struct vts_error *err);

/* After pass 1: gives each vt its output index (r->new_index). */
int vt_offset_scan_number_outputs(struct vt_offset_run *r, struct vts_error *err);

#endif
