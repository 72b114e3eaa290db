/* An LD_PRELOAD library that makes reads of one input file fail with EIO, as a failing disk
 * would (tests/robust/tool_eio.sh, docs/robustness.md "Read errors").
 *
 * Environment:
 *   VT_EIO_PATH   a substring of the path (as /proc/self/fd/N names it: absolute, links
 *                 followed) of the files whose reads fail; unset or empty: the shim does nothing
 *   VT_EIO_AFTER  N >= 0: the first N read calls on matching files succeed, every later one
 *                 fails (-1, EIO; stdio calls return their failure value with the stream's error
 *                 flag set and errno EIO). Unset or negative: count only.
 *   VT_EIO_TIMES  K > 0: only K calls fail (calls N+1..N+K), later ones succeed again: a transient
 *                 fault. Unset: every call after the first N fails (a dead disk).
 *   VT_EIO_FUNCS  a comma-separated list of the function names that count and fail (e.g.
 *                 "read,pread"); unset: all of them (for the self-test showing that stdio
 *                 bypasses read())
 *   VT_EIO_LOG    a file the shim appends to: "fail FUNC PATH after N" at the first injected
 *                 fault, and "calls C failed F mmaps M" at exit. Unset: in counting mode the exit
 *                 line goes to stderr; when failing, nothing is printed (the tool's stderr is
 *                 what the test checks).
 *
 * Which calls: read, readv, pread, pread64, preadv, preadv64 (libtiff, OpenEXRCore, the store
 * reader) and the stdio reading functions. glibc's stdio does not go through the exported read():
 * fread, getline, getc... refill their buffer with libc-internal calls (__read_nocancel inside
 * _IO_file_read) that no interposition sees, so interposing read() alone never fails an fread()
 * (checked: tool_eio.sh --self-test). The stdio functions are therefore interposed themselves:
 * each call on a matching stream counts as one read, whether or not it would have reached the
 * file. mmap() of a matching file is only counted: a fault in a mapping is a SIGBUS, not a
 * status, and the test requires the count to be 0 (libtiff is opened with "m" for no mmap).
 * The dynamic loader reads libraries with its own internal calls: never affected.
 *
 * The shim is built without sanitizers; in the ASan build the executable's interceptors come
 * first in the lookup order and call the shim through dlsym(RTLD_NEXT), which calls libc's. */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <errno.h>
#include <fcntl.h>
#include <stdarg.h>
#include <stdatomic.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/types.h>
#include <sys/uio.h>
#include <unistd.h>

/* glibc's other names of functions it exports (no prototype in the headers). */
int _IO_getc(FILE *stream);
ssize_t __getdelim(char **line, size_t *cap, int delim, FILE *stream);

static const char *pattern;
static const char *funcs;
static long long fail_after = -1;
static long long fail_times = -1; /* -1: no end */
static int log_fd = -1;
static atomic_llong calls, failed, mmaps;
static atomic_int init_state; /* 0 not yet, 1 in progress, 2 done */

static void init(void)
{
    int expected = 0;
    if (!atomic_compare_exchange_strong(&init_state, &expected, 1)) {
        while (atomic_load(&init_state) != 2) {
            /* another thread is reading the environment: a few instructions */
        }
        return;
    }
    const char *p = getenv("VT_EIO_PATH");
    pattern = p && *p ? p : NULL;
    const char *f = getenv("VT_EIO_FUNCS");
    funcs = f && *f ? f : NULL;
    const char *a = getenv("VT_EIO_AFTER");
    fail_after = a && *a ? strtoll(a, NULL, 10) : -1;
    const char *k = getenv("VT_EIO_TIMES");
    fail_times = k && *k ? strtoll(k, NULL, 10) : -1;
    const char *l = getenv("VT_EIO_LOG");
    if (pattern && l && *l)
        log_fd = open(l, O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
    atomic_store(&init_state, 2);
}

__attribute__((constructor)) static void shim_start(void)
{
    init();
}

__attribute__((format(printf, 2, 3))) static void log_line(int fd, const char *fmt, ...)
{
    char buf[4200];
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    if (n < 0)
        return;
    if ((size_t)n >= sizeof buf)
        n = (int)sizeof buf - 1;
    if (write(fd, buf, (size_t)n) < 0) {
        /* nowhere to report it */
    }
}

__attribute__((destructor)) static void shim_end(void)
{
    if (!pattern)
        return;
    int fd = log_fd >= 0 ? log_fd : fail_after < 0 ? 2 : -1;
    if (fd >= 0)
        log_line(fd, "eio_shim: calls %lld failed %lld mmaps %lld\n", atomic_load(&calls),
                 atomic_load(&failed), atomic_load(&mmaps));
}

/* The path of fd, or "" when it has none. */
static bool fd_path(int fd, char *path, size_t cap)
{
    char link[64];
    snprintf(link, sizeof link, "/proc/self/fd/%d", fd);
    ssize_t n = readlink(link, path, cap - 1);
    if (n < 0)
        return false;
    path[n] = '\0';
    return true;
}

/* true when fn is one of VT_EIO_FUNCS (or that is unset). */
static bool selected(const char *fn)
{
    if (!funcs)
        return true;
    size_t n = strlen(fn);
    for (const char *p = funcs; (p = strstr(p, fn)) != NULL; p += n)
        if ((p == funcs || p[-1] == ',') && (p[n] == ',' || p[n] == '\0'))
            return true;
    return false;
}

/* true when this call on fd must fail (errno is then EIO); counts the calls on matching files. */
static bool inject(int fd, const char *fn)
{
    if (atomic_load(&init_state) != 2)
        init();
    if (!pattern || fd < 0 || !selected(fn))
        return false;
    char path[4096];
    if (!fd_path(fd, path, sizeof path) || !strstr(path, pattern))
        return false;
    long long earlier = atomic_fetch_add(&calls, 1);
    if (fail_after < 0 || earlier < fail_after ||
        (fail_times >= 0 && earlier >= fail_after + fail_times))
        return false;
    if (atomic_fetch_add(&failed, 1) == 0 && log_fd >= 0)
        log_line(log_fd, "eio_shim: fail %s %s after %lld\n", fn, path, earlier);
    errno = EIO;
    return true;
}

static void count_mmap(int fd)
{
    if (atomic_load(&init_state) != 2)
        init();
    char path[4096];
    if (pattern && fd >= 0 && fd_path(fd, path, sizeof path) && strstr(path, pattern))
        atomic_fetch_add(&mmaps, 1);
}

/* The next definition of a symbol (libc's, or the one after us). */
static void *next(const char *name)
{
    void *f = dlsym(RTLD_NEXT, name);
    if (!f) {
        log_line(2, "eio_shim: no next %s\n", name);
        abort();
    }
    return f;
}
#define REAL(name)                                                                                 \
    static __typeof__(&name) real_##name;                                                          \
    if (!real_##name)                                                                              \
    real_##name = (__typeof__(&name))next(#name)

/* A stdio failure: the stream's error flag, as glibc sets it when its read fails. */
static void stream_error(FILE *stream)
{
    stream->_flags |= _IO_ERR_SEEN;
}

ssize_t read(int fd, void *buf, size_t len)
{
    REAL(read);
    return inject(fd, "read") ? -1 : real_read(fd, buf, len);
}

ssize_t readv(int fd, const struct iovec *iov, int count)
{
    REAL(readv);
    return inject(fd, "readv") ? -1 : real_readv(fd, iov, count);
}

ssize_t pread(int fd, void *buf, size_t len, off_t off)
{
    REAL(pread);
    return inject(fd, "pread") ? -1 : real_pread(fd, buf, len, off);
}

ssize_t pread64(int fd, void *buf, size_t len, off64_t off)
{
    REAL(pread64);
    return inject(fd, "pread64") ? -1 : real_pread64(fd, buf, len, off);
}

ssize_t preadv(int fd, const struct iovec *iov, int count, off_t off)
{
    REAL(preadv);
    return inject(fd, "preadv") ? -1 : real_preadv(fd, iov, count, off);
}

ssize_t preadv64(int fd, const struct iovec *iov, int count, off64_t off)
{
    REAL(preadv64);
    return inject(fd, "preadv64") ? -1 : real_preadv64(fd, iov, count, off);
}

void *mmap(void *addr, size_t len, int prot, int flags, int fd, off_t off)
{
    REAL(mmap);
    if (!(flags & MAP_ANONYMOUS))
        count_mmap(fd);
    return real_mmap(addr, len, prot, flags, fd, off);
}

void *mmap64(void *addr, size_t len, int prot, int flags, int fd, off64_t off)
{
    REAL(mmap64);
    if (!(flags & MAP_ANONYMOUS))
        count_mmap(fd);
    return real_mmap64(addr, len, prot, flags, fd, off);
}

size_t fread(void *ptr, size_t size, size_t n, FILE *stream)
{
    REAL(fread);
    if (inject(fileno(stream), "fread")) {
        stream_error(stream);
        return 0;
    }
    return real_fread(ptr, size, n, stream);
}

#undef fread_unlocked /* a macro of bits/stdio.h when optimising */
size_t fread_unlocked(void *ptr, size_t size, size_t n, FILE *stream)
{
    REAL(fread_unlocked);
    if (inject(fileno(stream), "fread_unlocked")) {
        stream_error(stream);
        return 0;
    }
    return real_fread_unlocked(ptr, size, n, stream);
}

/* One definition per name of the one-character readers. */
#define GETC_LIKE(name)                                                                            \
    int name(FILE *stream)                                                                         \
    {                                                                                              \
        REAL(name);                                                                                \
        if (inject(fileno(stream), #name)) {                                                       \
            stream_error(stream);                                                                  \
            return EOF;                                                                            \
        }                                                                                          \
        return real_##name(stream);                                                                \
    }
GETC_LIKE(fgetc)
GETC_LIKE(getc)
GETC_LIKE(_IO_getc)

char *fgets(char *s, int size, FILE *stream)
{
    REAL(fgets);
    if (inject(fileno(stream), "fgets")) {
        stream_error(stream);
        return NULL;
    }
    return real_fgets(s, size, stream);
}

ssize_t getdelim(char **line, size_t *cap, int delim, FILE *stream)
{
    REAL(getdelim);
    if (inject(fileno(stream), "getdelim")) {
        stream_error(stream);
        return -1;
    }
    return real_getdelim(line, cap, delim, stream);
}

ssize_t __getdelim(char **line, size_t *cap, int delim, FILE *stream)
{
    REAL(__getdelim);
    if (inject(fileno(stream), "__getdelim")) {
        stream_error(stream);
        return -1;
    }
    return real___getdelim(line, cap, delim, stream);
}

ssize_t getline(char **line, size_t *cap, FILE *stream)
{
    REAL(getline);
    if (inject(fileno(stream), "getline")) {
        stream_error(stream);
        return -1;
    }
    return real_getline(line, cap, stream);
}
