#include "vt_output_path.h"

#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define MAX_LINKS 40

/* Replaces the link path in cur (of length cur_len) by its target read into target. */
static int follow_link(char *cur, const char *target, size_t target_len)
{
    if (target[0] == '/' || !strrchr(cur, '/')) {
        if (target_len >= VT_PATH_MAX)
            return -1;
        memcpy(cur, target, target_len + 1);
        return 0;
    }
    size_t dir_len = (size_t)(strrchr(cur, '/') - cur) + 1; /* keeps the slash */
    if (dir_len + target_len >= VT_PATH_MAX)
        return -1;
    memcpy(cur + dir_len, target, target_len + 1);
    return 0;
}

static void describe(struct vt_output_target *t, const struct stat *st)
{
    t->kind = S_ISREG(st->st_mode)   ? VT_OUTPUT_REGULAR
              : S_ISDIR(st->st_mode) ? VT_OUTPUT_DIRECTORY
                                     : VT_OUTPUT_SPECIAL;
    t->dev = st->st_dev;
    t->ino = st->st_ino;
    t->mode = st->st_mode;
    t->uid = st->st_uid;
    t->gid = st->st_gid;
}

/* Set once from main (vt_output_path_use_stdio), read by every path decision after it: whether
 * "-" is standard input and output is the command line's convention, not the library's. */
static bool use_stdio;

void vt_output_path_use_stdio(void)
{
    use_stdio = true;
}

bool vt_output_path_is_stdio(const char *path)
{
    return use_stdio && path && strcmp(path, VT_PATH_STDIO) == 0;
}

/* The name of a path in messages: "<stdin>" / "<stdout>" for "-", else the path. */
static const char *shown(const char *path, bool is_input)
{
    if (!vt_output_path_is_stdio(path))
        return path;
    return is_input ? VT_STDIN_NAME : VT_STDOUT_NAME;
}

int vt_output_path_resolve(const char *output, struct vt_output_target *t, struct vts_error *err)
{
    memset(t, 0, sizeof *t);
    struct stat st;
    if (vt_output_path_is_stdio(output)) {
        /* written into whatever file descriptor 1 is: never renamed over, not even a regular file
         * (the shell opened it; it may be appended to, or hold what came before) */
        if (fstat(STDOUT_FILENO, &st) == 0)
            describe(t, &st);
        t->kind = VT_OUTPUT_SPECIAL;
        memcpy(t->path, VT_PATH_STDIO, sizeof VT_PATH_STDIO);
        return 0;
    }
    size_t len = strlen(output);
    if (len >= sizeof t->path)
        return vt_error_set(err, VTS_ERR_ARG, "output path '%s' is too long", output);
    memcpy(t->path, output, len + 1);
    if (stat(output, &st) == 0 && !S_ISREG(st.st_mode) && !S_ISDIR(st.st_mode)) {
        /* a device, FIFO or socket is opened, never renamed: keep the path as given, which also
         * works through /proc's links (/dev/stdout -> /proc/self/fd/1 -> "pipe:[N]") */
        describe(t, &st);
        return 0;
    }
    for (int links = 0; links <= MAX_LINKS; links++) {
        if (lstat(t->path, &st) != 0) {
            t->kind = VT_OUTPUT_NEW;
            return 0;
        }
        if (S_ISLNK(st.st_mode)) {
            char target[VT_PATH_MAX];
            ssize_t n = readlink(t->path, target, sizeof target - 1);
            if (n <= 0) {
                t->kind = VT_OUTPUT_NEW;
                return 0;
            }
            target[n] = '\0';
            if (follow_link(t->path, target, (size_t)n) != 0)
                return vt_error_set(err, VTS_ERR_ARG,
                                    "output path '%s' resolves to a path too long", output);
            continue;
        }
        describe(t, &st);
        return 0;
    }
    return vt_error_set(err, VTS_ERR_ARG, "output '%s': too many levels of symbolic links", output);
}

int vt_output_path_scratch_dir(const char *output, char *dir, size_t dir_cap, struct vts_error *err)
{
    struct vt_output_target t;
    int rc = vt_output_path_resolve(output, &t, err);
    if (rc != 0)
        return rc;
    int n;
    if (t.kind == VT_OUTPUT_SPECIAL) {
        const char *tmp = getenv("TMPDIR");
        n = snprintf(dir, dir_cap, "%s", tmp && *tmp ? tmp : "/tmp");
    } else {
        const char *slash = strrchr(t.path, '/');
        n = snprintf(dir, dir_cap, "%.*s", slash ? (int)(slash - t.path) + (slash == t.path) : 1,
                     slash ? t.path : ".");
    }
    if (n < 0 || (size_t)n >= dir_cap)
        return vt_error_set(err, VTS_ERR_ARG, "the directory for scratch files of '%s' is too long",
                            output);
    return 0;
}

int vt_output_path_check(const char *output, const char *const *inputs, size_t input_count,
                         struct vts_error *err)
{
    struct vt_output_target t;
    int rc = vt_output_path_resolve(output, &t, err);
    if (rc != 0)
        return rc;
    if (t.kind == VT_OUTPUT_DIRECTORY)
        return vt_error_set(err, VTS_ERR_ARG, "output '%s' is a directory", output);
    for (size_t i = 0; i < input_count; i++) {
        struct stat st;
        struct vt_output_target in;
        bool same = false;
        if (!inputs[i])
            continue;
        if (vt_output_path_is_stdio(inputs[i])) /* standard input, before it is read */
            same = fstat(STDIN_FILENO, &st) == 0 && S_ISREG(st.st_mode) &&
                   t.kind != VT_OUTPUT_NEW && st.st_dev == t.dev && st.st_ino == t.ino;
        else if (stat(inputs[i], &st) == 0)
            same = t.kind != VT_OUTPUT_NEW && st.st_dev == t.dev && st.st_ino == t.ino;
        else if (t.kind == VT_OUTPUT_NEW && vt_output_path_resolve(inputs[i], &in, NULL) == 0)
            same = strcmp(in.path, t.path) == 0; /* not there yet (another output): one name */
        if (same)
            return vt_error_set(err, VTS_ERR_ARG, "output '%s' is the input '%s' (the same file)",
                                shown(output, false), shown(inputs[i], true));
    }
    return 0;
}
