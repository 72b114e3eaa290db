#include "vt_error.h"

#include <stdarg.h>
#include <stdio.h>

int vt_error_set(struct vt_error *err, int status, const char *fmt, ...)
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

void vt_error_clear(struct vt_error *err)
{
    if (err) {
        err->status = VT_OK;
        err->message[0] = '\0';
    }
}

const char *vt_status_name(int status)
{
    switch (status) {
    case VT_OK:
        return "ok";
    case VT_ERR_IO:
        return "io";
    case VT_ERR_NOMEM:
        return "nomem";
    case VT_ERR_NOT_VTS:
        return "not-vts";
    case VT_ERR_VERSION:
        return "version";
    case VT_ERR_CORRUPT:
        return "corrupt";
    case VT_ERR_CHECKSUM:
        return "checksum";
    case VT_ERR_RANGE:
        return "range";
    case VT_ERR_LIMIT:
        return "limit";
    case VT_ERR_UNSUPPORTED:
        return "unsupported";
    case VT_ERR_ARG:
        return "arg";
    case VT_ERR_CANCELLED:
        return "cancelled";
    case VT_ERR_BAD_INPUT:
        return "bad-input";
    default:
        return "unknown";
    }
}
