/* The folders and files of an export: built in a staging folder next to the final one and moved
 * there whole at the end (an atomic exchange where the file system has one), so that a failed or
 * killed run never leaves a half-made export under the final name. */
#define _GNU_SOURCE /* renameat2, nftw */
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <ftw.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "internal/vt_export_impl.h"

static int remove_entry(const char *path, const struct stat *st, int type, struct FTW *ftw)
{
    (void)st;
    (void)type;
    (void)ftw;
    remove(path);
    return 0;
}

/* Removes path and everything under it, symbolic links not followed. */
static void remove_tree(const char *path)
{
    nftw(path, remove_entry, 16, FTW_DEPTH | FTW_PHYS);
}

static bool dir_is_empty(const char *path)
{
    DIR *dir = opendir(path);
    struct dirent *e;
    bool empty = dir != NULL;
    while (empty && (e = readdir(dir)))
        empty = strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0;
    if (dir)
        closedir(dir);
    return empty;
}

/* True when the file at keep lies inside the folder dir (both resolved). */
static bool contains(const char *dir, const char *keep)
{
    char d[PATH_MAX], k[PATH_MAX];
    if (!keep || !realpath(dir, d) || !realpath(keep, k))
        return false;
    size_t n = strlen(d);
    return strncmp(d, k, n) == 0 && (k[n] == '/' || d[n - 1] == '/');
}

int vt_export_dir_create(struct vt_export_dir *d, const char *final_path, bool force,
                         const char *keep, struct vts_error *err)
{
    struct stat st;
    *d = (struct vt_export_dir){0};
    if ((size_t)snprintf(d->final_path, sizeof d->final_path, "%s", final_path) >=
            sizeof d->final_path - 16 ||
        !final_path[0])
        return vt_error_set(err, VTS_ERR_ARG, "'%s': output folder name too long", final_path);
    while (strlen(d->final_path) > 1 && d->final_path[strlen(d->final_path) - 1] == '/')
        d->final_path[strlen(d->final_path) - 1] = 0;
    if (stat(d->final_path, &st) == 0) {
        if (!S_ISDIR(st.st_mode))
            return vt_error_set(err, VTS_ERR_ARG, "'%s': exists and is not a folder", final_path);
        if (contains(d->final_path, keep))
            return vt_error_set(err, VTS_ERR_ARG, "'%s': holds the input '%s'; not replacing it",
                                final_path, keep);
        if (!force && !dir_is_empty(d->final_path))
            return vt_error_set(err, VTS_ERR_ARG,
                                "'%s': exists and is not empty (--force replaces it)", final_path);
    }
    snprintf(d->tmp_path, sizeof d->tmp_path, "%s.tmp-XXXXXX", d->final_path);
    if (!mkdtemp(d->tmp_path)) {
        int e = errno;
        d->tmp_path[0] = 0;
        return vt_error_set(err, VTS_ERR_IO, "cannot create a folder next to '%s': %s", final_path,
                            strerror(e));
    }
    mode_t mask = umask(0);
    umask(mask);
    chmod(d->tmp_path, 0777 & ~mask);
    return 0;
}

int vt_export_dir_commit(struct vt_export_dir *d, struct vts_error *err)
{
    struct stat st;
    if (stat(d->final_path, &st) != 0) {
        if (rename(d->tmp_path, d->final_path) != 0)
            return vt_error_set(err, VTS_ERR_IO, "cannot rename '%s' to '%s': %s", d->tmp_path,
                                d->final_path, strerror(errno));
        d->tmp_path[0] = 0;
        return 0;
    }
    /* The old folder moves to the staging name in the same step, then goes. */
    if (renameat2(AT_FDCWD, d->tmp_path, AT_FDCWD, d->final_path, RENAME_EXCHANGE) != 0) {
        char old[sizeof d->final_path + 16];
        snprintf(old, sizeof old, "%s.old-XXXXXX", d->final_path);
        if (!mkdtemp(old) || rename(d->final_path, old) != 0)
            return vt_error_set(err, VTS_ERR_IO, "cannot replace '%s': %s", d->final_path,
                                strerror(errno));
        if (rename(d->tmp_path, d->final_path) != 0) {
            int e = errno;
            rename(old, d->final_path);
            return vt_error_set(err, VTS_ERR_IO, "cannot rename '%s' to '%s': %s", d->tmp_path,
                                d->final_path, strerror(e));
        }
        remove_tree(old);
    } else {
        remove_tree(d->tmp_path);
    }
    d->tmp_path[0] = 0;
    return 0;
}

void vt_export_dir_abort(struct vt_export_dir *d)
{
    if (d && d->tmp_path[0])
        remove_tree(d->tmp_path);
    if (d)
        d->tmp_path[0] = 0;
}

/* Creates the folders of dir/rel up to its last component. */
static int make_parents(const char *dir, const char *rel, struct vts_error *err)
{
    char path[4608];
    int n = snprintf(path, sizeof path, "%s/%s", dir, rel);
    if (n < 0 || (size_t)n >= sizeof path)
        return vt_error_set(err, VTS_ERR_ARG, "'%s/%s': path too long", dir, rel);
    for (char *s = path + strlen(dir) + 1; (s = strchr(s, '/')); s++) {
        *s = 0;
        if (mkdir(path, 0777) != 0 && errno != EEXIST)
            return vt_error_set(err, VTS_ERR_IO, "cannot create folder '%s': %s", path,
                                strerror(errno));
        *s = '/';
    }
    return 0;
}

int vt_export_write_file(const char *dir, const char *rel, const void *bytes, size_t len,
                         struct vts_error *err)
{
    char path[4608];
    snprintf(path, sizeof path, "%s/%s", dir, rel);
    int rc = make_parents(dir, rel, err);
    if (rc != 0)
        return rc;
    int fd = open(path, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0)
        return vt_error_set(err, VTS_ERR_IO, "cannot create '%s': %s", path, strerror(errno));
    const unsigned char *p = bytes;
    while (len > 0) {
        ssize_t w = write(fd, p, len);
        if (w < 0 && errno == EINTR)
            continue;
        if (w <= 0) {
            int e = w < 0 ? errno : ENOSPC;
            close(fd);
            return vt_error_set(err, VTS_ERR_IO, "cannot write '%s': %s", path, strerror(e));
        }
        p += w;
        len -= (size_t)w;
    }
    if (close(fd) != 0)
        return vt_error_set(err, VTS_ERR_IO, "cannot write '%s': %s", path, strerror(errno));
    return 0;
}
