/* Output files that appear under their final name only when complete (temp file + rename).
 *
 * What the final path names decides how (vt_output_path_resolve):
 * - nothing or a regular file: a hidden temporary file next to it, renamed over it at commit; an
 *   existing file's permission bits (and owner and group, as root) are kept;
 * - a symbolic link: the same, next to the link's resolved target, renamed over the target (the
 *   link stays a link);
 * - a directory: refused (VTS_ERR_ARG);
 * - a device, FIFO or socket: never renamed over. Writers that declare VT_ATOMIC_FILE_SEQUENTIAL
 *   write straight into it; others write an unnamed scratch file (in $TMPDIR, or /tmp) that commit
 *   copies into it. Either way, nothing can be taken back once written;
 * - "-", once vt_output_path_use_stdio() was called: standard output, whatever file descriptor 1
 *   is (a regular file too: written into at its offset, never renamed over), as a device above;
 *   messages name it '<stdout>'. Before that call, "-" is a file name like any other. */
#ifndef VT_ATOMIC_FILE_H
#define VT_ATOMIC_FILE_H

#include <stddef.h>

#include "vt_error.h"

#include "vt_output_path.h"

enum vt_atomic_file_flags {
    /* Every write starts where the previous one ended (offsets 0, n, n + m...): a device or FIFO
     * output is written into directly instead of through a scratch file. */
    VT_ATOMIC_FILE_SEQUENTIAL = 1 << 0,
};

enum vt_atomic_file_mode {
    VT_ATOMIC_FILE_RENAME = 0, /* temp_path renamed over target_path at commit */
    VT_ATOMIC_FILE_STREAM,     /* fd is the device or FIFO itself */
    VT_ATOMIC_FILE_SPOOL,      /* fd is an unnamed scratch file, copied into device_fd at commit */
};

/* A zeroed struct with fd = -1 is a closed one (vt_atomic_file_abort does nothing). */
struct vt_atomic_file {
    int fd;                        /* open for read and write; -1 when closed */
    char final_path[VT_PATH_MAX];  /* as given: the name in messages ("-": '<stdout>') */
    char temp_path[VT_PATH_MAX];   /* hidden file next to the target: .<name>.<tag>-XXXXXX */
    char target_path[VT_PATH_MAX]; /* final_path with its symbolic links followed */
    enum vt_atomic_file_mode mode; /* set by create, kept after commit and abort */
    int device_fd;                 /* VT_ATOMIC_FILE_SPOOL: the output, open for writing */
    unsigned long long stream_end; /* VT_ATOMIC_FILE_STREAM: bytes written so far */
};

/* Opens final_path for writing as described above (a new temporary file has permissions
 * 0666 & ~umask, or those of the file it replaces). tag names its role in the temporary name
 * ("tmp", "spool"); flags are enum vt_atomic_file_flags. Opening a FIFO waits for its reader.
 * Returns 0 or VTS_ERR_IO / VTS_ERR_ARG (a directory, a path too long). */
int vt_atomic_file_create(struct vt_atomic_file *f, const char *final_path, const char *tag,
                          unsigned flags, struct vts_error *err);

/* Like vt_atomic_file_create(), for a scratch file that is never committed, next to final_path's
 * target (in $TMPDIR or /tmp when that is a device or FIFO; a directory is refused): it has no
 * name where the file system allows (O_TMPFILE), so nothing is left even if the process is
 * killed; falls back to a hidden named file otherwise. */
int vt_atomic_file_create_scratch(struct vt_atomic_file *f, const char *final_path,
                                  struct vts_error *err);

/* A scratch file that is never committed and belongs to no output (the spool of standard input):
 * unnamed (O_TMPFILE) in $TMPDIR, or /tmp, where the file system allows, else a hidden named file
 * there (temp_path, removed by vt_atomic_file_abort() or a signal). name is its name in messages.
 * Returns 0, or VTS_ERR_IO / VTS_ERR_ARG with a message naming name and the directory. */
int vt_atomic_file_create_tmp(struct vt_atomic_file *f, const char *name, struct vts_error *err);

/* Flushes the temporary file to disk, closes it and renames it over the target, then flushes the
 * directory. On failure the temporary file is removed and final_path is untouched. A device or
 * FIFO output gets the spooled bytes (VT_ATOMIC_FILE_SPOOL) and is closed. */
int vt_atomic_file_commit(struct vt_atomic_file *f, struct vts_error *err);

/* Closes and removes the temporary file (no-op when already committed or aborted). */
void vt_atomic_file_abort(struct vt_atomic_file *f);

/* pwrite of the whole buffer, retrying short writes and EINTR; VTS_ERR_IO with a message naming
 * the final path on failure (ENOSPC included, and an offset out of order on a stream). */
int vt_atomic_file_pwrite(struct vt_atomic_file *f, const void *buf, size_t len,
                          unsigned long long off, struct vts_error *err);

/* Installs SIGINT, SIGTERM and SIGHUP handlers that remove every temporary file still open in this
 * process, then die of the signal as before. Call once at the start of a tool's main. */
void vt_atomic_file_cleanup_on_signals(void);

#endif
