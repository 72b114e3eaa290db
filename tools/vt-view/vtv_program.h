/* vt-view GL programs: one vertex and one fragment shader, each assembled from source pieces,
 * compiled and linked, with the compiler's or linker's log in the error. Needs a current GL 3.3
 * core context. */
#ifndef VTV_PROGRAM_H
#define VTV_PROGRAM_H

#include <epoxy/gl.h>

#include "vt_error.h"

/* vs: vs_count pieces of the vertex shader; fs: fs_count pieces of the fragment shader; what names
 * the program in messages ("cannot compile the <what> vertex shader: <log>"). Returns the program,
 * or 0 and err (VTS_ERR_UNSUPPORTED). */
GLuint vtv_program_build(const char *const *vs, int vs_count, const char *const *fs, int fs_count,
                         const char *what, struct vts_error *err);

#endif
