/* libFuzzer target for the OBJ/MTL reader (lib/obj/vt_obj.c): parses the input from memory as an
 * OBJ and as an MTL file. Invariants are checked, not only crashes: every face corner must index
 * the arrays read so far, every failure must give a reader status with a message naming the input,
 * and every map of a material read must have both a file and a resolved path or neither. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "vt_obj.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#define NAME "dir/fuzz.obj"

static int check_face(void *user, const struct vt_obj *obj, const struct vt_obj_face *f,
                      struct vts_error *err)
{
    (void)user, (void)err;
    if (f->corner_count < 3 || !f->material || !f->group || !f->object)
        abort();
    for (uint32_t i = 0; i < f->corner_count; i++) {
        const struct vt_obj_corner *c = &f->corners[i];
        if (c->v >= vt_obj_position_count(obj) ||
            (c->vt != VT_OBJ_NONE && c->vt >= vt_obj_texcoord_count(obj)) ||
            (c->vn != VT_OBJ_NONE && c->vn >= vt_obj_normal_count(obj)))
            abort();
        if (c->vt != VT_OBJ_NONE) {
            unsigned n = vt_obj_texcoord_components(obj, c->vt);
            if (n < 1 || n > 3)
                abort();
        }
    }
    return 0;
}

static int check_mtllib(void *user, const struct vt_obj *obj, const char *path, uint64_t line,
                        struct vts_error *err)
{
    (void)user, (void)obj, (void)err;
    if (!path[0] || strchr(path, '\\') || line == 0)
        abort();
    return 0;
}

static void check_failure(int rc, const struct vts_error *err)
{
    if (rc != VTS_ERR_BAD_INPUT && rc != VTS_ERR_LIMIT && rc != VTS_ERR_NOMEM)
        abort();
    if (err->status != rc || !strstr(err->message, "fuzz.obj"))
        abort();
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    struct vt_obj_limits limits;
    vt_obj_limits_default(&limits);
    limits.max_line_bytes = 4096; /* small limits keep the fuzzer fast and reach the limit paths */
    limits.max_vertices = 1 << 12;
    limits.max_materials = 64;

    struct vts_error err = {0};
    struct vt_obj *obj = vt_obj_create(&limits, &err);
    if (!obj)
        abort();
    struct vt_obj_callbacks cb = {check_mtllib, NULL, check_face, NULL};
    int rc = vt_obj_parse_memory(obj, data, size, NAME, &cb, &err);
    if (rc != 0)
        check_failure(rc, &err);
    vt_obj_destroy(obj);

    struct vt_mtl mtl;
    rc = vt_mtl_parse_memory(data, size, NAME, &limits, &mtl, &err);
    if (rc != 0)
        check_failure(rc, &err);
    for (size_t i = 0; i < mtl.material_count; i++) {
        const struct vt_mtl_material *m = &mtl.materials[i];
        if (!m->name || vt_mtl_find(&mtl, m->name) == NULL)
            abort();
        for (int k = 0; k < VT_MTL_MAP_COUNT; k++)
            if (!m->maps[k].file != !m->maps[k].path ||
                (m->maps[k].path && strchr(m->maps[k].path, '\\')))
                abort();
    }
    vt_mtl_release(&mtl);
    return 0;
}
