/* Test helper shared by the end-to-end atlas tests (tests/pipeline, tests/atlas): every face
 * corner of an OBJ with its material and texture coordinate, in file order, and a logged
 * system(). */
#ifndef VT_TEST_CORNERS_H
#define VT_TEST_CORNERS_H

#include <stdint.h>

#include "vt_error.h"

struct vt_test_corners {
    uint32_t count, cap;
    int *material; /* index into the names given to vt_test_corners_read(), -1 for others */
    double *uv;    /* u, v per corner */
};

/* Reads the OBJ at file (lib/obj/vt_obj.h) into *c (zeroed first). Returns 0 or the reader's status
 * with its message in err. Release *c with vt_test_corners_release() either way. */
int vt_test_corners_read(const char *file, const char *const *names, int name_count,
                         struct vt_test_corners *c, struct vts_error *err);
void vt_test_corners_release(struct vt_test_corners *c);

/* Prints "+ cmd" on stderr and runs it with system(); returns its status. */
int vt_test_run(const char *cmd);

#endif
