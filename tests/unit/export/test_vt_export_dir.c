/* formats/export's staging folder: nothing under the final name before the commit, an existing
 * folder replaced whole (with force), a non-empty one or one holding the input refused, an abort
 * leaving nothing. */
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "internal/vt_export_impl.h"
#include "vt_test.h"

static char base[256];

static bool exists(const char *dir, const char *rel)
{
    char p[512];
    struct stat st;
    snprintf(p, sizeof p, "%s/%s", dir, rel);
    return stat(p, &st) == 0;
}

static int entries(const char *dir)
{
    DIR *d = opendir(dir);
    struct dirent *e;
    int n = 0;
    while (d && (e = readdir(d)))
        n += e->d_name[0] != '.';
    if (d)
        closedir(d);
    return n;
}

static void a_commit_moves_the_whole_folder(void)
{
    struct vt_export_dir d;
    struct vts_error err = {0};
    char out[300];
    snprintf(out, sizeof out, "%s/new", base);
    VT_CHECK_INT_EQ(vt_export_dir_create(&d, out, false, NULL, &err), 0);
    VT_CHECK_INT_EQ(vt_export_write_file(d.tmp_path, "a/b/c.txt", "hi", 2, &err), 0);
    VT_CHECK(!exists(out, "a/b/c.txt"));
    VT_CHECK(access(out, F_OK) != 0);
    VT_CHECK_INT_EQ(vt_export_write_file(d.tmp_path, "a/b/c.txt", "x", 1, &err), VTS_ERR_IO);
    VT_CHECK_STR_CONTAINS(err.message, "cannot create");
    VT_CHECK_INT_EQ(vt_export_dir_commit(&d, &err), 0);
    VT_CHECK(exists(out, "a/b/c.txt"));
    VT_CHECK_INT_EQ(entries(base), 1); /* no staging folder left */
}

static void force_replaces_and_refusals_keep(void)
{
    struct vt_export_dir d;
    struct vts_error err = {0};
    char out[300], store[320];
    snprintf(out, sizeof out, "%s/new", base);
    VT_CHECK_INT_EQ(vt_export_dir_create(&d, out, false, NULL, &err), VTS_ERR_ARG);
    VT_CHECK_STR_CONTAINS(err.message, "exists and is not empty (--force replaces it)");
    snprintf(store, sizeof store, "%s/a/b/c.txt", out);
    VT_CHECK_INT_EQ(vt_export_dir_create(&d, out, true, store, &err), VTS_ERR_ARG);
    VT_CHECK_STR_CONTAINS(err.message, "holds the input");
    VT_CHECK(exists(out, "a/b/c.txt"));
    VT_CHECK_INT_EQ(vt_export_dir_create(&d, out, true, NULL, &err), 0);
    VT_CHECK_INT_EQ(vt_export_write_file(d.tmp_path, "d.txt", "d", 1, &err), 0);
    VT_CHECK_INT_EQ(vt_export_dir_commit(&d, &err), 0);
    VT_CHECK(exists(out, "d.txt"));
    VT_CHECK(!exists(out, "a"));
    VT_CHECK_INT_EQ(entries(base), 1); /* the old folder went */
}

static void an_abort_leaves_nothing(void)
{
    struct vt_export_dir d;
    struct vts_error err = {0};
    char out[300];
    snprintf(out, sizeof out, "%s/aborted", base);
    VT_CHECK_INT_EQ(vt_export_dir_create(&d, out, false, NULL, &err), 0);
    VT_CHECK_INT_EQ(vt_export_write_file(d.tmp_path, "x/y.png", "y", 1, &err), 0);
    vt_export_dir_abort(&d);
    VT_CHECK(access(out, F_OK) != 0);
    VT_CHECK_INT_EQ(entries(base), 1);
    vt_export_dir_abort(&d); /* twice is harmless */
}

static void a_file_is_not_a_folder(void)
{
    struct vt_export_dir d;
    struct vts_error err = {0};
    char out[300];
    snprintf(out, sizeof out, "%s/new/d.txt", base);
    VT_CHECK_INT_EQ(vt_export_dir_create(&d, out, true, NULL, &err), VTS_ERR_ARG);
    VT_CHECK_STR_CONTAINS(err.message, "exists and is not a folder");
}

int main(void)
{
    snprintf(base, sizeof base, "%s/vt-export-dir-XXXXXX",
             getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp");
    if (!mkdtemp(base))
        return 2;
    VT_RUN(a_commit_moves_the_whole_folder);
    VT_RUN(force_replaces_and_refusals_keep);
    VT_RUN(an_abort_leaves_nothing);
    VT_RUN(a_file_is_not_a_folder);
    char cmd[300];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", base);
    if (system(cmd) != 0)
        return 2;
    return vt_test_main_result();
}
