/* Path helpers of vt-obj2ply (see vt_obj2ply_path.h). */
#define _XOPEN_SOURCE 700 /* realpath */
#include "vt_obj2ply_path.h"

#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Absolute, normalised form of path (realpath of its directory + its name). malloc'ed or NULL. */
char *vt_obj2ply_path_absolute(const char *path)
{
    char *copy = strdup(path);
    if (!copy)
        return NULL;
    char *slash = strrchr(copy, '/');
    const char *dir = ".", *name = copy;
    if (slash == copy) {
        dir = "/";
        name = copy + 1;
    } else if (slash) {
        *slash = '\0';
        dir = copy;
        name = slash + 1;
    }
    char *rdir = realpath(dir, NULL);
    char *res = NULL;
    if (rdir) {
        size_t n = strlen(rdir) + strlen(name) + 2;
        res = malloc(n);
        if (res)
            snprintf(res, n, "%s%s%s", rdir, strcmp(rdir, "/") ? "/" : "", name);
    }
    free(rdir);
    free(copy);
    return res;
}

/* target relative to directory dir (both absolute). malloc'ed or NULL. */
char *vt_obj2ply_path_relative(const char *dir, const char *target)
{
    size_t dir_len = strlen(dir), common = 0, i = 0;
    while (dir[i] && dir[i] == target[i]) {
        i++;
        if (dir[i - 1] == '/')
            common = i;
    }
    if (!dir[i] && target[i] == '/')
        common = i + 1; /* target is inside dir */
    const char *rest = common <= dir_len ? dir + common : "";
    size_t ups = 0;
    for (const char *p = rest; *p; p++)
        if (*p != '/' && (p == rest || p[-1] == '/'))
            ups++;
    size_t n = 3 * ups + strlen(target + common) + 1;
    char *res = malloc(n);
    if (!res)
        return NULL;
    res[0] = '\0';
    for (size_t k = 0; k < ups; k++)
        strcat(res, "../");
    strcat(res, target + common);
    return res;
}
