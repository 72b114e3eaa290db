#include "vt_stdin_spool.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define CHUNK (1 << 16)

int vt_stdin_spool_read(struct vt_stdin_spool *s, struct vts_error *err)
{
    memset(s, 0, sizeof *s);
    s->file.fd = -1;
    int rc = vt_atomic_file_create_tmp(&s->file, VT_STDIN_NAME, err);
    if (rc != 0)
        return rc;
    s->open = true;
    if (s->file.temp_path[0])
        snprintf(s->path, sizeof s->path, "%s", s->file.temp_path);
    else
        snprintf(s->path, sizeof s->path, "/proc/self/fd/%d", s->file.fd);
    unsigned char *buf = malloc(CHUNK);
    if (!buf)
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory reading '%s'", VT_STDIN_NAME);
    for (;;) {
        ssize_t n = read(STDIN_FILENO, buf, CHUNK);
        if (n < 0 && errno == EINTR)
            continue;
        if (n < 0) {
            rc = vt_error_set(err, VTS_ERR_IO, "cannot read '%s': %s", VT_STDIN_NAME,
                              strerror(errno));
            break;
        }
        if (n == 0)
            break;
        rc = vt_atomic_file_pwrite(&s->file, buf, (size_t)n, s->size, err);
        if (rc != 0)
            break;
        s->size += (uint64_t)n;
    }
    free(buf);
    if (rc == 0 && s->size == 0)
        rc = vt_error_set(err, VTS_ERR_BAD_INPUT, "'%s' is empty", VT_STDIN_NAME);
    return rc;
}

void vt_stdin_spool_release(struct vt_stdin_spool *s)
{
    if (s->open)
        vt_atomic_file_abort(&s->file);
    s->open = false;
    s->path[0] = '\0';
}
