/* The golden bad stores of tests/data/bad/: tiny files named for their defect, each listed in
 * MANIFEST as "file status message-substring". Each must give exactly that status and a one-line
 * message naming the file, opened from a path and from an exact-size memory copy (status "ok":
 * must open and read every tile). Every .vts file in the directory must be listed, so a kept fuzz
 * finding cannot be forgotten. Most files come from test_vts_corrupt --write-bad; fuzz findings
 * are added by hand. Usage: test_vts_bad_files [DIR] (default: the source tree's). */
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "robust/vts_fixture.h"
#include "vt_error.h"
#include "vt_test.h"
#include "vts.h"

#ifndef VT_BAD_DIR
#define VT_BAD_DIR "tests/data/bad"
#endif

static const char *dir = VT_BAD_DIR;

struct listed {
    char file[128];
    char status[32];
    char message[200];
};

static struct listed list[512];
static int list_count;

static int read_manifest(void)
{
    char path[1024], line[512];
    snprintf(path, sizeof path, "%s/MANIFEST", dir);
    FILE *f = fopen(path, "r");
    if (!f)
        return -1;
    while (fgets(line, sizeof line, f) && list_count < (int)(sizeof list / sizeof list[0])) {
        line[strcspn(line, "\n")] = '\0';
        if (line[0] == '#' || line[0] == '\0')
            continue;
        struct listed *l = &list[list_count];
        int used = 0;
        if (sscanf(line, "%127s %31s %n", l->file, l->status, &used) != 2 || used == 0) {
            fprintf(stderr, "MANIFEST: bad line '%s'\n", line);
            fclose(f);
            return -1;
        }
        snprintf(l->message, sizeof l->message, "%s", line + used);
        list_count++;
    }
    fclose(f);
    return 0;
}

static bool check_one(const struct listed *l, struct vts_store *s, const struct vts_error *err,
                      const char *name, const char *how)
{
    bool ok;
    if (strcmp(l->status, "ok") == 0)
        ok = s != NULL;
    else
        ok = s == NULL && strcmp(vts_status_name(err->status), l->status) == 0 &&
             strstr(err->message, l->message) && strstr(err->message, name) &&
             !strchr(err->message, '\n');
    if (!ok)
        fprintf(stderr, "  %s (%s): %s, %s '%s'; expected %s '%s'\n", l->file, how,
                s ? "opened" : "failed", vts_status_name(err->status), err->message, l->status,
                l->message);
    vts_close(s);
    return ok;
}

static void every_listed_file_gives_its_status(void)
{
    VT_CHECK_INT_EQ(read_manifest(), 0);
    VT_CHECK(list_count >= 25);
    int failed = 0;
    for (int i = 0; i < list_count; i++) {
        const struct listed *l = &list[i];
        char path[1024];
        if (snprintf(path, sizeof path, "%s/%s", dir, l->file) >= (int)sizeof path) {
            VT_CHECK(!"path too long");
            continue;
        }
        struct vts_error err = {0};
        bool ok = check_one(l, vts_open(path, &err), &err, path, "file");
        size_t size = 0;
        unsigned char *data = vts_fixture_read_file(path, &size);
        VT_CHECK(data != NULL);
        if (data) {
            unsigned char *exact = malloc(size ? size : 1); /* ASan sees over-reads */
            memcpy(exact, data, size);
            vt_error_clear(&err);
            ok &=
                check_one(l, vts_open_memory(exact, size, l->file, &err), &err, l->file, "memory");
            unsigned read_failures = 0;
            if (strcmp(l->status, "ok") == 0) {
                VT_CHECK_INT_EQ(vts_fixture_exercise(exact, size, l->file, &err, &read_failures),
                                0);
                VT_CHECK_INT_EQ(read_failures, 0);
            }
            free(exact);
            free(data);
        }
        VT_CHECK(ok);
        failed += !ok;
    }
    fprintf(stderr, "     %d bad files, %d failed\n", list_count, failed);
}

static void every_file_in_the_directory_is_listed(void)
{
    DIR *d = opendir(dir);
    VT_CHECK(d != NULL);
    if (!d)
        return;
    int files = 0;
    for (struct dirent *de; (de = readdir(d));) {
        size_t n = strlen(de->d_name);
        if (de->d_name[0] == '.' || strcmp(de->d_name, "MANIFEST") == 0)
            continue;
        files++;
        bool listed = false;
        for (int i = 0; i < list_count && !listed; i++)
            listed = strcmp(list[i].file, de->d_name) == 0;
        VT_CHECK(listed && n > 4 && strcmp(de->d_name + n - 4, ".vts") == 0);
        if (!listed)
            fprintf(stderr, "  %s is not listed in %s/MANIFEST\n", de->d_name, dir);
    }
    closedir(d);
    VT_CHECK_INT_EQ(files, list_count);
}

int main(int argc, char **argv)
{
    if (argc > 1)
        dir = argv[1];
    VT_RUN(every_listed_file_gives_its_status);
    VT_RUN(every_file_in_the_directory_is_listed);
    return vt_test_main_result();
}
