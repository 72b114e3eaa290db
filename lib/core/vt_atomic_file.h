/* Output files that appear under their final name only when complete (temp file + rename). */
#ifndef VT_ATOMIC_FILE_H
#define VT_ATOMIC_FILE_H

#include <stddef.h>

#include "vt_error.h"

#define VT_PATH_MAX 4096

struct vt_atomic_file {
    int fd; /* open for read and write; -1 when closed */
    char final_path[VT_PATH_MAX];
    char temp_path[VT_PATH_MAX]; /* hidden file in the same directory: .<name>.<tag>-XXXXXX */
};

/* Creates a new empty temporary file next to final_path (permissions 0666 & ~umask). tag names
 * its role in the temporary name ("tmp", "spool"). Returns 0 or VTS_ERR_IO / VTS_ERR_ARG. */
int vt_atomic_file_create(struct vt_atomic_file *f, const char *final_path, const char *tag,
                          struct vts_error *err);

/* Like vt_atomic_file_create(), for a scratch file that is never committed: it has no name where
 * the file system allows (O_TMPFILE), so nothing is left even if the process is killed; falls
 * back to a hidden named file otherwise. */
int vt_atomic_file_create_scratch(struct vt_atomic_file *f, const char *final_path,
                                  struct vts_error *err);

/* Flushes the temporary file to disk, closes it and renames it over final_path, then flushes the
 * directory. On failure the temporary file is removed and final_path is untouched. */
int vt_atomic_file_commit(struct vt_atomic_file *f, struct vts_error *err);

/* Closes and removes the temporary file (no-op when already committed or aborted). */
void vt_atomic_file_abort(struct vt_atomic_file *f);

/* pwrite of the whole buffer, retrying short writes and EINTR; VTS_ERR_IO with a message naming
 * the final path on failure (ENOSPC included). */
int vt_atomic_file_pwrite(struct vt_atomic_file *f, const void *buf, size_t len,
                          unsigned long long off, struct vts_error *err);

/* Installs SIGINT, SIGTERM and SIGHUP handlers that remove every temporary file still open in this
 * process, then die of the signal as before. Call once at the start of a tool's main. */
void vt_atomic_file_cleanup_on_signals(void);

#endif
