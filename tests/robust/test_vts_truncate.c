/* Every truncated prefix of a valid store fails cleanly: an exact status, a one-line message that
 * names the file, never a crash. Each prefix is a fresh allocation of exactly its length, so ASan
 * (sanitizer build) reports any read past it; a sample of lengths also goes through a real file. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "internal/vts_format.h"
#include "robust/vts_fixture.h"
#include "vt_error.h"
#include "vt_test.h"
#include "vts.h"

static char tmpdir[256];

/* What a prefix of len bytes must report: shorter than the magic, shorter than the header, or
 * cut somewhere in the layer table, index, metadata or data (a region lies past the end). */
static int expected_status(size_t len, const char **message)
{
    if (len < VTS_MAGIC_SIZE) {
        *message = "is not a vts store";
        return VTS_ERR_NOT_VTS;
    }
    if (len < VTS_HEADER_SIZE) {
        *message = "header is truncated";
        return VTS_ERR_CORRUPT;
    }
    *message = "lies past the end of the file";
    return VTS_ERR_CORRUPT;
}

static int check_failure(struct vts_store *s, const struct vts_error *err, size_t len,
                         const char *name, const char *how)
{
    const char *want;
    int status = expected_status(len, &want);
    bool ok = s == NULL && err->status == status && strstr(err->message, want) &&
              strstr(err->message, name) && strchr(err->message, '\n') == NULL;
    VT_CHECK(ok);
    if (!ok)
        fprintf(stderr, "  prefix %zu (%s): %s, %s '%s'\n", len, how, s ? "opened" : "failed",
                vts_status_name(err->status), err->message);
    vts_close(s);
    return ok ? 0 : 1;
}

static void every_prefix_fails_cleanly(enum vts_fixture which)
{
    size_t size;
    unsigned char *full = vts_fixture_bytes(tmpdir, which, &size);
    VT_CHECK(full != NULL);
    if (!full)
        return;
    char path[400];
    snprintf(path, sizeof path, "%s/prefix.vts", tmpdir);
    int failures = 0;
    unsigned files = 0;
    for (size_t len = 0; len < size; len++) {
        unsigned char *copy = malloc(len ? len : 1);
        memcpy(copy, full, len);
        struct vts_error err = {0};
        char name[64];
        snprintf(name, sizeof name, "prefix-%zu.vts", len);
        failures +=
            check_failure(vts_open_memory(copy, len, name, &err), &err, len, name, "memory");
        free(copy);
        /* real files: every length around the structure boundaries and every 37th */
        if (len < 140 || len % 37 == 0 || size - len < 70) {
            VT_CHECK_INT_EQ(vts_fixture_write_file(path, full, len), 0);
            vt_error_clear(&err);
            failures += check_failure(vts_open(path, &err), &err, len, path, "file");
            files++;
        }
    }
    /* the whole file opens and every tile reads back */
    unsigned char *copy = malloc(size);
    memcpy(copy, full, size);
    struct vts_error err = {0};
    unsigned read_failures = 99;
    VT_CHECK_INT_EQ(vts_fixture_exercise(copy, size, "full", &err, &read_failures), 0);
    VT_CHECK_INT_EQ(read_failures, 0);
    VT_CHECK_INT_EQ(vts_fixture_write_file(path, full, size), 0);
    struct vts_store *s = vts_open(path, &err);
    VT_CHECK(s != NULL);
    vts_close(s);
    fprintf(stderr, "     fixture %d: %zu prefixes (%u also as files), %d failed\n", (int)which,
            size, files, failures);
    free(copy);
    free(full);
    unlink(path);
}

static void every_prefix_of_the_small_store_fails_cleanly(void)
{
    every_prefix_fails_cleanly(VTS_FIXTURE_SMALL);
}

static void every_prefix_of_the_medium_store_fails_cleanly(void)
{
    every_prefix_fails_cleanly(VTS_FIXTURE_MEDIUM);
}

static void every_prefix_of_a_store_without_payloads_fails_cleanly(void)
{
    every_prefix_fails_cleanly(VTS_FIXTURE_EMPTY);
}

int main(void)
{
    if (!vts_fixture_mkdtemp(tmpdir, sizeof tmpdir, "test_vts_truncate"))
        return 1;
    VT_RUN(every_prefix_of_the_small_store_fails_cleanly);
    VT_RUN(every_prefix_of_the_medium_store_fails_cleanly);
    VT_RUN(every_prefix_of_a_store_without_payloads_fails_cleanly);
    vts_fixture_rmdir_all(tmpdir);
    return vt_test_main_result();
}
