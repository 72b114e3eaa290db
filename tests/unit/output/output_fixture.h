/* Shared by the tests of formats/output (test_vt_png_file, test_vt_tiff_file). */
#ifndef OUTPUT_FIXTURE_H
#define OUTPUT_FIXTURE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/* A fresh directory under $TMPDIR (or /tmp), made by the test's main. */
extern char test_dir[256];

/* The state of the seeded byte stream (set it to seed). */
extern uint64_t rng_state;
uint64_t rng_next(void);
void rng_fill(void *buf, size_t len);

/* test_dir/name, in a static buffer (valid until the next call). */
const char *test_path(const char *name);

bool file_exists(const char *path);

/* Number of entries in test_dir besides . and .. (temporary files included). */
int dir_entry_count(void);

#endif
