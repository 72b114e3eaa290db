/* vt-obj2ply's buffered output into an atomic file (tools/vt-obj2ply/vt-obj2ply.c). */
#ifndef VT_OBJ2PLY_OUT_H
#define VT_OBJ2PLY_OUT_H

#include <stddef.h>

#include "vt_atomic_file.h"
#include "vt_error.h"

struct vt_obj2ply_out {
    struct vt_atomic_file file;
    unsigned long long offset;
    size_t used;
    unsigned char data[1 << 16];
};

/* Writes the buffered bytes at the file's current offset. Returns 0 or a negative status. */
int vt_obj2ply_out_flush(struct vt_obj2ply_out *o, struct vts_error *err);

/* Appends n bytes (flushing when the buffer fills). Returns 0 or a negative status. */
int vt_obj2ply_out_write(struct vt_obj2ply_out *o, const void *p, size_t n, struct vts_error *err);

/* Appends a string. Returns 0 or a negative status. */
int vt_obj2ply_out_str(struct vt_obj2ply_out *o, const char *s, struct vts_error *err);

#endif
