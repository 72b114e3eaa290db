/* lib/core/vt_atomic_file: nothing under the final name before commit, commit replaces an old
 * file by a rename, abort and failures leave neither the final file nor a temporary, the
 * temporary lives in the destination directory, errors name the file (an unwritable directory, a
 * full disk as RLIMIT_FSIZE makes it), scratch files have no name, and the signal cleanup removes
 * the temporaries of a process killed by SIGTERM, SIGINT or SIGHUP. */
#define _GNU_SOURCE /* O_TMPFILE, for the check that scratch files have no name */
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "file_fixture.h"
#include "vt_atomic_file.h"
#include "vt_error.h"
#include "vt_test.h"

static bool exists(const char *path)
{
    struct stat st;
    return lstat(path, &st) == 0;
}

static int put(struct vt_atomic_file *f, const char *text, struct vts_error *err)
{
    return vt_atomic_file_pwrite(f, text, strlen(text), 0, err);
}

static void the_checks_catch_wrong_values(void)
{
    char dir[512], path[600];
    fresh_dir(dir, sizeof dir, "checks");
    join(path, sizeof path, dir, "a.txt");
    write_file(path, "abc");
    VT_CHECK(holds(path, "abc"));
    VT_CHECK(!holds(path, "abd"));  /* other content */
    VT_CHECK(!holds(path, "abcd")); /* a prefix is not the whole */
    VT_CHECK(!holds(path, "ab"));
    VT_CHECK_INT_EQ(count_entries(dir, NULL, 0), 1);
    VT_CHECK(exists(path));
    unlink(path);
    VT_CHECK(!exists(path));
    VT_CHECK_INT_EQ(count_entries(dir, NULL, 0), 0);
}

static void nothing_appears_under_the_final_name_before_commit(void)
{
    char dir[512], path[600], list[1024];
    fresh_dir(dir, sizeof dir, "before_commit");
    join(path, sizeof path, dir, "out.vts");
    struct vt_atomic_file f;
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(vt_atomic_file_create(&f, path, "tmp", 0, &err), 0);
    VT_CHECK(!exists(path));
    VT_CHECK_INT_EQ(put(&f, "complete content", &err), 0);
    VT_CHECK(!exists(path));
    /* the only entry is the hidden temporary, in the destination directory */
    VT_CHECK_INT_EQ(count_entries(dir, list, sizeof list), 1);
    VT_CHECK(strncmp(list, ".out.vts.tmp-", 13) == 0);
    char expected_prefix[700];
    snprintf(expected_prefix, sizeof expected_prefix, "%s/.out.vts.tmp-", dir);
    VT_CHECK(strncmp(f.temp_path, expected_prefix, strlen(expected_prefix)) == 0);
    VT_CHECK(holds(f.temp_path, "complete content"));
    VT_CHECK_INT_EQ(vt_atomic_file_commit(&f, &err), 0);
    VT_CHECK(holds(path, "complete content"));
    VT_CHECK_INT_EQ(count_entries(dir, list, sizeof list), 1); /* the final file only */
    VT_CHECK(strcmp(list, "out.vts") == 0);
    VT_CHECK_INT_EQ(f.fd, -1);
    vt_atomic_file_abort(&f); /* after a commit: nothing to do, the output stays */
    VT_CHECK(holds(path, "complete content"));
}

static void a_name_without_a_directory_puts_the_temporary_in_the_working_directory(void)
{
    char dir[512], cwd[PATH_MAX], list[1024];
    fresh_dir(dir, sizeof dir, "no_slash");
    VT_CHECK(getcwd(cwd, sizeof cwd) != NULL);
    VT_CHECK(chdir(dir) == 0);
    struct vt_atomic_file f;
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(vt_atomic_file_create(&f, "plain.json", "tmp", 0, &err), 0);
    VT_CHECK(strncmp(f.temp_path, ".plain.json.tmp-", 16) == 0);
    VT_CHECK_INT_EQ(put(&f, "{}", &err), 0);
    VT_CHECK_INT_EQ(vt_atomic_file_commit(&f, &err), 0);
    VT_CHECK(chdir(cwd) == 0);
    VT_CHECK_INT_EQ(count_entries(dir, list, sizeof list), 1);
    VT_CHECK(strcmp(list, "plain.json") == 0);
}

static void commit_replaces_an_old_file_by_a_rename(void)
{
    char dir[512], path[600];
    fresh_dir(dir, sizeof dir, "replace");
    join(path, sizeof path, dir, "out.vts");
    write_file(path, "old");
    struct stat before;
    VT_CHECK(stat(path, &before) == 0);
    int reader = open(path, O_RDONLY); /* a reader holding the old file */
    VT_CHECK(reader >= 0);
    struct vt_atomic_file f;
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(vt_atomic_file_create(&f, path, "tmp", 0, &err), 0);
    VT_CHECK_INT_EQ(put(&f, "brand new", &err), 0);
    VT_CHECK(holds(path, "old")); /* untouched until the commit */
    VT_CHECK_INT_EQ(vt_atomic_file_commit(&f, &err), 0);
    VT_CHECK(holds(path, "brand new"));
    struct stat after;
    VT_CHECK(stat(path, &after) == 0);
    VT_CHECK(after.st_ino != before.st_ino); /* a new file, not the old one rewritten */
    char buf[16] = {0};
    VT_CHECK(pread(reader, buf, sizeof buf - 1, 0) == 3 && strcmp(buf, "old") == 0);
    close(reader);
    VT_CHECK_INT_EQ(count_entries(dir, NULL, 0), 1);
}

static void writes_land_at_their_offsets(void)
{
    char dir[512], path[600];
    fresh_dir(dir, sizeof dir, "offsets");
    join(path, sizeof path, dir, "o.bin");
    struct vt_atomic_file f;
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(vt_atomic_file_create(&f, path, "tmp", 0, &err), 0);
    VT_CHECK_INT_EQ(vt_atomic_file_pwrite(&f, "tail", 4, 6, &err), 0);
    VT_CHECK_INT_EQ(vt_atomic_file_pwrite(&f, "head", 4, 0, &err), 0);
    VT_CHECK_INT_EQ(vt_atomic_file_pwrite(&f, "", 0, 100, &err), 0); /* nothing: no growth */
    VT_CHECK_INT_EQ(vt_atomic_file_commit(&f, &err), 0);
    char buf[16];
    FILE *in = fopen(path, "rb");
    size_t n = in ? fread(buf, 1, sizeof buf, in) : 0;
    if (in)
        fclose(in);
    VT_CHECK_INT_EQ(n, 10);
    VT_CHECK(memcmp(buf, "head\0\0tail", 10) == 0);
}

static void abort_leaves_neither_the_final_file_nor_a_temporary(void)
{
    char dir[512], path[600], old_path[600];
    fresh_dir(dir, sizeof dir, "abort");
    join(path, sizeof path, dir, "new.vts");
    struct vt_atomic_file f;
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(vt_atomic_file_create(&f, path, "tmp", 0, &err), 0);
    VT_CHECK_INT_EQ(put(&f, "half", &err), 0);
    vt_atomic_file_abort(&f);
    VT_CHECK(!exists(path));
    VT_CHECK_INT_EQ(count_entries(dir, NULL, 0), 0);
    VT_CHECK_INT_EQ(f.fd, -1);
    vt_atomic_file_abort(&f); /* twice: a no-op */
    vt_atomic_file_abort(NULL);
    VT_CHECK_INT_EQ(count_entries(dir, NULL, 0), 0);
    /* an old file under the name stays as it was */
    join(old_path, sizeof old_path, dir, "kept.vts");
    write_file(old_path, "old");
    VT_CHECK_INT_EQ(vt_atomic_file_create(&f, old_path, "tmp", 0, &err), 0);
    VT_CHECK_INT_EQ(put(&f, "new", &err), 0);
    vt_atomic_file_abort(&f);
    VT_CHECK(holds(old_path, "old"));
    VT_CHECK_INT_EQ(count_entries(dir, NULL, 0), 1);
    /* committing an aborted file is refused and creates nothing */
    VT_CHECK_INT_EQ(vt_atomic_file_commit(&f, &err), VTS_ERR_ARG);
    VT_CHECK_STR_CONTAINS(err.message, "kept.vts");
    VT_CHECK_INT_EQ(count_entries(dir, NULL, 0), 1);
}

static void a_failed_commit_removes_the_temporary_and_keeps_the_old_name(void)
{
    /* rename() of a file onto a non-empty directory fails: the commit must clean up. (A
     * directory there at create is refused; this one appears while the file is written.) */
    char dir[512], path[600], inner[700];
    fresh_dir(dir, sizeof dir, "failed_commit");
    join(path, sizeof path, dir, "busy");
    struct vt_atomic_file f;
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(vt_atomic_file_create(&f, path, "tmp", 0, &err), 0);
    VT_CHECK_INT_EQ(put(&f, "data", &err), 0);
    VT_CHECK(mkdir(path, 0755) == 0);
    join(inner, sizeof inner, path, "inside");
    write_file(inner, "x");
    VT_CHECK_INT_EQ(vt_atomic_file_commit(&f, &err), VTS_ERR_IO);
    VT_CHECK_STR_CONTAINS(err.message, "cannot rename onto");
    VT_CHECK_STR_CONTAINS(err.message, path);
    VT_CHECK_INT_EQ(count_entries(dir, NULL, 0), 1); /* the directory only: no temporary */
    VT_CHECK(holds(inner, "x"));
    vt_atomic_file_abort(&f); /* after a failed commit: nothing left to do */
    VT_CHECK_INT_EQ(count_entries(dir, NULL, 0), 1);
}

static void invalid_paths_are_refused(void)
{
    char dir[512], path[600];
    fresh_dir(dir, sizeof dir, "invalid");
    struct vt_atomic_file f;
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(vt_atomic_file_create(&f, "", "tmp", 0, &err), VTS_ERR_ARG);
    VT_CHECK_INT_EQ(f.fd, -1);
    snprintf(path, sizeof path, "%s/", dir); /* a directory, no file name */
    VT_CHECK_INT_EQ(vt_atomic_file_create(&f, path, "tmp", 0, &err), VTS_ERR_ARG);
    VT_CHECK_STR_CONTAINS(err.message, "is a directory");
    snprintf(path, sizeof path, "%s/none/", dir); /* no file name, nothing there */
    VT_CHECK_INT_EQ(vt_atomic_file_create(&f, path, "tmp", 0, &err), VTS_ERR_ARG);
    VT_CHECK_STR_CONTAINS(err.message, "invalid output path");
    char *long_path = malloc(VT_PATH_MAX + 10);
    memset(long_path, 'a', VT_PATH_MAX + 9);
    long_path[VT_PATH_MAX + 9] = '\0';
    VT_CHECK_INT_EQ(vt_atomic_file_create(&f, long_path, "tmp", 0, &err), VTS_ERR_ARG);
    VT_CHECK_INT_EQ(vt_atomic_file_create_scratch(&f, long_path, &err), VTS_ERR_ARG);
    free(long_path);
    VT_CHECK_INT_EQ(count_entries(dir, NULL, 0), 0);
}

static void a_missing_directory_gives_an_error_naming_the_file(void)
{
    char path[600];
    snprintf(path, sizeof path, "%s/no/such/dir/out.vts", tmpdir);
    struct vt_atomic_file f;
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(vt_atomic_file_create(&f, path, "tmp", 0, &err), VTS_ERR_IO);
    VT_CHECK_STR_CONTAINS(err.message, path);
    VT_CHECK_STR_CONTAINS(err.message, strerror(ENOENT));
    VT_CHECK_INT_EQ(f.fd, -1);
    VT_CHECK_INT_EQ(f.temp_path[0], '\0');
    vt_atomic_file_abort(&f); /* safe after a failed create */
}

/* In a child (so that dropping root or changing limits does not affect the test): the status of
 * vt_atomic_file_create in a read-only directory, its message written to fd. */
static void unwritable_directory_child(const char *dir, const char *path, int fd)
{
    if (geteuid() == 0) { /* root writes anywhere: become nobody, for whom dir is read-only */
        if (setgid(65534) != 0 || setuid(65534) != 0)
            _exit(90);
    } else if (chmod(dir, 0555) != 0) {
        _exit(91);
    }
    struct vt_atomic_file f;
    struct vts_error err = {0};
    int rc = vt_atomic_file_create(&f, path, "tmp", 0, &err);
    if (write(fd, err.message, strlen(err.message)) < 0)
        _exit(92);
    if (rc == 0)
        vt_atomic_file_abort(&f);
    _exit(rc == VTS_ERR_IO ? 0 : 93);
}

static void an_unwritable_directory_gives_a_clear_error_naming_the_file(void)
{
    char dir[512], path[600], msg[1024] = {0};
    fresh_dir(dir, sizeof dir, "read_only");
    VT_CHECK(chmod(dir, 0755) == 0);
    join(path, sizeof path, dir, "out.vts");
    int p[2];
    VT_CHECK(pipe(p) == 0);
    fflush(NULL);
    pid_t pid = fork();
    if (pid == 0) {
        close(p[0]);
        unwritable_directory_child(dir, path, p[1]);
    }
    close(p[1]);
    size_t n = 0;
    ssize_t got;
    while (n + 1 < sizeof msg && (got = read(p[0], msg + n, sizeof msg - 1 - n)) > 0)
        n += (size_t)got;
    close(p[0]);
    int status = 0;
    VT_CHECK(waitpid(pid, &status, 0) == pid);
    VT_CHECK(WIFEXITED(status) && WEXITSTATUS(status) == 0);
    VT_CHECK_STR_CONTAINS(msg, "cannot create a file next to");
    VT_CHECK_STR_CONTAINS(msg, path);
    VT_CHECK_STR_CONTAINS(msg, strerror(EACCES));
    chmod(dir, 0755);
    VT_CHECK_INT_EQ(count_entries(dir, NULL, 0), 0);
}

/* A child under RLIMIT_FSIZE (SIGXFSZ ignored: writes past the limit fail with EFBIG, as a full
 * disk fails with ENOSPC). Exit 0 when every expectation held; the messages go to fd. */
static void file_size_limit_child(const char *path, int fd)
{
    signal(SIGXFSZ, SIG_IGN);
    struct rlimit rl = {64 * 1024, 64 * 1024};
    if (setrlimit(RLIMIT_FSIZE, &rl) != 0)
        _exit(80);
    static char block[100 * 1024];
    memset(block, 'v', sizeof block);
    struct vt_atomic_file f;
    struct vts_error err = {0};
    if (vt_atomic_file_create(&f, path, "tmp", 0, &err) != 0)
        _exit(81);
    if (vt_atomic_file_pwrite(&f, block, 32 * 1024, 0, &err) != 0) /* below the limit */
        _exit(82);
    int rc = vt_atomic_file_pwrite(&f, block, sizeof block, 32 * 1024, &err); /* past it */
    if (write(fd, err.message, strlen(err.message)) < 0)
        _exit(83);
    vt_atomic_file_abort(&f);
    _exit(rc == VTS_ERR_IO ? 0 : 84);
}

static void a_write_past_the_file_size_limit_fails_cleanly(void)
{
    char dir[512], path[600], msg[1024] = {0};
    fresh_dir(dir, sizeof dir, "fsize");
    join(path, sizeof path, dir, "big.vts");
    write_file(path, "old");
    int p[2];
    VT_CHECK(pipe(p) == 0);
    fflush(NULL);
    pid_t pid = fork();
    if (pid == 0) {
        close(p[0]);
        file_size_limit_child(path, p[1]);
    }
    close(p[1]);
    size_t n = 0;
    ssize_t got;
    while (n + 1 < sizeof msg && (got = read(p[0], msg + n, sizeof msg - 1 - n)) > 0)
        n += (size_t)got;
    close(p[0]);
    int status = 0;
    VT_CHECK(waitpid(pid, &status, 0) == pid);
    VT_CHECK(WIFEXITED(status) && WEXITSTATUS(status) == 0); /* not killed by SIGXFSZ */
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
        fprintf(stderr, "  child status %d\n", status);
    VT_CHECK_STR_CONTAINS(msg, "cannot write");
    VT_CHECK_STR_CONTAINS(msg, path);
    VT_CHECK_STR_CONTAINS(msg, strerror(EFBIG));
    VT_CHECK(holds(path, "old"));
    VT_CHECK_INT_EQ(count_entries(dir, NULL, 0), 1);
}

static void two_writers_of_one_name_get_their_own_temporaries(void)
{
    char dir[512], path[600];
    fresh_dir(dir, sizeof dir, "two_writers");
    join(path, sizeof path, dir, "same.vts");
    struct vt_atomic_file a, b;
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(vt_atomic_file_create(&a, path, "tmp", 0, &err), 0);
    VT_CHECK_INT_EQ(vt_atomic_file_create(&b, path, "tmp", 0, &err), 0);
    VT_CHECK(strcmp(a.temp_path, b.temp_path) != 0);
    VT_CHECK_INT_EQ(count_entries(dir, NULL, 0), 2);
    VT_CHECK_INT_EQ(put(&a, "first", &err), 0);
    VT_CHECK_INT_EQ(put(&b, "second", &err), 0);
    VT_CHECK_INT_EQ(vt_atomic_file_commit(&a, &err), 0);
    VT_CHECK_INT_EQ(vt_atomic_file_commit(&b, &err), 0);
    VT_CHECK(holds(path, "second")); /* the last commit wins, whole */
    VT_CHECK_INT_EQ(count_entries(dir, NULL, 0), 1);
}

static void a_scratch_file_has_no_name(void)
{
    char dir[512], path[600];
    fresh_dir(dir, sizeof dir, "scratch");
    join(path, sizeof path, dir, "out.vts");
    struct vt_atomic_file f;
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(vt_atomic_file_create_scratch(&f, path, &err), 0);
    VT_CHECK(f.fd >= 0);
    VT_CHECK_INT_EQ(vt_atomic_file_pwrite(&f, "spooled", 7, 0, &err), 0);
    char buf[8] = {0};
    VT_CHECK(pread(f.fd, buf, 7, 0) == 7 && strcmp(buf, "spooled") == 0);
#ifdef O_TMPFILE
    int probe = open(dir, O_TMPFILE | O_RDWR, 0600);
    if (probe >= 0) { /* the file system has unnamed files: the scratch file is one */
        close(probe);
        VT_CHECK_INT_EQ(f.temp_path[0], '\0');
        VT_CHECK_INT_EQ(count_entries(dir, NULL, 0), 0);
        /* it cannot be committed */
        VT_CHECK_INT_EQ(vt_atomic_file_commit(&f, &err), VTS_ERR_ARG);
        VT_CHECK(!exists(path));
    }
#endif
    vt_atomic_file_abort(&f);
    VT_CHECK_INT_EQ(f.fd, -1);
    VT_CHECK_INT_EQ(count_entries(dir, NULL, 0), 0);
    VT_CHECK(!exists(path));
}

/* A child that creates a committed file and two open temporaries, reports "ready" on fd and
 * waits to be killed. With install false it skips vt_atomic_file_cleanup_on_signals(): the
 * temporaries must then stay, which shows that the check below would see them. */
static void signal_child(const char *dir, bool install, int fd)
{
    if (install)
        vt_atomic_file_cleanup_on_signals();
    char p1[600], p2[600], p3[600];
    join(p1, sizeof p1, dir, "done.txt");
    join(p2, sizeof p2, dir, "a.vts");
    join(p3, sizeof p3, dir, "b.json");
    struct vt_atomic_file done, a, b;
    struct vts_error err = {0};
    if (vt_atomic_file_create(&done, p1, "tmp", 0, &err) || put(&done, "done", &err) ||
        vt_atomic_file_commit(&done, &err) || vt_atomic_file_create(&a, p2, "tmp", 0, &err) ||
        put(&a, "half", &err) || vt_atomic_file_create(&b, p3, "tmp", 0, &err))
        _exit(70);
    if (write(fd, "r", 1) != 1)
        _exit(71);
    for (;;)
        pause();
}

/* Runs signal_child, waits for its "ready" (not for a time), sends sig, returns the wait
 * status; *left gets the number of entries in dir other than done.txt. */
static int kill_child_when_ready(const char *dir, bool install, int sig, int *left)
{
    int p[2];
    if (pipe(p) != 0)
        return -1;
    fflush(NULL);
    pid_t pid = fork();
    if (pid == 0) {
        close(p[0]);
        signal_child(dir, install, p[1]);
    }
    close(p[1]);
    char c = 0;
    ssize_t got;
    while ((got = read(p[0], &c, 1)) < 0 && errno == EINTR)
        ;
    close(p[0]);
    VT_CHECK(got == 1 && c == 'r');
    kill(pid, sig);
    int status = 0;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR)
        ;
    char list[1024];
    *left = count_entries(dir, list, sizeof list) - 1;
    char done[600];
    join(done, sizeof done, dir, "done.txt");
    VT_CHECK(holds(done, "done"));
    return status;
}

static void the_signal_cleanup_removes_temporaries_of_a_killed_process(void)
{
    static const int sigs[] = {SIGTERM, SIGINT, SIGHUP};
    for (size_t i = 0; i < sizeof sigs / sizeof sigs[0]; i++) {
        char dir[512], name[32];
        snprintf(name, sizeof name, "signal_%d", sigs[i]);
        fresh_dir(dir, sizeof dir, name);
        int left = -1;
        int status = kill_child_when_ready(dir, true, sigs[i], &left);
        VT_CHECK(WIFSIGNALED(status) && WTERMSIG(status) == sigs[i]); /* died of the signal */
        VT_CHECK_INT_EQ(left, 0);
    }
    /* without the handlers the same kill leaves both temporaries: the check has teeth */
    char dir[512];
    fresh_dir(dir, sizeof dir, "signal_no_handler");
    int left = -1;
    int status = kill_child_when_ready(dir, false, SIGTERM, &left);
    VT_CHECK(WIFSIGNALED(status) && WTERMSIG(status) == SIGTERM);
    VT_CHECK_INT_EQ(left, 2);
}

int main(void)
{
    snprintf(tmpdir, sizeof tmpdir, "%s/test_vt_atomic_file.XXXXXX",
             getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp");
    if (!mkdtemp(tmpdir))
        return 1;
    chmod(tmpdir, 0755); /* the unwritable-directory child (as nobody) must get inside */
    VT_RUN(the_checks_catch_wrong_values);
    VT_RUN(nothing_appears_under_the_final_name_before_commit);
    VT_RUN(a_name_without_a_directory_puts_the_temporary_in_the_working_directory);
    VT_RUN(commit_replaces_an_old_file_by_a_rename);
    VT_RUN(writes_land_at_their_offsets);
    VT_RUN(abort_leaves_neither_the_final_file_nor_a_temporary);
    VT_RUN(a_failed_commit_removes_the_temporary_and_keeps_the_old_name);
    VT_RUN(invalid_paths_are_refused);
    VT_RUN(a_missing_directory_gives_an_error_naming_the_file);
    VT_RUN(an_unwritable_directory_gives_a_clear_error_naming_the_file);
    VT_RUN(a_write_past_the_file_size_limit_fails_cleanly);
    VT_RUN(two_writers_of_one_name_get_their_own_temporaries);
    VT_RUN(a_scratch_file_has_no_name);
    VT_RUN(the_signal_cleanup_removes_temporaries_of_a_killed_process);
    remove_tree(tmpdir);
    return vt_test_main_result();
}
