/* Status codes and the error record that travels with every call that can fail. */
#ifndef VT_ERROR_H
#define VT_ERROR_H

#ifdef __cplusplus
extern "C" {
#endif

/* Pinned values: scripts and other languages test them. Never renumber, only append. */
enum vt_status {
    VT_OK = 0,
    VT_ERR_IO = -1,          /* open/read/write/rename failed; the message carries strerror */
    VT_ERR_NOMEM = -2,       /* allocation failed */
    VT_ERR_NOT_VTS = -3,     /* the file is not a .vts store (bad magic) */
    VT_ERR_VERSION = -4,     /* a .vts store of a major version this reader does not know */
    VT_ERR_CORRUPT = -5,     /* structure invalid: offsets, lengths, counts, geometry */
    VT_ERR_CHECKSUM = -6,    /* a CRC-32C does not match */
    VT_ERR_RANGE = -7,       /* layer/level/tile/key outside what the store holds */
    VT_ERR_LIMIT = -8,       /* a size overflows or exceeds a configured limit */
    VT_ERR_UNSUPPORTED = -9, /* a codec or sample type this build cannot handle */
    VT_ERR_ARG = -10,        /* invalid argument from the caller */
    VT_ERR_CANCELLED = -11,  /* a progress callback asked to stop */
    VT_ERR_BAD_INPUT = -12,  /* an input file (image, payload, text) is malformed */
};

#define VT_ERROR_MESSAGE_MAX 256

/* Owned by the caller; functions that take one may be given NULL. */
struct vt_error {
    int status;                         /* VT_OK or a negative enum vt_status */
    char message[VT_ERROR_MESSAGE_MAX]; /* one line, no trailing newline */
};

/* Fills err (if not NULL) with status and a printf-style message (control characters such as a
 * newline in a quoted file name become '?', so a message is always one line); returns status so
 * that callers can write `return vt_error_set(err, VT_ERR_IO, ...)`. Truncates long messages.
 * Thread-safe. */
int vt_error_set(struct vt_error *err, int status, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* Resets err to VT_OK with an empty message. Accepts NULL. */
void vt_error_clear(struct vt_error *err);

/* Stable lowercase name of a status ("corrupt", "checksum"...); "unknown" for other values. */
const char *vt_status_name(int status);

#ifdef __cplusplus
}
#endif
#endif
