/* Replays the kept fuzz findings and hostile inputs of tests/data/fuzz/<target>/ through the normal
 * (non-fuzzer) build: each file of fuzz_codec_decode/ (selector byte + payload, as the fuzz target
 * reads it) and of fuzz_image_input/ (an image file, opened by path) must fail cleanly: a non-zero
 * status and a one-line message (naming the file for image input). The fuzz targets' own checks
 * run too (compiled in with VT_FUZZ_NO_ENTRY): a violated invariant aborts the test.
 * Usage: test_fuzz_regressions [DIR] (default: the source tree's tests/data/fuzz). */
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vt_error.h"
#include "vt_test.h"

#ifndef VT_FUZZ_DATA_DIR
#define VT_FUZZ_DATA_DIR "tests/data/fuzz"
#endif

int fuzz_codec_decode_one(const uint8_t *data, size_t size, struct vts_error *err);
int fuzz_image_input_file(const char *path, struct vts_error *err);

static const char *root = VT_FUZZ_DATA_DIR;

static unsigned char *read_all(const char *path, size_t *size)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    unsigned char *buf = NULL;
    size_t cap = 0, n = 0;
    for (;;) {
        if (n == cap) {
            unsigned char *more = realloc(buf, cap = cap ? 2 * cap : 4096);
            if (!more)
                break;
            buf = more;
        }
        size_t got = fread(buf + n, 1, cap - n, f);
        n += got;
        if (got == 0)
            break;
    }
    fclose(f);
    /* an exact-size copy, so that ASan builds see any read past the end */
    unsigned char *exact = malloc(n ? n : 1);
    if (exact && n)
        memcpy(exact, buf, n);
    free(buf);
    *size = n;
    return exact;
}

/* Calls run() for every regular file of root/target; returns how many. */
static int replay(const char *target, void (*run)(const char *path, const char *name))
{
    char dir[1024];
    snprintf(dir, sizeof dir, "%s/%s", root, target);
    DIR *d = opendir(dir);
    VT_CHECK(d != NULL);
    if (!d)
        return 0;
    int count = 0;
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        if (e->d_name[0] == '.')
            continue;
        char path[2048];
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        run(path, e->d_name);
        count++;
    }
    closedir(d);
    return count;
}

static void run_codec(const char *path, const char *name)
{
    size_t size = 0;
    unsigned char *data = read_all(path, &size);
    VT_CHECK(data != NULL);
    if (!data)
        return;
    struct vts_error err = {0};
    int rc = fuzz_codec_decode_one(data, size, &err);
    free(data);
    if (rc == 0 || err.message[0] == '\0' || strchr(err.message, '\n'))
        fprintf(stderr, "fuzz_codec_decode/%s: status %d '%s'\n", name, rc, err.message);
    VT_CHECK(rc < 0);
    VT_CHECK(err.message[0] != '\0' && !strchr(err.message, '\n'));
}

static void run_image(const char *path, const char *name)
{
    struct vts_error err = {0};
    int rc = fuzz_image_input_file(path, &err);
    if (rc == 0 || !strstr(err.message, path) || strchr(err.message, '\n'))
        fprintf(stderr, "fuzz_image_input/%s: status %d '%s'\n", name, rc, err.message);
    VT_CHECK(rc < 0);
    VT_CHECK_STR_CONTAINS(err.message, path);
    VT_CHECK(!strchr(err.message, '\n'));
}

static void codec_findings_fail_cleanly(void)
{
    VT_CHECK(replay("fuzz_codec_decode", run_codec) > 0);
}

static void image_input_findings_fail_cleanly(void)
{
    VT_CHECK(replay("fuzz_image_input", run_image) > 0);
}

int main(int argc, char **argv)
{
    if (argc > 1)
        root = argv[1];
    VT_RUN(codec_findings_fail_cleanly);
    VT_RUN(image_input_findings_fail_cleanly);
    return vt_test_main_result();
}
