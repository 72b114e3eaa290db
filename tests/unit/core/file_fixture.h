/* Shared by the tests of lib/core's output files (test_vt_atomic_file, test_vt_output_path): a
 * scratch directory per test and small file helpers. */
#ifndef FILE_FIXTURE_H
#define FILE_FIXTURE_H

#include <stdbool.h>
#include <stddef.h>

/* The test's own directory under $TMPDIR (or /tmp), made by its main with mkdtemp(). */
extern char tmpdir[256];

/* A fresh empty directory tmpdir/name, path in out (aborts when it cannot be made). */
void fresh_dir(char *out, size_t cap, const char *name);

/* dir/name into out. */
void join(char *out, size_t cap, const char *dir, const char *name);

/* Entries of dir other than . and .. (names joined by spaces into list, when list is not NULL);
 * -1 when dir cannot be opened. */
int count_entries(const char *dir, char *list, size_t cap);

/* The whole content of path is text (and nothing more). */
bool holds(const char *path, const char *text);

/* Writes text to path (aborts when it cannot). */
void write_file(const char *path, const char *text);

/* Removes dir and everything below it (links are removed, not followed). */
void remove_tree(const char *dir);

#endif
