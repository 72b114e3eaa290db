#define _GNU_SOURCE /* O_TMPFILE */
#include "vt_atomic_file.h"
#include "vt_error.h"

#include <errno.h>
#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
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

int vt_atomic_file_create(struct vt_atomic_file *f, const char *final_path, const char *tag,
                          struct vts_error *err)
{
    f->fd = -1;
    f->temp_path[0] = '\0';
    char dir[VT_PATH_MAX];
    const char *base;
    size_t len = strlen(final_path);
    if (len == 0 || len >= sizeof f->final_path || split_path(final_path, dir, sizeof dir, &base) ||
        *base == '\0')
        return vt_error_set(err, VTS_ERR_ARG, "invalid output path '%s'", final_path);
    memcpy(f->final_path, final_path, len + 1);

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
        int n = strcmp(dir, ".") == 0 && !strchr(final_path, '/')
                    ? snprintf(f->temp_path, sizeof f->temp_path, ".%s.%s-%s", base, tag, suffix)
                    : snprintf(f->temp_path, sizeof f->temp_path, "%s/.%s.%s-%s",
                               strcmp(dir, "/") == 0 ? "" : dir, base, tag, suffix);
        if (n < 0 || (size_t)n >= sizeof f->temp_path)
            return vt_error_set(err, VTS_ERR_ARG, "output path '%s' is too long", final_path);
        f->fd = open(f->temp_path, O_RDWR | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (f->fd >= 0) {
            temp_register(f->temp_path);
            return 0;
        }
        if (errno != EEXIST)
            break;
    }
    int e = errno;
    f->temp_path[0] = '\0';
    return vt_error_set(err, VTS_ERR_IO, "cannot create a file next to '%s': %s", final_path,
                        strerror(e));
}

int vt_atomic_file_create_scratch(struct vt_atomic_file *f, const char *final_path,
                                  struct vts_error *err)
{
    char dir[VT_PATH_MAX];
    const char *base;
    size_t len = strlen(final_path);
    f->fd = -1;
    f->temp_path[0] = '\0';
    if (len == 0 || len >= sizeof f->final_path || split_path(final_path, dir, sizeof dir, &base))
        return vt_error_set(err, VTS_ERR_ARG, "invalid output path '%s'", final_path);
    memcpy(f->final_path, final_path, len + 1);
#ifdef O_TMPFILE
    f->fd = open(dir, O_TMPFILE | O_RDWR | O_CLOEXEC, 0600);
    if (f->fd >= 0)
        return 0;
#endif
    return vt_atomic_file_create(f, final_path, "spool", err);
}

int vt_atomic_file_pwrite(struct vt_atomic_file *f, const void *buf, size_t len,
                          unsigned long long off, struct vts_error *err)
{
    const unsigned char *p = buf;
    while (len > 0) {
        ssize_t n = pwrite(f->fd, p, len, (off_t)off);
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0)
            return vt_error_set(err, VTS_ERR_IO, "cannot write '%s': %s", f->final_path,
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

int vt_atomic_file_commit(struct vt_atomic_file *f, struct vts_error *err)
{
    if (f->fd < 0 || f->temp_path[0] == '\0')
        return vt_error_set(err, VTS_ERR_ARG, "'%s' is not open for writing", f->final_path);
    int rc = 0;
    if (fsync(f->fd) != 0)
        rc = vt_error_set(err, VTS_ERR_IO, "cannot flush '%s': %s", f->final_path, strerror(errno));
    if (close(f->fd) != 0 && rc == 0)
        rc = vt_error_set(err, VTS_ERR_IO, "cannot close '%s': %s", f->final_path, strerror(errno));
    f->fd = -1;
    if (rc == 0 && rename(f->temp_path, f->final_path) != 0)
        rc = vt_error_set(err, VTS_ERR_IO, "cannot rename onto '%s': %s", f->final_path,
                          strerror(errno));
    /* Unlinked before it is unregistered: a signal in between still finds and removes it. */
    if (rc != 0)
        unlink(f->temp_path);
    temp_unregister(f->temp_path);
    f->temp_path[0] = '\0';
    if (rc != 0)
        return rc;
    sync_directory_of(f->final_path);
    return 0;
}

void vt_atomic_file_abort(struct vt_atomic_file *f)
{
    if (!f)
        return;
    if (f->fd >= 0)
        close(f->fd);
    f->fd = -1;
    if (f->temp_path[0]) {
        unlink(f->temp_path);
        temp_unregister(f->temp_path);
    }
    f->temp_path[0] = '\0';
}
