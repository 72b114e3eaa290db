/* vt-obj2ply: the OBJ side of the optional MeshLab stage (scripts/mesh-clean, docs/mesh-clean.md).
 *
 *   vt-obj2ply IN.obj -o OUT.ply
 *       Writes IN.obj as a binary PLY that meshlabserver 2020.09 reads (it aborts on every OBJ):
 *       float x y z per vertex; per face (polygons fanned into triangles) the vertex indices, the
 *       six wedge texture coordinates and a texnumber. Each material used becomes one
 *       "comment TextureFile vt-material-N" line (N in order of first use), so that the material
 *       MeshLab writes for a face names the original material, whatever its textures are.
 *   vt-obj2ply --restore IN.obj MESHLAB.obj -o OUT.obj
 *       Rewrites the OBJ that meshlabserver wrote from that PLY: every "usemtl material_K" gets the
 *       original material name back (looked up through MeshLab's MTL: map_Kd vt-material-N), and
 *       mtllib names IN.obj's own MTL files (relative to OUT.obj), so materials keep their colours,
 *       options and every map, not MeshLab's copies (Kd 1 1 1, Tr 1).
 *   vt-obj2ply --check IN.obj OUT.obj [--same-faces] [--tolerance T]
 *       Compares: every face of OUT.obj has a material whose map_Kd is the same file as in IN.obj
 *       (resolved paths); with --same-faces, face I of OUT.obj has the material of triangle I of
 *       IN.obj and the same (position, uv) corners as a set, within T (positions: T * max(1, |x|),
 *       texcoords: T; default 1e-6). Prints "vertices A -> B, faces C -> D".
 * Exit status 0 ok, 1 bad input or check failed, 2 usage.
 *
 * Modules: vt_obj2ply_mesh.c (reading), vt_obj2ply_convert.c (PLY), vt_obj2ply_restore.c,
 * vt_obj2ply_check.c, vt_obj2ply_out.c (buffered output), vt_obj2ply_path.c. */
#include <errno.h>
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tool_common.h"
#include "vt_atomic_file.h"
#include "vt_error.h"
#include "vt_obj2ply_check.h"
#include "vt_obj2ply_convert.h"
#include "vt_obj2ply_mesh.h"
#include "vt_obj2ply_restore.h"

static void usage(FILE *f)
{
    fprintf(f, "usage: vt-obj2ply IN.obj -o OUT.ply\n"
               "       vt-obj2ply --restore IN.obj MESHLAB.obj -o OUT.obj\n"
               "       vt-obj2ply --check IN.obj OUT.obj [--same-faces] [--tolerance T]\n"
               "The OBJ side of scripts/mesh-clean (MeshLab reads PLY only): converts an OBJ to a\n"
               "PLY with wedge texture coordinates, restores the original materials in the OBJ\n"
               "meshlabserver wrote, and checks the result against the input.\n"
               "  -o, --output FILE  the file to write\n"
               "  --restore          the original materials back into MeshLab's OBJ\n"
               "  --check            compare OUT.obj with IN.obj; writes nothing\n"
               "  --same-faces       --check: face I must have the corners of input triangle I\n"
               "  --tolerance T      --check: largest difference (default 1e-6)\n"
               "  -q, --quiet        errors only\n"
               "  -h, --help         this help\n"
               "  --version          version\n");
}

int main(int argc, char **argv)
{
    vt_tool_init("vt-obj2ply");
    vt_atomic_file_cleanup_on_signals();
    enum { OPT_RESTORE = 256, OPT_CHECK, OPT_SAME, OPT_TOL, OPT_VERSION };
    static const struct option longopts[] = {{"output", required_argument, NULL, 'o'},
                                             {"restore", no_argument, NULL, OPT_RESTORE},
                                             {"check", no_argument, NULL, OPT_CHECK},
                                             {"same-faces", no_argument, NULL, OPT_SAME},
                                             {"tolerance", required_argument, NULL, OPT_TOL},
                                             {"quiet", no_argument, NULL, 'q'},
                                             {"help", no_argument, NULL, 'h'},
                                             {"version", no_argument, NULL, OPT_VERSION},
                                             {NULL, 0, NULL, 0}};
    const char *output = NULL;
    bool do_restore = false, do_check = false, same_faces = false;
    double tol = 1e-6;
    opterr = 0;
    int c;
    while ((c = vt_getopt_long(argc, argv, ":o:qh", longopts)) != -1) {
        switch (c) {
        case 'o':
            output = optarg;
            break;
        case OPT_RESTORE:
            do_restore = true;
            break;
        case OPT_CHECK:
            do_check = true;
            break;
        case OPT_SAME:
            same_faces = true;
            break;
        case OPT_TOL: {
            char *end;
            errno = 0;
            tol = strtod(optarg, &end);
            if (errno || end == optarg || *end || !(tol >= 0) || !isfinite(tol))
                return vt_usage_error("bad --tolerance '%s'", optarg);
            break;
        }
        case 'q':
            vt_log_set_level(VT_LOG_ERROR);
            break;
        case 'h':
            usage(stdout);
            return VT_EXIT_OK;
        case OPT_VERSION:
            vt_print_version(stdout);
            return VT_EXIT_OK;
        default:
            return vt_usage_getopt_error(c, argv);
        }
    }
    int nargs = argc - optind;
    if (do_restore && do_check)
        return vt_usage_error("--restore and --check exclude each other");
    if ((do_restore || do_check) ? nargs != 2 : nargs != 1)
        return vt_usage_error("wrong number of files");
    if (!do_check && !output)
        return vt_usage_error("no output: give -o FILE");
    if (do_check && output)
        return vt_usage_error("--check writes nothing: no -o");
    if (!do_check && same_faces)
        return vt_usage_error("--same-faces needs --check");
    const char *inputs[] = {argv[optind], nargs > 1 ? argv[optind + 1] : NULL};
    int status = vt_check_output(output, inputs, 2);
    if (status >= 0)
        return status;

    struct vts_error err = {0};
    struct vt_obj2ply_mesh a, b;
    memset(&b, 0, sizeof(b));
    int rc = vt_obj2ply_mesh_read(&a, argv[optind], &err);
    if (!rc && do_restore)
        rc = vt_obj2ply_restore_write(&a, argv[optind + 1], output, &err);
    else if (!rc && do_check) {
        rc = vt_obj2ply_mesh_read_mtls(&a, &err);
        if (!rc)
            rc = vt_obj2ply_mesh_read(&b, argv[optind + 1], &err);
        if (!rc)
            rc = vt_obj2ply_mesh_read_mtls(&b, &err);
        if (!rc)
            rc = vt_obj2ply_check_compare(&a, &b, same_faces, tol, &err);
    } else if (!rc) {
        rc = vt_obj2ply_convert_write(&a, output, &err);
    }
    vt_obj2ply_mesh_release(&a);
    vt_obj2ply_mesh_release(&b);
    if (rc) {
        vt_log(VT_LOG_ERROR, "%s", err.message);
        return VT_EXIT_BAD_INPUT;
    }
    return VT_EXIT_OK;
}
