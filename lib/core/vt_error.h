/* Filling the caller's struct vts_error (the type and the status values are the public API's:
 * include/vts/vts.h). Internal to vtpipe: not exported from libvts.so. */
#ifndef VT_ERROR_H
#define VT_ERROR_H

#include "vts.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Fills err (if not NULL) with status and a printf-style message (control characters such as a
 * newline in a quoted file name become '?', so a message is always one line); returns status so
 * that callers can write `return vt_error_set(err, VTS_ERR_IO, ...)`. Truncates long messages.
 * Thread-safe. */
int vt_error_set(struct vts_error *err, int status, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* Resets err to VTS_OK with an empty message. Accepts NULL. */
void vt_error_clear(struct vts_error *err);

#ifdef __cplusplus
}
#endif
#endif
