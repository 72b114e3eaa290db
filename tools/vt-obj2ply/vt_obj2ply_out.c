/* vt-obj2ply's buffered output (see vt_obj2ply_out.h). */
#include "vt_obj2ply_out.h"

#include <string.h>

int vt_obj2ply_out_flush(struct vt_obj2ply_out *o, struct vts_error *err)
{
    int rc = vt_atomic_file_pwrite(&o->file, o->data, o->used, o->offset, err);
    o->offset += o->used;
    o->used = 0;
    return rc;
}

int vt_obj2ply_out_write(struct vt_obj2ply_out *o, const void *p, size_t n, struct vts_error *err)
{
    const unsigned char *b = p;
    while (n) {
        if (o->used == sizeof(o->data)) {
            int rc = vt_obj2ply_out_flush(o, err);
            if (rc)
                return rc;
        }
        size_t k = sizeof(o->data) - o->used;
        if (k > n)
            k = n;
        memcpy(o->data + o->used, b, k);
        o->used += k;
        b += k;
        n -= k;
    }
    return 0;
}

int vt_obj2ply_out_str(struct vt_obj2ply_out *o, const char *s, struct vts_error *err)
{
    return vt_obj2ply_out_write(o, s, strlen(s), err);
}
