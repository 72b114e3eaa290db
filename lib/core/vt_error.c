#include "vt_error.h"

#include <stdarg.h>
#include <stdio.h>

int vt_error_set(struct vts_error *err, int status, const char *fmt, ...)
{
    if (err) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(err->message, sizeof err->message, fmt, ap);
        va_end(ap);
        /* Messages are one line whatever a file name or a quoted input holds. */
        for (char *p = err->message; *p; p++)
            if ((unsigned char)*p < 0x20 || *p == 0x7f)
                *p = '?';
        err->status = status;
    }
    return status;
}

void vt_error_clear(struct vts_error *err)
{
    if (err) {
        err->status = VTS_OK;
        err->message[0] = '\0';
    }
}
