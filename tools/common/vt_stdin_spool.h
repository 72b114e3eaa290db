/* An input "-": standard input copied to its end into a scratch file in $TMPDIR (or /tmp), so
 * that the readers, which seek, open it as a file. Unnamed (O_TMPFILE) where the file system
 * allows, reached through /proc/self/fd; else a hidden named file removed on release or on a
 * signal (vt_atomic_file_create_tmp). Messages name it '<stdin>' (VT_STDIN_NAME). */
#ifndef VT_STDIN_SPOOL_H
#define VT_STDIN_SPOOL_H

#include <stdbool.h>
#include <stdint.h>

#include "vt_atomic_file.h"
#include "vt_error.h"

struct vt_stdin_spool {
    struct vt_atomic_file file; /* the copy, open for reading and writing (file.fd) */
    char path[VT_PATH_MAX];     /* opens the copy: /proc/self/fd/N, or the named file */
    uint64_t size;              /* bytes read */
    bool open;                  /* file is ours to abort */
};

/* Reads standard input to its end into a new scratch file. Returns 0, or VTS_ERR_IO (a read or
 * write error), VTS_ERR_BAD_INPUT ("'<stdin>' is empty": nothing to read) or VTS_ERR_ARG, with a
 * message naming '<stdin>'. Release with vt_stdin_spool_release() either way. */
int vt_stdin_spool_read(struct vt_stdin_spool *s, struct vts_error *err);

/* Closes and removes the copy. Accepts a zeroed struct and one already released. */
void vt_stdin_spool_release(struct vt_stdin_spool *s);

#endif
