/* The writer's atomic-output promise under SIGKILL and a full disk. A child process writes a
 * largish store (2048 distinct tiles of 64 KiB: a 128 MiB spool, then a 128 MiB output) to a path
 * where a valid old store already exists, reporting its phases through a pipe. The parent kills it
 * at seeded random moments, at fixed points while it spools (writer created, half the tiles put),
 * right before vts_writer_finish() (the child waits on a pipe there), and at fractions of the
 * measured duration of finish after it began. Afterwards the file under the final name must be the
 * old store byte for byte, or, only when the kill came after finish began, the complete new store;
 * and the directory may hold nothing else but hidden temporaries (.store.vts.spool-*,
 * .store.vts.tmp-*). A run that is not killed must replace the old store by a rename (a reader that
 * holds the old store keeps reading it) and leave no temporaries, and runs whose file-size limit
 * (RLIMIT_FSIZE, a full disk as the writer sees it) is hit must fail with VTS_ERR_IO, keep the old
 * store and remove their temporaries. */
#include <dirent.h>
#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "robust/vts_fixture.h"
#include "vt_test.h"
#include "vts.h"
#include "vts_writer.h"

#define TILES_X    64u
#define TILES_Y    32u
#define TILE_BYTES (64u * 1024u)

static const struct vts_geometry big_geo = {TILES_X * 16, TILES_Y * 16, 16, 0, 16, 1, 1, 0};
static const struct vts_layer big_layer = {VTS_CODEC_RAW, 1, VTS_SAMPLE_U8, VTS_COLOUR_DATA, 0, 0,
                                           "blob"};

static char tmpdir[256], final_path[400];
static unsigned char *old_bytes;
static size_t old_size;

static uint64_t mix(uint64_t z)
{
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

/* Tile t's payload: one pseudo-random 64 KiB block with the tile number stamped at both ends,
 * so that every tile differs (nothing is deduplicated) and filling one costs a memcpy. */
static void fill_tile(uint32_t t, unsigned char *buf)
{
    static unsigned char block[TILE_BYTES];
    static bool made;
    if (!made) {
        for (uint32_t i = 0; i < TILE_BYTES; i += 8) {
            uint64_t v = mix(i + 1);
            memcpy(block + i, &v, 8);
        }
        made = true;
    }
    memcpy(buf, block, TILE_BYTES);
    memcpy(buf, &t, sizeof t);
    memcpy(buf + TILE_BYTES - sizeof t, &t, sizeof t);
}

enum child_mode {
    RUN_THROUGH,        /* write, finish, exit */
    WAIT_BEFORE_FINISH, /* after the last put, block until killed */
    WAIT_AT_CREATED,    /* right after the writer is created, block until killed */
    WAIT_AT_HALF,       /* after half of the tiles are put, block until killed */
};

/* Phases a child reports on its pipe (control bytes: they never occur in a message). */
#define CREATED  '\001' /* writer created */
#define PUT      '\002' /* every tile put */
#define FINISH   '\003' /* vts_writer_finish() begins */
#define FINISHED '\004' /* vts_writer_finish() returned */
#define HALF     '\005' /* half of the tiles put */

/* The child: reports its phases on report_fd, then the message of a failure, and exits with 0, or
 * 10 + the status of the failing call, negated. With fsize_limit, RLIMIT_FSIZE is set first
 * (SIGXFSZ ignored, so writes fail with EFBIG). */
static void child(const char *path, int report_fd, int wait_fd, enum child_mode mode,
                  rlim_t fsize_limit)
{
    if (fsize_limit) {
        signal(SIGXFSZ, SIG_IGN);
        struct rlimit rl = {fsize_limit, fsize_limit};
        if (setrlimit(RLIMIT_FSIZE, &rl) != 0)
            _exit(99);
    }
    struct vts_error err = {0};
    struct vts_writer *w = vts_writer_create(path, &big_geo, &big_layer, &err);
    if (!w)
        _exit(10 - VTS_ERR_IO);
    char c;
    if (write(report_fd, (char[]){CREATED}, 1) != 1)
        _exit(98);
    if (mode == WAIT_AT_CREATED && read(wait_fd, &c, 1) < 0)
        _exit(97);
    unsigned char *buf = malloc(TILE_BYTES);
    int rc = 0;
    for (uint32_t t = 0; t < TILES_X * TILES_Y && rc == 0; t++) {
        fill_tile(t, buf);
        rc = vts_writer_put(w, 0, 0, t % TILES_X, t / TILES_X, buf, TILE_BYTES, &err);
        if (t == TILES_X * TILES_Y / 2) {
            if (write(report_fd, (char[]){HALF}, 1) != 1)
                _exit(98);
            if (mode == WAIT_AT_HALF && read(wait_fd, &c, 1) < 0)
                _exit(97);
        }
    }
    if (rc == 0)
        rc = vts_writer_set_meta(w, "writer", "test_kill_writer", &err);
    if (rc == 0) {
        if (write(report_fd, (char[]){PUT}, 1) != 1)
            _exit(98);
        if (mode == WAIT_BEFORE_FINISH && read(wait_fd, &c, 1) < 0)
            _exit(97);
        if (write(report_fd, (char[]){FINISH}, 1) != 1)
            _exit(98);
        rc = vts_writer_finish(w, &err);
        if (write(report_fd, (char[]){FINISHED}, 1) != 1)
            _exit(98);
    }
    if (rc) /* the message, for the parent to check */
        if (write(report_fd, err.message, strlen(err.message)) < 0)
            _exit(98);
    vts_writer_destroy(w);
    free(buf);
    _exit(rc ? 10 - rc : 0);
}

struct run {
    pid_t pid;
    int report_fd, wait_fd; /* parent ends */
    char phases[512];       /* everything the child reported */
    int wait_status;
    double seconds;
};

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + ts.tv_nsec / 1e9;
}

static void start(struct run *r, const char *path, enum child_mode mode, rlim_t fsize_limit)
{
    int rep[2], wt[2];
    if (pipe(rep) != 0 || pipe(wt) != 0)
        abort();
    fflush(NULL);
    memset(r, 0, sizeof *r);
    r->seconds = now();
    r->pid = fork();
    if (r->pid < 0)
        abort();
    if (r->pid == 0) {
        close(rep[0]);
        close(wt[1]);
        child(path, rep[1], wt[0], mode, fsize_limit);
    }
    close(rep[1]);
    close(wt[0]);
    r->report_fd = rep[0];
    r->wait_fd = wt[1];
}

/* Reads reports until one of the wanted bytes arrives (or EOF). */
static bool wait_for(struct run *r, char wanted)
{
    size_t n = strlen(r->phases);
    while (n + 1 < sizeof r->phases) {
        ssize_t got = read(r->report_fd, r->phases + n, 1);
        if (got <= 0)
            return false;
        if (r->phases[n++] == wanted)
            return true;
    }
    return false;
}

static void finish_run(struct run *r, bool kill_it)
{
    if (kill_it)
        kill(r->pid, SIGKILL);
    while (waitpid(r->pid, &r->wait_status, 0) < 0 && errno == EINTR)
        ;
    r->seconds = now() - r->seconds;
    wait_for(r, '\0'); /* drain whatever was reported */
    close(r->report_fd);
    close(r->wait_fd);
}

static void sleep_seconds(double s)
{
    struct timespec ts = {(time_t)s, (long)((s - (double)(time_t)s) * 1e9)};
    while (nanosleep(&ts, &ts) != 0 && errno == EINTR)
        ;
}

/* Directory contents other than the final name, split into hidden temporaries and others. */
static void list_dir(int *temporaries, int *others, bool remove_temporaries)
{
    *temporaries = *others = 0;
    DIR *d = opendir(tmpdir);
    if (!d)
        return;
    for (struct dirent *de; (de = readdir(d));) {
        const char *n = de->d_name;
        if (strcmp(n, ".") == 0 || strcmp(n, "..") == 0 || strcmp(n, "store.vts") == 0)
            continue;
        if (strncmp(n, ".store.vts.spool-", 17) == 0 || strncmp(n, ".store.vts.tmp-", 15) == 0) {
            (*temporaries)++;
            if (remove_temporaries) {
                char p[700];
                snprintf(p, sizeof p, "%s/%s", tmpdir, n);
                unlink(p);
            }
        } else {
            (*others)++;
            fprintf(stderr, "  unexpected file %s\n", n);
        }
    }
    closedir(d);
}

static bool final_is_old(void)
{
    size_t size = 0;
    unsigned char *now_bytes = vts_fixture_read_file(final_path, &size);
    bool same = now_bytes && size == old_size && memcmp(now_bytes, old_bytes, size) == 0;
    free(now_bytes);
    if (same) {
        struct vts_store *s = vts_open(final_path, NULL);
        same = s != NULL;
        vts_close(s);
    }
    return same;
}

/* The complete new store: opens, has every tile, and every tile reads back exactly. */
static bool final_is_new(const char *path)
{
    struct vts_error err = {0};
    struct vts_store *s = vts_open(path, &err);
    if (!s)
        return false;
    bool ok =
        vts_store_tile_count(s) == TILES_X * TILES_Y && vts_store_meta_find(s, "writer") != NULL;
    unsigned char *want = malloc(TILE_BYTES), *got = malloc(TILE_BYTES);
    for (uint32_t t = 0; t < TILES_X * TILES_Y && ok; t++) {
        size_t len = 0;
        fill_tile(t, want);
        ok = vts_store_read(s, 0, 0, t % TILES_X, t / TILES_X, got, TILE_BYTES, &len, 0, &err) ==
                 0 &&
             len == TILE_BYTES && memcmp(got, want, TILE_BYTES) == 0;
    }
    free(want);
    free(got);
    vts_close(s);
    return ok;
}

static void restore_old(void)
{
    VT_CHECK_INT_EQ(vts_fixture_write_file(final_path, old_bytes, old_size), 0);
}

/* Phase durations of an unkilled run, measured by calibrate_and_check_a_full_write(). */
static double put_seconds = 0.2, finish_seconds = 0.2;

/* Checks after a killed run: once finish began, the rename may already be done. */
static void check_after_kill(const struct run *r, const char *what, int *replaced)
{
    bool finish_began = strchr(r->phases, FINISH) != NULL;
    bool old = final_is_old();
    bool new_store = !old && finish_began && final_is_new(final_path);
    VT_CHECK(old || new_store);
    if (!old && !new_store)
        fprintf(stderr, "  %s: the final name holds neither the old nor the complete new store\n",
                what);
    int temporaries, others;
    list_dir(&temporaries, &others, true);
    VT_CHECK_INT_EQ(others, 0);
    if (new_store) {
        (*replaced)++;
        restore_old();
    }
}

static void calibrate_and_check_a_full_write(void)
{
    char path[400];
    snprintf(path, sizeof path, "%s/calibrate.vts", tmpdir);
    struct run r;
    start(&r, path, RUN_THROUGH, 0);
    double t0 = now();
    VT_CHECK(wait_for(&r, PUT));
    double t_put = now();
    VT_CHECK(wait_for(&r, FINISH));
    double t_finish = now();
    finish_run(&r, false);
    VT_CHECK(WIFEXITED(r.wait_status) && WEXITSTATUS(r.wait_status) == 0);
    VT_CHECK(final_is_new(path));
    put_seconds = t_put - t0;
    finish_seconds = t0 + r.seconds - t_finish;
    fprintf(stderr, "     a full write: %.2f s of puts, %.2f s of finish\n", put_seconds,
            finish_seconds);
    unlink(path);
}

/* Seeded random delays within the measured duration of the puts: whatever phase a kill hits, the
 * old store must survive (or, after the rename, the complete new one). */
static void kills_at_random_moments_leave_the_old_store(void)
{
    uint64_t seed = 12345;
    int replaced = 0, before_finish = 0;
    for (int i = 0; i < 8; i++) {
        seed = mix(seed + i);
        double delay = put_seconds * (double)(seed % 1000) / 1000.0;
        struct run r;
        start(&r, final_path, RUN_THROUGH, 0);
        sleep_seconds(delay);
        finish_run(&r, true);
        char what[64];
        snprintf(what, sizeof what, "kill after %.3f s", delay);
        before_finish += strchr(r.phases, FINISH) == NULL;
        check_after_kill(&r, what, &replaced);
    }
    /* how many landed where depends on the machine's speed; the fixed points below do not */
    fprintf(stderr, "     8 random kills: %d before finish, %d after the rename\n", before_finish,
            replaced);
}

/* Deterministic points while spooling: as soon as the writer exists (spool created, empty) and
 * when half of the tiles are put; the child waits there to be killed, so that the kill cannot land
 * later however slowly the parent runs. */
static void kills_while_spooling_leave_the_old_store_and_nothing_else(void)
{
    const char points[] = {CREATED, HALF};
    const enum child_mode modes[] = {WAIT_AT_CREATED, WAIT_AT_HALF};
    for (int i = 0; i < 2; i++) {
        struct run r;
        start(&r, final_path, modes[i], 0);
        VT_CHECK(wait_for(&r, points[i]));
        finish_run(&r, true);
        VT_CHECK(WIFSIGNALED(r.wait_status) && WTERMSIG(r.wait_status) == SIGKILL);
        VT_CHECK(strchr(r.phases, FINISH) == NULL);
        VT_CHECK(final_is_old());
        int temporaries, others;
        list_dir(&temporaries, &others, true);
        VT_CHECK_INT_EQ(temporaries, 0); /* the spool has no name (O_TMPFILE): nothing is left */
        VT_CHECK_INT_EQ(others, 0);
    }
}

static void kill_right_before_finish_leaves_the_old_store_and_no_spool(void)
{
    struct run r;
    start(&r, final_path, WAIT_BEFORE_FINISH, 0);
    VT_CHECK(wait_for(&r, PUT));
    int temporaries, others;
    list_dir(&temporaries, &others, false);
    VT_CHECK_INT_EQ(temporaries, 0); /* the spool holds every payload but has no name */
    finish_run(&r, true);
    VT_CHECK(WIFSIGNALED(r.wait_status) && WTERMSIG(r.wait_status) == SIGKILL);
    VT_CHECK(strchr(r.phases, FINISH) == NULL);
    VT_CHECK(final_is_old());
    list_dir(&temporaries, &others, true);
    VT_CHECK_INT_EQ(temporaries, 0);
    VT_CHECK_INT_EQ(others, 0);
}

/* Kills at fractions of the measured duration of finish (layout, copy, fsync, rename), from the
 * moment the child reports that finish begins. */
static void kills_during_finish_leave_old_or_complete_new_store(void)
{
    static const double fractions[] = {0, 0.01, 0.05, 0.1, 0.25, 0.5, 0.75, 0.9, 1.0};
    int replaced = 0;
    for (size_t i = 0; i < sizeof fractions / sizeof fractions[0]; i++) {
        struct run r;
        start(&r, final_path, RUN_THROUGH, 0);
        VT_CHECK(wait_for(&r, FINISH));
        sleep_seconds(fractions[i] * finish_seconds);
        finish_run(&r, true);
        char what[64];
        snprintf(what, sizeof what, "kill %.0f %% into finish", fractions[i] * 100);
        check_after_kill(&r, what, &replaced);
    }
    fprintf(stderr, "     %zu kills during finish: %d after the rename\n",
            sizeof fractions / sizeof fractions[0], replaced);
}

/* Every tile of an open old store still reads back as the old fixture's payload. */
static bool old_store_reads_back(const struct vts_store *s)
{
    const struct vts_geometry *g = vts_fixture_geometry(VTS_FIXTURE_MEDIUM);
    bool ok = memcmp(vts_store_geometry(s), g, sizeof *g) == 0;
    unsigned char want[VTS_FIXTURE_MAX_PAYLOAD], got[VTS_FIXTURE_MAX_PAYLOAD];
    for (uint32_t layer = 0; layer < g->layer_count && ok; layer++)
        for (uint32_t level = 0; level < g->level_count && ok; level++) {
            struct vts_level L;
            vts_store_level(s, level, &L);
            for (uint32_t t = 0; t < L.tiles_x * L.tiles_y && ok; t++) {
                uint32_t tx = t % L.tiles_x, ty = t / L.tiles_x;
                size_t want_len =
                    vts_fixture_payload(VTS_FIXTURE_MEDIUM, layer, level, tx, ty, want);
                size_t len = 0;
                ok = vts_store_read(s, layer, level, tx, ty, got, sizeof got, &len, 0, NULL) == 0 &&
                     len == want_len && memcmp(got, want, len) == 0;
            }
        }
    return ok;
}

/* The new store replaces the old one by a rename, never by rewriting it in place: a reader that
 * had the old store open keeps reading the old tiles. */
static void a_run_that_is_not_killed_replaces_the_old_store(void)
{
    struct vts_store *reader = vts_open(final_path, NULL);
    VT_CHECK(reader != NULL);
    struct run r;
    start(&r, final_path, RUN_THROUGH, 0);
    finish_run(&r, false);
    VT_CHECK(WIFEXITED(r.wait_status) && WEXITSTATUS(r.wait_status) == 0);
    VT_CHECK(strchr(r.phases, FINISHED) != NULL);
    VT_CHECK(!final_is_old());
    VT_CHECK(final_is_new(final_path));
    VT_CHECK(reader && old_store_reads_back(reader));
    vts_close(reader);
    int temporaries, others;
    list_dir(&temporaries, &others, false);
    VT_CHECK_INT_EQ(temporaries, 0);
    VT_CHECK_INT_EQ(others, 0);
    restore_old();
}

/* RLIMIT_FSIZE makes write()/copy_file_range() fail with EFBIG, as a full disk fails with ENOSPC:
 * once while spooling payloads (1 MiB), once while writing the output (the 128 MiB spool fits,
 * the output, which adds the header and index, does not). */
static void full_disk_fails_cleanly_and_removes_temporaries(void)
{
    const rlim_t limits[] = {1u << 20, (rlim_t)TILES_X * TILES_Y * TILE_BYTES + 1024};
    const char phases[] = {CREATED, FINISH};
    for (int i = 0; i < 2; i++) {
        struct run r;
        start(&r, final_path, RUN_THROUGH, limits[i]);
        finish_run(&r, false);
        VT_CHECK(WIFEXITED(r.wait_status) && WEXITSTATUS(r.wait_status) == 10 - VTS_ERR_IO);
        VT_CHECK(strchr(r.phases, phases[i]) != NULL);
        VT_CHECK((i == 0) == (strchr(r.phases, FINISH) == NULL));
        VT_CHECK_STR_CONTAINS(r.phases, "File too large");
        VT_CHECK_STR_CONTAINS(r.phases, final_path);
        VT_CHECK(final_is_old());
        int temporaries, others;
        list_dir(&temporaries, &others, true);
        VT_CHECK_INT_EQ(temporaries, 0);
        VT_CHECK_INT_EQ(others, 0);
    }
}

int main(void)
{
    if (!vts_fixture_mkdtemp(tmpdir, sizeof tmpdir, "test_kill_writer"))
        return 1;
    snprintf(final_path, sizeof final_path, "%s/store.vts", tmpdir);
    struct vts_error err = {0};
    if (vts_fixture_write(final_path, VTS_FIXTURE_MEDIUM, &err) != 0 ||
        !(old_bytes = vts_fixture_read_file(final_path, &old_size))) {
        fprintf(stderr, "cannot write the old store: %s\n", err.message);
        return 1;
    }
    VT_RUN(calibrate_and_check_a_full_write);
    VT_RUN(kills_at_random_moments_leave_the_old_store);
    VT_RUN(kills_while_spooling_leave_the_old_store_and_nothing_else);
    VT_RUN(kill_right_before_finish_leaves_the_old_store_and_no_spool);
    VT_RUN(kills_during_finish_leave_old_or_complete_new_store);
    VT_RUN(a_run_that_is_not_killed_replaces_the_old_store);
    VT_RUN(full_disk_fails_cleanly_and_removes_temporaries);
    free(old_bytes);
    vts_fixture_rmdir_all(tmpdir);
    return vt_test_main_result();
}
