#define _GNU_SOURCE /* O_TMPFILE */
#include "vt_atomic_file.h"
#include "vt_error.h"

#include <errno.h>
#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

/* Temporary files the signal handler removes. A process-wide table is unavoidable here: a signal
 * handler has no other way to find them. Slots hold pointers into live vt_atomic_file structs;
 * the handler only reads them and calls unlink(), which is async-signal-safe. */
#define TEMP_SLOTS 256
static const char *volatile temp_slots[TEMP_SLOTS];
static pthread_mutex_t temp_lock = PTHREAD_MUTEX_INITIALIZER;

static void temp_register(const char *path)
{
    pthread_mutex_lock(&temp_lock);
    for (int i = 0; i < TEMP_SLOTS; i++)
        if (!temp_slots[i]) {
            temp_slots[i] = path;
            break;
        }
    pthread_mutex_unlock(&temp_lock);
}

static void temp_unregister(const char *path)
{
    pthread_mutex_lock(&temp_lock);
    for (int i = 0; i < TEMP_SLOTS; i++)
        if (temp_slots[i] == path)
            temp_slots[i] = NULL;
    pthread_mutex_unlock(&temp_lock);
}

static void remove_temps_and_die(int sig)
{
    for (int i = 0; i < TEMP_SLOTS; i++) {
        const char *p = temp_slots[i];
        if (p)
            unlink(p);
    }
    signal(sig, SIG_DFL);
    raise(sig);
}

/* The signals the handler cleans up after, blocked in the calling thread (old receives the mask
 * before): around a temporary file's creation and registration, so that the handler never runs
 * between the two (it would leave the file behind). */
static void block_cleanup_signals(sigset_t *old)
{
    sigset_t set;
    sigemptyset(&set);
    sigaddset(&set, SIGINT);
    sigaddset(&set, SIGTERM);
    sigaddset(&set, SIGHUP);
    pthread_sigmask(SIG_BLOCK, &set, old);
}

void vt_atomic_file_cleanup_on_signals(void)
{
    static const int sigs[] = {SIGINT, SIGTERM, SIGHUP};
    for (size_t i = 0; i < sizeof sigs / sizeof sigs[0]; i++) {
        struct sigaction sa;
        memset(&sa, 0, sizeof sa);
        sa.sa_handler = remove_temps_and_die;
        sigemptyset(&sa.sa_mask);
        sigaction(sigs[i], &sa, NULL);
    }
}

/* Splits path into directory (without trailing slash; "." when none) and base name. */
static int split_path(const char *path, char *dir, size_t dir_cap, const char **base)
{
    const char *slash = strrchr(path, '/');
    if (!slash) {
        *base = path;
        return snprintf(dir, dir_cap, ".") < (int)dir_cap ? 0 : -1;
    }
    *base = slash + 1;
    size_t n = slash == path ? 1 : (size_t)(slash - path);
    if (n >= dir_cap)
        return -1;
    memcpy(dir, path, n);
    dir[n] = '\0';
    return 0;
}

static void reset(struct vt_atomic_file *f)
{
    f->fd = -1;
    f->device_fd = -1;
    f->mode = VT_ATOMIC_FILE_RENAME;
    f->stream_end = 0;
    f->temp_path[0] = '\0';
    f->final_path[0] = '\0';
    f->target_path[0] = '\0';
}

/* The output's name in messages: "<stdout>" for "-", else final_path as given. */
static const char *shown(const struct vt_atomic_file *f)
{
    return vt_output_path_is_stdio(f->final_path) ? VT_STDOUT_NAME : f->final_path;
}

/* Records final_path and resolves it into f->target_path and *t. */
static int resolve(struct vt_atomic_file *f, const char *final_path, struct vt_output_target *t,
                   struct vts_error *err)
{
    size_t len = strlen(final_path);
    if (len == 0 || len >= sizeof f->final_path)
        return vt_error_set(err, VTS_ERR_ARG, "invalid output path '%s'", final_path);
    memcpy(f->final_path, final_path, len + 1);
    int rc = vt_output_path_resolve(final_path, t, err);
    if (rc != 0)
        return rc;
    if (t->kind == VT_OUTPUT_DIRECTORY)
        return vt_error_set(err, VTS_ERR_ARG, "cannot write '%s': it is a directory", final_path);
    memcpy(f->target_path, t->path, strlen(t->path) + 1);
    return 0;
}

/* Creates f->temp_path, a new hidden file next to path (.<base>.<tag>-XXXXXX), open in f->fd. */
static int create_named_temp(struct vt_atomic_file *f, const char *path, const char *tag,
                             struct vts_error *err)
{
    char dir[VT_PATH_MAX];
    const char *base;
    if (split_path(path, dir, sizeof dir, &base) || *base == '\0')
        return vt_error_set(err, VTS_ERR_ARG, "invalid output path '%s'", f->final_path);
    /* O_EXCL with a fresh name each try: no race with other writers of the same output. */
    static const char digits[] = "abcdefghijklmnopqrstuvwxyz0123456789";
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    uint64_t seed = (uint64_t)ts.tv_nsec ^ ((uint64_t)getpid() << 32) ^ (uint64_t)(uintptr_t)f;
    for (int attempt = 0; attempt < 100; attempt++) {
        char suffix[7];
        for (int i = 0; i < 6; i++) {
            seed = seed * 6364136223846793005ull + 1442695040888963407ull;
            suffix[i] = digits[(seed >> 33) % (sizeof digits - 1)];
        }
        suffix[6] = '\0';
        int n = strcmp(dir, ".") == 0 && !strchr(path, '/')
                    ? snprintf(f->temp_path, sizeof f->temp_path, ".%s.%s-%s", base, tag, suffix)
                    : snprintf(f->temp_path, sizeof f->temp_path, "%s/.%s.%s-%s",
                               strcmp(dir, "/") == 0 ? "" : dir, base, tag, suffix);
        if (n < 0 || (size_t)n >= sizeof f->temp_path) {
            f->temp_path[0] = '\0';
            return vt_error_set(err, VTS_ERR_ARG, "output path '%s' is too long", f->final_path);
        }
        /* A signal pending meanwhile is handled once the file is registered. The pool's workers
         * block these signals (vt_pool.c), so none of them takes it in this window instead. */
        sigset_t old;
        block_cleanup_signals(&old);
        f->fd = open(f->temp_path, O_RDWR | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        int open_errno = errno;
        if (f->fd >= 0)
            temp_register(f->temp_path);
        pthread_sigmask(SIG_SETMASK, &old, NULL);
        if (f->fd >= 0)
            return 0;
        errno = open_errno;
        if (errno != EEXIST)
            break;
    }
    int e = errno;
    f->temp_path[0] = '\0';
    if (strcmp(path, f->target_path) != 0) /* in $TMPDIR: for a device, "-" or no output */
        return vt_error_set(err, VTS_ERR_IO, "cannot create a scratch file for '%s' in '%s': %s",
                            shown(f), dir, strerror(e));
    return vt_error_set(err, VTS_ERR_IO, "cannot create a file next to '%s': %s", shown(f),
                        strerror(e));
}

/* Opens an unnamed file in the directory of path (O_TMPFILE), or a named hidden one there. */
static int create_unnamed_temp(struct vt_atomic_file *f, const char *path, struct vts_error *err)
{
#ifdef O_TMPFILE
    char dir[VT_PATH_MAX];
    const char *base;
    if (split_path(path, dir, sizeof dir, &base) == 0) {
        f->fd = open(dir, O_TMPFILE | O_RDWR | O_CLOEXEC, 0600);
        if (f->fd >= 0)
            return 0;
    }
#endif
    return create_named_temp(f, path, "spool", err);
}

/* A path in the directory for scratch files of device outputs ($TMPDIR, or /tmp). */
static int scratch_dir_path(char *out, size_t cap)
{
    const char *dir = getenv("TMPDIR");
    if (!dir || !*dir)
        dir = "/tmp";
    int n = snprintf(out, cap, "%s/vtpipe", dir);
    return n < 0 || (size_t)n >= cap ? -1 : 0;
}

/* The replacement of an existing regular file gets its permission bits (rwx, not set-user-ID,
 * set-group-ID or sticky: they would carry over to new content), and as root its owner and
 * group (best effort: a file system that refuses keeps the new file's). */
static void keep_attributes(int fd, const struct vt_output_target *t)
{
    if (t->kind != VT_OUTPUT_REGULAR)
        return;
    if (geteuid() == 0 && fchown(fd, t->uid, t->gid) != 0) {
        /* best effort, see above */
    }
    if (fchmod(fd, t->mode & 0777) != 0) {
        /* best effort, see above */
    }
}

/* A device, FIFO or socket: open it for writing; stream into it or spool for it. "-" is a copy
 * of file descriptor 1 (closed at commit; standard output itself stays open). */
static int open_special(struct vt_atomic_file *f, unsigned flags, struct vts_error *err)
{
    int fd = vt_output_path_is_stdio(f->target_path)
                 ? fcntl(STDOUT_FILENO, F_DUPFD_CLOEXEC, 0)
                 : open(f->target_path, O_WRONLY | O_CLOEXEC | O_NOCTTY);
    if (fd < 0)
        return vt_error_set(err, VTS_ERR_IO, "cannot open '%s' for writing: %s", shown(f),
                            strerror(errno));
    if (flags & VT_ATOMIC_FILE_SEQUENTIAL) {
        f->mode = VT_ATOMIC_FILE_STREAM;
        f->fd = fd;
        return 0;
    }
    char spool[VT_PATH_MAX];
    int rc = scratch_dir_path(spool, sizeof spool)
                 ? vt_error_set(err, VTS_ERR_ARG, "TMPDIR is too long")
                 : create_unnamed_temp(f, spool, err);
    if (rc != 0) {
        close(fd);
        return rc;
    }
    /* A named fallback scratch file is removed at once: it is only read back through fd. */
    if (f->temp_path[0]) {
        unlink(f->temp_path);
        temp_unregister(f->temp_path);
        f->temp_path[0] = '\0';
    }
    f->mode = VT_ATOMIC_FILE_SPOOL;
    f->device_fd = fd;
    return 0;
}

int vt_atomic_file_create(struct vt_atomic_file *f, const char *final_path, const char *tag,
                          unsigned flags, struct vts_error *err)
{
    reset(f);
    struct vt_output_target t;
    int rc = resolve(f, final_path, &t, err);
    if (rc != 0)
        return rc;
    if (t.kind == VT_OUTPUT_SPECIAL)
        return open_special(f, flags, err);
    rc = create_named_temp(f, f->target_path, tag, err);
    if (rc == 0)
        keep_attributes(f->fd, &t);
    return rc;
}

int vt_atomic_file_create_scratch(struct vt_atomic_file *f, const char *final_path,
                                  struct vts_error *err)
{
    reset(f);
    struct vt_output_target t;
    int rc = resolve(f, final_path, &t, err);
    if (rc != 0)
        return rc;
    char path[VT_PATH_MAX];
    if (t.kind == VT_OUTPUT_SPECIAL) {
        if (scratch_dir_path(path, sizeof path))
            return vt_error_set(err, VTS_ERR_ARG, "TMPDIR is too long");
    } else {
        memcpy(path, f->target_path, strlen(f->target_path) + 1);
    }
    return create_unnamed_temp(f, path, err);
}

int vt_atomic_file_create_tmp(struct vt_atomic_file *f, const char *name, struct vts_error *err)
{
    reset(f);
    char path[VT_PATH_MAX];
    size_t len = strlen(name);
    if (len >= sizeof f->final_path)
        return vt_error_set(err, VTS_ERR_ARG, "name '%s' is too long", name);
    memcpy(f->final_path, name, len + 1);
    if (scratch_dir_path(path, sizeof path))
        return vt_error_set(err, VTS_ERR_ARG, "TMPDIR is too long");
    return create_unnamed_temp(f, path, err);
}

/* write() of the whole buffer to a stream, retrying short writes and EINTR. */
static int write_all(int fd, const void *buf, size_t len, const char *name, struct vts_error *err)
{
    const unsigned char *p = buf;
    while (len > 0) {
        ssize_t n = write(fd, p, len);
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0)
            return vt_error_set(err, VTS_ERR_IO, "cannot write '%s': %s", name,
                                n < 0 ? strerror(errno) : "no space written");
        p += n;
        len -= (size_t)n;
    }
    return 0;
}

int vt_atomic_file_pwrite(struct vt_atomic_file *f, const void *buf, size_t len,
                          unsigned long long off, struct vts_error *err)
{
    if (f->mode == VT_ATOMIC_FILE_STREAM) {
        if (off != f->stream_end)
            return vt_error_set(err, VTS_ERR_IO,
                                "cannot write '%s' at byte %llu after byte %llu: it is not a "
                                "regular file",
                                shown(f), off, f->stream_end);
        int rc = write_all(f->fd, buf, len, shown(f), err);
        if (rc == 0)
            f->stream_end += len;
        return rc;
    }
    const unsigned char *p = buf;
    while (len > 0) {
        ssize_t n = pwrite(f->fd, p, len, (off_t)off);
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0)
            return vt_error_set(err, VTS_ERR_IO, "cannot write '%s': %s", shown(f),
                                n < 0 ? strerror(errno) : "no space written");
        p += n;
        len -= (size_t)n;
        off += (unsigned long long)n;
    }
    return 0;
}

static void sync_directory_of(const char *path)
{
    char dir[VT_PATH_MAX];
    const char *base;
    if (split_path(path, dir, sizeof dir, &base))
        return;
    int dfd = open(dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (dfd >= 0) {
        fsync(dfd); /* best effort: some file systems refuse fsync on directories */
        close(dfd);
    }
}

/* VT_ATOMIC_FILE_SPOOL: copies the scratch file, start to end, into the device. */
static int copy_spool(struct vt_atomic_file *f, struct vts_error *err)
{
    enum { CHUNK = 1 << 16 };
    unsigned char *buf = malloc(CHUNK);
    if (!buf)
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory writing '%s'", shown(f));
    int rc = 0;
    for (off_t off = 0; rc == 0;) {
        ssize_t n = pread(f->fd, buf, CHUNK, off);
        if (n < 0 && errno == EINTR)
            continue;
        if (n < 0)
            rc = vt_error_set(err, VTS_ERR_IO, "cannot read back the spool of '%s': %s", shown(f),
                              strerror(errno));
        if (n <= 0)
            break;
        rc = write_all(f->device_fd, buf, (size_t)n, shown(f), err);
        off += n;
    }
    free(buf);
    return rc;
}

/* Commit of a device or FIFO output: nothing to rename, nothing to flush (fsync does not apply). */
static int commit_special(struct vt_atomic_file *f, struct vts_error *err)
{
    int rc = f->mode == VT_ATOMIC_FILE_SPOOL ? copy_spool(f, err) : 0;
    int out_fd = f->mode == VT_ATOMIC_FILE_SPOOL ? f->device_fd : f->fd;
    if (close(out_fd) != 0 && rc == 0)
        rc = vt_error_set(err, VTS_ERR_IO, "cannot close '%s': %s", shown(f), strerror(errno));
    if (f->mode == VT_ATOMIC_FILE_SPOOL)
        close(f->fd);
    f->fd = f->device_fd = -1;
    return rc;
}

int vt_atomic_file_commit(struct vt_atomic_file *f, struct vts_error *err)
{
    if (f->fd >= 0 && f->mode != VT_ATOMIC_FILE_RENAME)
        return commit_special(f, err);
    if (f->fd < 0 || f->temp_path[0] == '\0')
        return vt_error_set(err, VTS_ERR_ARG, "'%s' is not open for writing", f->final_path);
    int rc = 0;
    if (fsync(f->fd) != 0)
        rc = vt_error_set(err, VTS_ERR_IO, "cannot flush '%s': %s", f->final_path, strerror(errno));
    if (close(f->fd) != 0 && rc == 0)
        rc = vt_error_set(err, VTS_ERR_IO, "cannot close '%s': %s", f->final_path, strerror(errno));
    f->fd = -1;
    if (rc == 0 && rename(f->temp_path, f->target_path) != 0)
        rc = vt_error_set(err, VTS_ERR_IO, "cannot rename onto '%s': %s", f->final_path,
                          strerror(errno));
    /* Unlinked before it is unregistered: a signal in between still finds and removes it. */
    if (rc != 0)
        unlink(f->temp_path);
    temp_unregister(f->temp_path);
    f->temp_path[0] = '\0';
    if (rc != 0)
        return rc;
    sync_directory_of(f->target_path);
    return 0;
}

void vt_atomic_file_abort(struct vt_atomic_file *f)
{
    if (!f)
        return;
    if (f->fd >= 0)
        close(f->fd);
    if (f->mode == VT_ATOMIC_FILE_SPOOL && f->device_fd >= 0)
        close(f->device_fd);
    f->fd = -1;
    f->device_fd = -1;
    if (f->temp_path[0]) {
        unlink(f->temp_path);
        temp_unregister(f->temp_path);
    }
    f->temp_path[0] = '\0';
}
