/* What an output path names before a tool writes it: a new file, a regular file (possibly through
 * symbolic links), a directory or a device/FIFO/socket; and whether it is one of the tool's inputs.
 * Used by vt_atomic_file (where to put the temporary file, how to commit) and by every tool right
 * after validating its options (vt_output_path_check). */
#ifndef VT_OUTPUT_PATH_H
#define VT_OUTPUT_PATH_H

#include <stdbool.h>
#include <stddef.h>
#include <sys/types.h>

#include "vt_error.h"

#define VT_PATH_MAX 4096

/* Once vt_output_path_use_stdio() is called, "-" names standard output as an output
 * (vt_output_path_resolve, vt_atomic_file: written into file descriptor 1, never renamed over) and
 * standard input as an input of vt_output_path_check(); messages call them VT_STDOUT_NAME and
 * VT_STDIN_NAME. A file named "-" is "./-". */
#define VT_PATH_STDIO  "-"
#define VT_STDIN_NAME  "<stdin>"
#define VT_STDOUT_NAME "<stdout>"

/* Makes "-" mean standard input and output in this process, from now on (the default keeps "-" a
 * file name, so that a library user, or a tool that does not document "-", is unchanged). Call
 * once at the start of main, before any thread. */
void vt_output_path_use_stdio(void);

/* True when "-" names standard input and output (vt_output_path_use_stdio) and path is "-". */
bool vt_output_path_is_stdio(const char *path);

enum vt_output_kind {
    VT_OUTPUT_NEW = 0,   /* nothing there yet (or a dangling symbolic link's target) */
    VT_OUTPUT_REGULAR,   /* an existing regular file: replaced by a rename */
    VT_OUTPUT_DIRECTORY, /* refused */
    VT_OUTPUT_SPECIAL,   /* character or block device, FIFO, socket, or "-" (standard output,
                            whatever it is): written into, never renamed */
};

struct vt_output_target {
    char
        path[VT_PATH_MAX]; /* the output with its symbolic links followed: what a rename replaces */
    enum vt_output_kind kind;
    dev_t dev; /* of the existing file (kind REGULAR, DIRECTORY, SPECIAL) */
    ino_t ino;
    mode_t mode; /* st_mode of the existing file */
    uid_t uid;
    gid_t gid;
};

/* Follows output through every symbolic link it ends in (relative targets against the link's
 * directory, at most 40 links) and describes what is there; a device, FIFO or socket keeps the
 * path as given (opened, never renamed: also through /proc's links, /dev/stdout -> "pipe:[N]").
 * "-" is standard output: VT_OUTPUT_SPECIAL with path "-" whatever file descriptor 1 is (a
 * regular file too: it is written into, never replaced), dev and ino those of file descriptor 1
 * (zero when it is closed). A path that cannot be examined (no
 * such directory, no permission) is reported as VT_OUTPUT_NEW: creating the file names the error.
 * Returns 0, or VTS_ERR_ARG for a path too long or a loop of links. */
int vt_output_path_resolve(const char *output, struct vt_output_target *t, struct vts_error *err);

/* The directory for a tool's scratch files of output (pass images): that of its resolved target
 * ("." for a bare name, "/" for one at the root), or $TMPDIR (else /tmp) for a device, FIFO,
 * socket or "-". Returns 0, or VTS_ERR_ARG when it does not fit in dir_cap bytes. */
int vt_output_path_scratch_dir(const char *output, char *dir, size_t dir_cap,
                               struct vts_error *err);

/* The check every tool makes before any work: refuses (VTS_ERR_ARG) an output that is an existing
 * directory, or that is the same file (device and inode, after following links; a hard link
 * counts) as one of the inputs[0..input_count). An input not there yet (another output of the
 * tool) is the same file when both paths resolve to one name. NULL entries are skipped. An output
 * "-" is file descriptor 1, an input "-" file descriptor 0 (when it is a regular file, compared by
 * device and inode, so that `tool - -o X <X` is refused; a pipe, socket or terminal read and
 * written at once destroys nothing). The message names the output and the input: "output 'a.png' is
 * the input 'b.png' (the same file)", '<stdout>' and '<stdin>' for "-".
 * Returns 0 or a negative vts_status. */
int vt_output_path_check(const char *output, const char *const *inputs, size_t input_count,
                         struct vts_error *err);

#endif
