/* Helpers for the vt-tiles end-to-end tests: write input images, run the tool, read stores back. */
#ifndef TILES_CHECK_H
#define TILES_CHECK_H

#include <stdbool.h>
#include <stdint.h>

#include "vt_image.h"
#include "vts.h"

extern const char *tiles_tool; /* path of vt-tiles */
extern const char *tiles_info; /* path of vt-info: every store written is checked with --verify */
extern char tiles_dir[256];    /* temporary directory of this test run */

/* Takes the test's arguments (vt-tiles and vt-info) into tiles_tool and tiles_info and makes
 * tiles_dir, a fresh "<$TMPDIR or /tmp>/<name>.XXXXXX". Returns 0, or the test's exit status: 2
 * for other arguments, 1 when the directory cannot be made. */
int tiles_start(int argc, char **argv, const char *name);

/* Removes tiles_dir, unless keep (a failed run's files are left for a look). */
void tiles_finish(bool keep);

/* Path of a file in tiles_dir (static buffer rotated among 8 calls). */
const char *tiles_path(const char *name);

/* Writes img (u8 or u16, 1..4 channels) as a PNG file; returns 0 or -1. */
int tiles_write_png(const char *path, const struct vt_image *img);

/* Runs "vt-tiles INPUT -o OUT ARGS..." (args: one string, split on spaces) with stderr captured
 * into tiles_path("stderr"); returns the exit status. When it succeeds, also runs
 * "vt-info --verify OUT" and returns 99 if that fails. */
int tiles_run(const char *input, const char *output, const char *args);

/* First line of the last run's stderr (static buffer). */
const char *tiles_stderr(void);

/* Payload of one tile decoded to texels (allocated; release with vt_image_release). Empty tiles
 * give a zeroed image and *empty = true. */
int tiles_read_payload(const struct vts_store *s, uint32_t level, uint32_t tx, uint32_t ty,
                       struct vt_image *out, bool *empty);

/* A whole level stitched from tile contents (no borders). */
int tiles_read_level(const struct vts_store *s, uint32_t level, struct vt_image *out);

/* Byte-compares two files. */
bool tiles_same_file(const char *a, const char *b);

#endif
