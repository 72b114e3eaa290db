/* Face corners of an OBJ for the end-to-end atlas tests (vt_test_corners.h). */
#include "vt_test_corners.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vt_error.h"
#include "vt_obj.h"

struct reader {
    struct vt_test_corners *c;
    const char *const *names;
    int name_count;
};

static int on_face(void *user, const struct vt_obj *obj, const struct vt_obj_face *f,
                   struct vts_error *err)
{
    struct reader *r = user;
    struct vt_test_corners *c = r->c;
    int m = -1;
    for (int k = 0; k < r->name_count; k++)
        if (strcmp(f->material, r->names[k]) == 0)
            m = k;
    for (uint32_t k = 0; k < f->corner_count; k++) {
        if (c->count == c->cap) {
            uint32_t cap = c->cap ? c->cap * 2 : 256;
            int *material = realloc(c->material, cap * sizeof *material);
            if (material)
                c->material = material;
            double *uv = realloc(c->uv, cap * 2 * sizeof *uv);
            if (uv)
                c->uv = uv;
            if (!material || !uv)
                return vt_error_set(err, VTS_ERR_NOMEM, "out of memory for face corners");
            c->cap = cap;
        }
        const double *vt = f->corners[k].vt == VT_OBJ_NONE
                               ? NULL
                               : vt_obj_texcoords(obj) + 3 * (size_t)f->corners[k].vt;
        c->material[c->count] = m;
        c->uv[2 * c->count] = vt ? vt[0] : 0;
        c->uv[2 * c->count + 1] = vt ? vt[1] : 0;
        c->count++;
    }
    return 0;
}

int vt_test_corners_read(const char *file, const char *const *names, int name_count,
                         struct vt_test_corners *c, struct vts_error *err)
{
    memset(c, 0, sizeof *c);
    struct vt_obj *obj = vt_obj_create(NULL, err);
    if (!obj)
        return err ? err->status : VTS_ERR_NOMEM;
    struct reader r = {c, names, name_count};
    struct vt_obj_callbacks cb = {.face = on_face, .user = &r};
    int rc = vt_obj_read(obj, file, &cb, err);
    vt_obj_destroy(obj);
    return rc;
}

void vt_test_corners_release(struct vt_test_corners *c)
{
    free(c->material);
    free(c->uv);
    memset(c, 0, sizeof *c);
}

int vt_test_run(const char *cmd)
{
    fprintf(stderr, "+ %s\n", cmd);
    return system(cmd);
}
