/* vt-obj2ply --restore (see vt_obj2ply_restore.h). */
#define _XOPEN_SOURCE 700 /* getline, ssize_t */
#include "vt_obj2ply_restore.h"

#include <errno.h>
#include <inttypes.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>

#include "tool_common.h"
#include "vt_error.h"
#include "vt_obj2ply_out.h"
#include "vt_obj2ply_path.h"

int vt_obj2ply_restore_write(const struct vt_obj2ply_mesh *orig, const char *meshlab_path,
                             const char *out_path, struct vts_error *err)
{
    struct vt_obj2ply_mesh ml;
    int rc = vt_obj2ply_mesh_read(&ml, meshlab_path, err);
    if (!rc)
        rc = vt_obj2ply_mesh_read_mtls(&ml, err);
    FILE *in = NULL;
    char *buf = NULL, *mtllib_line = NULL, *out_dir = NULL;
    size_t cap = 0;
    struct vt_obj2ply_out *o = NULL;
    bool created = false;
    if (rc)
        goto cleanup;
    /* the mtllib line: IN.obj's MTL files relative to OUT.obj's directory */
    out_dir = vt_obj2ply_path_absolute(out_path);
    if (!out_dir) {
        rc = vt_error_set(err, VTS_ERR_IO, "'%s': cannot resolve the directory: %s", out_path,
                          strerror(errno));
        goto cleanup;
    }
    char *last = strrchr(out_dir, '/');
    if (last)
        last[last == out_dir ? 1 : 0] = '\0';
    size_t len = strlen("mtllib") + 2;
    mtllib_line = malloc(len);
    if (!mtllib_line) {
        rc = vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
        goto cleanup;
    }
    strcpy(mtllib_line, "mtllib");
    for (size_t i = 0; i < orig->mtllib_count; i++) {
        char *abs = vt_obj2ply_path_absolute(orig->mtllibs[i]);
        char *rel = abs ? vt_obj2ply_path_relative(out_dir, abs) : NULL;
        free(abs);
        if (!rel) {
            rc = vt_error_set(err, VTS_ERR_IO, "'%s': cannot resolve the path", orig->mtllibs[i]);
            goto cleanup;
        }
        len += strlen(rel) + 1;
        char *n = realloc(mtllib_line, len);
        if (!n) {
            free(rel);
            rc = vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
            goto cleanup;
        }
        mtllib_line = n;
        strcat(mtllib_line, " ");
        strcat(mtllib_line, rel);
        free(rel);
    }
    strcat(mtllib_line, "\n");

    in = fopen(meshlab_path, "r");
    if (!in) {
        rc = vt_error_set(err, VTS_ERR_IO, "'%s': %s", meshlab_path, strerror(errno));
        goto cleanup;
    }
    o = malloc(sizeof(*o));
    if (!o) {
        rc = vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
        goto cleanup;
    }
    o->offset = 0;
    o->used = 0;
    rc = vt_atomic_file_create(&o->file, out_path, "tmp", VT_ATOMIC_FILE_SEQUENTIAL, err);
    if (rc)
        goto cleanup;
    created = true;
    rc = vt_obj2ply_out_str(
        o, "# vt-obj2ply --restore: MeshLab output with the original materials\n", err);
    bool mtllib_done = false, material_seen = false;
    uint64_t lineno = 0;
    ssize_t n;
    while (!rc && (n = getline(&buf, &cap, in)) >= 0) {
        lineno++;
        const char *p = buf;
        while (*p == ' ' || *p == '\t')
            p++;
        if (!strncmp(p, "mtllib", 6) && (p[6] == ' ' || p[6] == '\t')) {
            if (!mtllib_done && orig->mtllib_count)
                rc = vt_obj2ply_out_str(o, mtllib_line, err);
            mtllib_done = true;
            continue;
        }
        if (!strncmp(p, "usemtl", 6) && (p[6] == ' ' || p[6] == '\t')) {
            char name[256];
            if (sscanf(p + 6, " %255s", name) != 1) {
                rc = vt_error_set(err, VTS_ERR_BAD_INPUT, "'%s':%" PRIu64 ": bad usemtl",
                                  meshlab_path, lineno);
                break;
            }
            const struct vt_mtl_material *mat = vt_obj2ply_mesh_find_material(&ml, name);
            const char *file = mat ? mat->maps[VT_MTL_MAP_KD].file : NULL;
            uint32_t index;
            if (!file ||
                strncmp(file, VT_OBJ2PLY_MESH_TOKEN_PREFIX, strlen(VT_OBJ2PLY_MESH_TOKEN_PREFIX)) ||
                vt_parse_u32(file + strlen(VT_OBJ2PLY_MESH_TOKEN_PREFIX), 0, UINT32_MAX, &index) ||
                index >= orig->material_count) {
                rc = vt_error_set(err, VTS_ERR_BAD_INPUT,
                                  "'%s':%" PRIu64
                                  ": material '%s' does not name one of '%s' (map_Kd '%s')",
                                  meshlab_path, lineno, name, orig->path, file ? file : "");
                break;
            }
            const char *orig_name = orig->materials[index];
            if (!orig_name[0]) {
                /* faces before any usemtl: expressible only before the first material */
                if (material_seen) {
                    rc = vt_error_set(
                        err, VTS_ERR_BAD_INPUT,
                        "'%s':%" PRIu64
                        ": faces without a material come after faces with one; OBJ cannot say that",
                        meshlab_path, lineno);
                    break;
                }
                continue;
            }
            material_seen = true;
            rc = vt_obj2ply_out_str(o, "usemtl ", err);
            if (!rc)
                rc = vt_obj2ply_out_str(o, orig_name, err);
            if (!rc)
                rc = vt_obj2ply_out_str(o, "\n", err);
            continue;
        }
        rc = vt_obj2ply_out_write(o, buf, (size_t)n, err);
    }
    if (!rc && ferror(in))
        rc = vt_error_set(err, VTS_ERR_IO, "'%s': read error", meshlab_path);
    if (!rc)
        rc = vt_obj2ply_out_flush(o, err);
    if (!rc) {
        rc = vt_atomic_file_commit(&o->file, err);
        created = false;
    }
cleanup:
    if (created)
        vt_atomic_file_abort(&o->file);
    free(o);
    if (in)
        fclose(in);
    free(buf);
    free(mtllib_line);
    free(out_dir);
    vt_obj2ply_mesh_release(&ml);
    return rc;
}
