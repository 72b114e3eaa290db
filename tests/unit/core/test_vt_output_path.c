/* lib/core/vt_output_path and what vt_atomic_file does with it: an output that is the same file
 * as an input (by name, hard link or symbolic link) or a directory is refused; a symbolic link is
 * written through (the link stays, its target is replaced); a FIFO and a character device are
 * written into, never renamed over (streamed, or spooled for a seeking writer); a replaced file
 * keeps its permission bits, owner and group; once asked for, "-" is standard output (written into
 * whatever file descriptor 1 is, never a file named "-") and, as an input, standard input. */
#define _GNU_SOURCE /* makedev */
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include "file_fixture.h"
#include "vt_atomic_file.h"
#include "vt_error.h"
#include "vt_output_path.h"
#include "vt_test.h"

static mode_t lmode(const char *path)
{
    struct stat st;
    return lstat(path, &st) == 0 ? st.st_mode : 0;
}

/* Writes text into path through vt_atomic_file (flags) and commits; the status of the first
 * failing step. */
static int write_through(const char *path, unsigned flags, const char *text)
{
    struct vt_atomic_file f;
    struct vts_error err = {0};
    int rc = vt_atomic_file_create(&f, path, "tmp", flags, &err);
    if (rc == 0)
        rc = vt_atomic_file_pwrite(&f, text, strlen(text), 0, &err);
    if (rc == 0)
        rc = vt_atomic_file_commit(&f, &err);
    vt_atomic_file_abort(&f);
    return rc;
}

static void the_same_file_as_an_input_is_refused(void)
{
    char dir[512], in[600], hard[600], soft[600], other[600], fresh[600];
    fresh_dir(dir, sizeof dir, "same");
    join(in, sizeof in, dir, "photo.png");
    join(hard, sizeof hard, dir, "hard.png");
    join(soft, sizeof soft, dir, "soft.png");
    join(other, sizeof other, dir, "other.png");
    join(fresh, sizeof fresh, dir, "fresh.vts");
    write_file(in, "input");
    write_file(other, "other");
    VT_CHECK(link(in, hard) == 0);
    VT_CHECK(symlink("photo.png", soft) == 0);
    struct vts_error err = {0};
    const char *inputs[] = {other, NULL, in};
    VT_CHECK_INT_EQ(vt_output_path_check(in, inputs, 3, &err), VTS_ERR_ARG);
    VT_CHECK_STR_CONTAINS(err.message, "is the input");
    VT_CHECK_STR_CONTAINS(err.message, "(the same file)");
    VT_CHECK_STR_CONTAINS(err.message, in);
    VT_CHECK_INT_EQ(vt_output_path_check(hard, inputs, 3, &err), VTS_ERR_ARG); /* a hard link */
    VT_CHECK_STR_CONTAINS(err.message, hard);
    VT_CHECK_INT_EQ(vt_output_path_check(soft, inputs, 3, &err), VTS_ERR_ARG); /* a symlink */
    const char *via_link[] = {soft};
    VT_CHECK_INT_EQ(vt_output_path_check(in, via_link, 1, &err), VTS_ERR_ARG); /* input linked */
    /* other outputs pass: the check does not refuse everything */
    const char *only_in[] = {in};
    VT_CHECK_INT_EQ(vt_output_path_check(other, only_in, 1, &err), 0);
    VT_CHECK_INT_EQ(vt_output_path_check(fresh, only_in, 1, &err), 0);
    VT_CHECK_INT_EQ(vt_output_path_check(in, NULL, 0, &err), 0);
    const char *missing[] = {fresh};
    VT_CHECK_INT_EQ(vt_output_path_check(in, missing, 1, &err), 0);
    /* two outputs not there yet, one a link to the other: one name once resolved */
    char to_fresh[600], elsewhere[600];
    join(to_fresh, sizeof to_fresh, dir, "to_fresh.mtl");
    join(elsewhere, sizeof elsewhere, dir, "elsewhere.mtl");
    VT_CHECK(symlink("fresh.vts", to_fresh) == 0);
    VT_CHECK_INT_EQ(vt_output_path_check(to_fresh, missing, 1, &err), VTS_ERR_ARG);
    VT_CHECK_INT_EQ(vt_output_path_check(fresh, missing, 1, &err), VTS_ERR_ARG);
    VT_CHECK_INT_EQ(vt_output_path_check(elsewhere, missing, 1, &err), 0);
    VT_CHECK(holds(in, "input"));
}

static void a_directory_is_refused(void)
{
    char dir[512], sub[600], link_to_sub[600];
    fresh_dir(dir, sizeof dir, "directory");
    join(sub, sizeof sub, dir, "out");
    join(link_to_sub, sizeof link_to_sub, dir, "link");
    VT_CHECK(mkdir(sub, 0755) == 0);
    VT_CHECK(symlink("out", link_to_sub) == 0);
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(vt_output_path_check(sub, NULL, 0, &err), VTS_ERR_ARG);
    VT_CHECK_STR_CONTAINS(err.message, "is a directory");
    VT_CHECK_INT_EQ(vt_output_path_check(link_to_sub, NULL, 0, &err), VTS_ERR_ARG);
    struct vt_atomic_file f;
    VT_CHECK_INT_EQ(vt_atomic_file_create(&f, sub, "tmp", 0, &err), VTS_ERR_ARG);
    VT_CHECK_STR_CONTAINS(err.message, "is a directory");
    VT_CHECK_INT_EQ(vt_atomic_file_create_scratch(&f, link_to_sub, &err), VTS_ERR_ARG);
    VT_CHECK_INT_EQ(count_entries(sub, NULL, 0), 0);
    VT_CHECK(S_ISDIR(lmode(sub)));
}

static void a_symbolic_link_is_written_through(void)
{
    char dir[512], sub[600], target[700], link1[600], link2[600], dangling[600], made[700];
    fresh_dir(dir, sizeof dir, "symlink");
    join(sub, sizeof sub, dir, "sub");
    VT_CHECK(mkdir(sub, 0755) == 0);
    join(target, sizeof target, sub, "store.vts");
    join(link1, sizeof link1, dir, "link1.vts");
    join(link2, sizeof link2, dir, "link2.vts");
    write_file(target, "old");
    VT_CHECK(symlink("sub/store.vts", link1) == 0);
    VT_CHECK(symlink(link1, link2) == 0); /* a chain: absolute, then relative */
    struct vt_atomic_file f;
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(vt_atomic_file_create(&f, link2, "tmp", 0, &err), 0);
    VT_CHECK_STR_EQ(f.target_path, target);
    VT_CHECK_INT_EQ(count_entries(sub, NULL, 0), 2); /* the temporary is next to the target */
    VT_CHECK_INT_EQ(vt_atomic_file_pwrite(&f, "new", 3, 0, &err), 0);
    VT_CHECK_INT_EQ(vt_atomic_file_commit(&f, &err), 0);
    VT_CHECK(S_ISLNK(lmode(link1)) && S_ISLNK(lmode(link2)));
    VT_CHECK(S_ISREG(lmode(target)));
    VT_CHECK(holds(target, "new"));
    VT_CHECK(holds(link2, "new"));
    VT_CHECK_INT_EQ(count_entries(sub, NULL, 0), 1);
    VT_CHECK_INT_EQ(count_entries(dir, NULL, 0), 3);
    /* a dangling link: its target is created */
    join(dangling, sizeof dangling, dir, "dangling.vts");
    join(made, sizeof made, sub, "made.vts");
    VT_CHECK(symlink("sub/made.vts", dangling) == 0);
    VT_CHECK_INT_EQ(write_through(dangling, VT_ATOMIC_FILE_SEQUENTIAL, "made"), 0);
    VT_CHECK(S_ISLNK(lmode(dangling)));
    VT_CHECK(holds(made, "made"));
    /* a loop of links is an error, not a hang */
    char loop[600];
    join(loop, sizeof loop, dir, "loop");
    VT_CHECK(symlink("loop", loop) == 0);
    VT_CHECK_INT_EQ(vt_atomic_file_create(&f, loop, "tmp", 0, &err), VTS_ERR_ARG);
    VT_CHECK_STR_CONTAINS(err.message, "symbolic links");
}

/* Reads what is in the FIFO's read end now (the writer has closed it). */
static void read_fifo(int fd, char *buf, size_t cap)
{
    size_t n = 0;
    for (;;) {
        ssize_t got = read(fd, buf + n, cap - 1 - n);
        if (got <= 0)
            break;
        n += (size_t)got;
    }
    buf[n] = '\0';
}

static void a_fifo_is_written_into_not_replaced(void)
{
    char dir[512], fifo[600], buf[256];
    fresh_dir(dir, sizeof dir, "fifo");
    join(fifo, sizeof fifo, dir, "out.vts");
    VT_CHECK(mkfifo(fifo, 0644) == 0);
    /* streamed: the reader is there first, so opening for writing does not wait */
    int rd = open(fifo, O_RDONLY | O_NONBLOCK);
    VT_CHECK(rd >= 0);
    VT_CHECK_INT_EQ(write_through(fifo, VT_ATOMIC_FILE_SEQUENTIAL, "streamed"), 0);
    read_fifo(rd, buf, sizeof buf);
    VT_CHECK_STR_EQ(buf, "streamed");
    /* a stream cannot go back */
    struct vt_atomic_file f;
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(vt_atomic_file_create(&f, fifo, "tmp", VT_ATOMIC_FILE_SEQUENTIAL, &err), 0);
    VT_CHECK_INT_EQ(vt_atomic_file_pwrite(&f, "ab", 2, 0, &err), 0);
    VT_CHECK_INT_EQ(vt_atomic_file_pwrite(&f, "cd", 2, 0, &err), VTS_ERR_IO);
    VT_CHECK_STR_CONTAINS(err.message, "not a regular file");
    vt_atomic_file_abort(&f);
    read_fifo(rd, buf, sizeof buf);
    VT_CHECK_STR_EQ(buf, "ab");
    /* spooled: writes out of order arrive in file order at commit */
    VT_CHECK_INT_EQ(vt_atomic_file_create(&f, fifo, "tmp", 0, &err), 0);
    VT_CHECK_INT_EQ(f.mode, VT_ATOMIC_FILE_SPOOL);
    VT_CHECK_INT_EQ(vt_atomic_file_pwrite(&f, "world", 5, 5, &err), 0);
    VT_CHECK_INT_EQ(vt_atomic_file_pwrite(&f, "hello", 5, 0, &err), 0);
    read_fifo(rd, buf, sizeof buf);
    VT_CHECK_STR_EQ(buf, ""); /* nothing before the commit */
    VT_CHECK_INT_EQ(vt_atomic_file_commit(&f, &err), 0);
    read_fifo(rd, buf, sizeof buf);
    VT_CHECK_STR_EQ(buf, "helloworld");
    close(rd);
    VT_CHECK(S_ISFIFO(lmode(fifo)));
    VT_CHECK_INT_EQ(count_entries(dir, NULL, 0), 1); /* no temporary, no spool left */
}

static void a_character_device_is_written_into_not_replaced(void)
{
    char dir[512], dev[600];
    fresh_dir(dir, sizeof dir, "device");
    join(dev, sizeof dev, dir, "null");
    if (mknod(dev, S_IFCHR | 0666, makedev(1, 3)) != 0) {
        fprintf(stderr, "skip: mknod: %s (needs root)\n", strerror(errno));
        return;
    }
    VT_CHECK_INT_EQ(write_through(dev, VT_ATOMIC_FILE_SEQUENTIAL, "streamed"), 0);
    VT_CHECK_INT_EQ(write_through(dev, 0, "spooled"), 0);
    struct vt_atomic_file f;
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(vt_atomic_file_create_scratch(&f, dev, &err), 0); /* not next to it */
    VT_CHECK_INT_EQ(count_entries(dir, NULL, 0), 1);
    vt_atomic_file_abort(&f);
    struct stat st;
    VT_CHECK(lstat(dev, &st) == 0 && S_ISCHR(st.st_mode) && st.st_rdev == makedev(1, 3));
    VT_CHECK_INT_EQ(count_entries(dir, NULL, 0), 1);
}

static void a_replaced_file_keeps_its_mode_owner_and_group(void)
{
    char dir[512], path[600], fresh[600];
    fresh_dir(dir, sizeof dir, "mode");
    join(path, sizeof path, dir, "secret.vts");
    join(fresh, sizeof fresh, dir, "fresh.vts");
    write_file(path, "old");
    VT_CHECK(chmod(path, 0600) == 0);
    bool root = geteuid() == 0;
    if (root)
        VT_CHECK(chown(path, 1234, 5678) == 0);
    VT_CHECK_INT_EQ(write_through(path, 0, "new"), 0);
    VT_CHECK_INT_EQ(write_through(fresh, 0, "new"), 0);
    struct stat st, st_fresh;
    VT_CHECK(stat(path, &st) == 0 && stat(fresh, &st_fresh) == 0);
    VT_CHECK(holds(path, "new"));
    VT_CHECK_INT_EQ(st.st_mode & 07777, 0600);
    VT_CHECK_INT_EQ(st_fresh.st_mode & 07777, 0644); /* umask 022: a new file would differ */
    if (root) {
        VT_CHECK_INT_EQ(st.st_uid, 1234);
        VT_CHECK_INT_EQ(st.st_gid, 5678);
        VT_CHECK_INT_EQ(st_fresh.st_uid, 0);
    }
}

static void scratch_files_go_next_to_the_target_or_to_tmpdir(void)
{
    char dir[512], sub[600], link_path[600], fifo[600], got[VT_PATH_MAX];
    fresh_dir(dir, sizeof dir, "scratch_dir");
    join(sub, sizeof sub, dir, "sub");
    join(link_path, sizeof link_path, dir, "link.vts");
    join(fifo, sizeof fifo, dir, "fifo.vts");
    VT_CHECK(mkdir(sub, 0755) == 0);
    VT_CHECK(symlink("sub/out.vts", link_path) == 0);
    VT_CHECK(mkfifo(fifo, 0644) == 0);
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(vt_output_path_scratch_dir("out.vts", got, sizeof got, &err), 0);
    VT_CHECK_STR_EQ(got, ".");
    VT_CHECK_INT_EQ(vt_output_path_scratch_dir("/out.vts", got, sizeof got, &err), 0);
    VT_CHECK_STR_EQ(got, "/");
    VT_CHECK_INT_EQ(vt_output_path_scratch_dir("a/b/out.vts", got, sizeof got, &err), 0);
    VT_CHECK_STR_EQ(got, "a/b");
    VT_CHECK_INT_EQ(vt_output_path_scratch_dir(link_path, got, sizeof got, &err), 0);
    VT_CHECK_STR_EQ(got, sub); /* the link's target's directory */
    setenv("TMPDIR", sub, 1);
    VT_CHECK_INT_EQ(vt_output_path_scratch_dir(fifo, got, sizeof got, &err), 0);
    VT_CHECK_STR_EQ(got, sub); /* a FIFO: $TMPDIR */
    unsetenv("TMPDIR");
    VT_CHECK_INT_EQ(vt_output_path_scratch_dir(fifo, got, sizeof got, &err), 0);
    VT_CHECK_STR_EQ(got, "/tmp");
    VT_CHECK_INT_EQ(vt_output_path_scratch_dir("a/b/out.vts", got, 3, &err), VTS_ERR_ARG);
}

/* Points file descriptor fd at path (opened with flags), returning a copy of the old one. */
static int redirect(int fd, const char *path, int flags)
{
    fflush(stdout);
    int saved = dup(fd);
    int to = open(path, flags, 0644);
    VT_CHECK(saved >= 0 && to >= 0 && dup2(to, fd) == fd);
    close(to);
    return saved;
}

static void restore(int fd, int saved)
{
    fflush(stdout);
    VT_CHECK(dup2(saved, fd) == fd);
    close(saved);
}

static void dash_is_a_file_name_until_asked(void)
{
    char dir[512], cwd[VT_PATH_MAX];
    fresh_dir(dir, sizeof dir, "dash_name");
    VT_CHECK(getcwd(cwd, sizeof cwd) != NULL);
    VT_CHECK(chdir(dir) == 0);
    VT_CHECK(!vt_output_path_is_stdio("-"));
    VT_CHECK_INT_EQ(write_through("-", 0, "a file"), 0); /* what a library user gets */
    VT_CHECK(holds("-", "a file"));
    VT_CHECK(chdir(cwd) == 0);
    vt_output_path_use_stdio(); /* from now on, as in the tools */
    VT_CHECK(vt_output_path_is_stdio("-") && !vt_output_path_is_stdio("./-") &&
             !vt_output_path_is_stdio(NULL));
}

static void dash_is_standard_output_written_into(void)
{
    char dir[512], out[600], cwd[VT_PATH_MAX];
    fresh_dir(dir, sizeof dir, "dash");
    join(out, sizeof out, dir, "stdout.txt");
    write_file(out, "before;");
    struct stat before, after;
    VT_CHECK(stat(out, &before) == 0);
    VT_CHECK(getcwd(cwd, sizeof cwd) != NULL);
    VT_CHECK(chdir(dir) == 0);
    setenv("TMPDIR", dir, 1);
    int saved = redirect(STDOUT_FILENO, out, O_WRONLY | O_APPEND);
    struct vt_output_target t;
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(vt_output_path_resolve("-", &t, &err), 0);
    VT_CHECK_INT_EQ(t.kind, VT_OUTPUT_SPECIAL); /* a regular file behind it: still written into */
    VT_CHECK_STR_EQ(t.path, "-");
    VT_CHECK(t.dev == before.st_dev && t.ino == before.st_ino);
    /* streamed at the file's offset (appended here), then spooled out of order */
    VT_CHECK_INT_EQ(write_through("-", VT_ATOMIC_FILE_SEQUENTIAL, "streamed;"), 0);
    struct vt_atomic_file f;
    VT_CHECK_INT_EQ(vt_atomic_file_create(&f, "-", "tmp", 0, &err), 0);
    VT_CHECK_INT_EQ(f.mode, VT_ATOMIC_FILE_SPOOL);
    VT_CHECK_INT_EQ(vt_atomic_file_pwrite(&f, "world", 5, 5, &err), 0);
    VT_CHECK_INT_EQ(vt_atomic_file_pwrite(&f, "hello", 5, 0, &err), 0);
    VT_CHECK_INT_EQ(vt_atomic_file_commit(&f, &err), 0);
    VT_CHECK(write(STDOUT_FILENO, ";still open", 11) == 11); /* fd 1 itself is not closed */
    /* the output "-" against the file standard output is */
    const char *inputs[] = {out};
    VT_CHECK_INT_EQ(vt_output_path_check("-", inputs, 1, &err), VTS_ERR_ARG);
    VT_CHECK_STR_CONTAINS(err.message, "output '<stdout>' is the input");
    restore(STDOUT_FILENO, saved);
    VT_CHECK(holds(out, "before;streamed;helloworld;still open"));
    VT_CHECK(stat(out, &after) == 0 && after.st_ino == before.st_ino); /* not replaced */
    VT_CHECK_INT_EQ(count_entries(dir, NULL, 0), 1); /* no file named "-", no spool left */
    VT_CHECK(chdir(cwd) == 0);
    unsetenv("TMPDIR");
}

static void dash_is_standard_input_for_the_check(void)
{
    char dir[512], in[600], other[600];
    fresh_dir(dir, sizeof dir, "dash_in");
    join(in, sizeof in, dir, "in.png");
    join(other, sizeof other, dir, "other.vts");
    write_file(in, "image");
    const char *inputs[] = {"-"};
    struct vts_error err = {0};
    int saved = redirect(STDIN_FILENO, in, O_RDONLY);
    VT_CHECK_INT_EQ(vt_output_path_check(in, inputs, 1, &err), VTS_ERR_ARG); /* tool - -o X <X */
    VT_CHECK_STR_CONTAINS(err.message, "output '");
    VT_CHECK_STR_CONTAINS(err.message, "is the input '<stdin>' (the same file)");
    VT_CHECK_INT_EQ(vt_output_path_check(other, inputs, 1, &err), 0);
    restore(STDIN_FILENO, saved);
    int fds[2]; /* a pipe is read, never destroyed: not compared */
    VT_CHECK(pipe(fds) == 0);
    saved = dup(STDIN_FILENO);
    VT_CHECK(dup2(fds[0], STDIN_FILENO) == STDIN_FILENO);
    VT_CHECK_INT_EQ(vt_output_path_check(in, inputs, 1, &err), 0);
    restore(STDIN_FILENO, saved);
    close(fds[0]);
    close(fds[1]);
}

static void dash_scratch_files_go_to_tmpdir(void)
{
    char dir[512], got[VT_PATH_MAX], missing[600];
    fresh_dir(dir, sizeof dir, "dash_tmp");
    join(missing, sizeof missing, dir, "missing");
    struct vts_error err = {0};
    setenv("TMPDIR", dir, 1);
    VT_CHECK_INT_EQ(vt_output_path_scratch_dir("-", got, sizeof got, &err), 0);
    VT_CHECK_STR_EQ(got, dir);
    struct vt_atomic_file f;
    VT_CHECK_INT_EQ(vt_atomic_file_create_tmp(&f, "<stdin>", &err), 0);
    VT_CHECK_INT_EQ(vt_atomic_file_pwrite(&f, "abc", 3, 0, &err), 0);
    VT_CHECK_INT_EQ(count_entries(dir, NULL, 0), f.temp_path[0] ? 1 : 0); /* unnamed if it can */
    vt_atomic_file_abort(&f);
    VT_CHECK_INT_EQ(count_entries(dir, NULL, 0), 0);
    setenv("TMPDIR", missing, 1);
    VT_CHECK_INT_EQ(vt_atomic_file_create_tmp(&f, "<stdin>", &err), VTS_ERR_IO);
    VT_CHECK_STR_CONTAINS(err.message, "for '<stdin>' in '");
    VT_CHECK_STR_CONTAINS(err.message, "missing");
    unsetenv("TMPDIR");
    /* standard output closed: named in the message (in dir: a wrong "-" would be a file there) */
    char cwd[VT_PATH_MAX];
    VT_CHECK(getcwd(cwd, sizeof cwd) != NULL && chdir(dir) == 0);
    fflush(stdout);
    int saved = dup(STDOUT_FILENO);
    close(STDOUT_FILENO);
    int rc = vt_atomic_file_create(&f, "-", "tmp", VT_ATOMIC_FILE_SEQUENTIAL, &err);
    vt_atomic_file_abort(&f); /* a no-op unless it wrongly made a file (fd 1 then) */
    VT_CHECK(dup2(saved, STDOUT_FILENO) == STDOUT_FILENO); /* before any check prints */
    close(saved);
    VT_CHECK(chdir(cwd) == 0);
    VT_CHECK_INT_EQ(rc, VTS_ERR_IO);
    VT_CHECK_STR_CONTAINS(err.message, "cannot open '<stdout>' for writing");
    VT_CHECK_INT_EQ(count_entries(dir, NULL, 0), 0);
}

int main(void)
{
    umask(022);
    snprintf(tmpdir, sizeof tmpdir, "%s/test_vt_output_path.XXXXXX",
             getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp");
    if (!mkdtemp(tmpdir))
        return 1;
    VT_RUN(the_same_file_as_an_input_is_refused);
    VT_RUN(a_directory_is_refused);
    VT_RUN(a_symbolic_link_is_written_through);
    VT_RUN(a_fifo_is_written_into_not_replaced);
    VT_RUN(a_character_device_is_written_into_not_replaced);
    VT_RUN(a_replaced_file_keeps_its_mode_owner_and_group);
    VT_RUN(scratch_files_go_next_to_the_target_or_to_tmpdir);
    VT_RUN(dash_is_a_file_name_until_asked);
    VT_RUN(dash_is_standard_output_written_into);
    VT_RUN(dash_is_standard_input_for_the_check);
    VT_RUN(dash_scratch_files_go_to_tmpdir);
    remove_tree(tmpdir);
    return vt_test_main_result();
}
