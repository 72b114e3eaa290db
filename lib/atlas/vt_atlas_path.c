/* Texture paths of vt-atlas's layout made relative to the atlas.json they are written into
 * (vt_atlas_place_relative_path() in vt_atlas_place.h). */
#include "vt_atlas_place.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "vt_checked.h"

/* Appends the components of path to the stack parts (".." pops, "." and "" are dropped). */
static size_t push_components(char *path, char **parts, size_t n)
{
    for (char *save = NULL, *c = strtok_r(path, "/", &save); c; c = strtok_r(NULL, "/", &save)) {
        if (strcmp(c, ".") == 0)
            continue;
        if (strcmp(c, "..") == 0) {
            if (n)
                n--;
            continue;
        }
        parts[n++] = c;
    }
    return n;
}

char *vt_atlas_place_relative_path(const char *output, const char *path)
{
    if (path[0] == '/')
        return strdup(path);
    char cwd[4096];
    if (!getcwd(cwd, sizeof cwd))
        return NULL;
    /* Each joined path fits in max bytes and has fewer than max components; the result climbs
     * at most max / 2 directories ("../" each) before b's components. */
    size_t max, out_bytes, parts_bytes;
    if (!vt_size_add(strlen(cwd) + 4, strlen(output), &max) ||
        !vt_size_add(max, strlen(path), &max) || !vt_size_mul(max, 3, &out_bytes) ||
        !vt_size_mul(max, sizeof(char *), &parts_bytes))
        return NULL;
    char *a = malloc(max), *b = malloc(max), *out = malloc(out_bytes);
    char **pa = malloc(parts_bytes), **pb = malloc(parts_bytes);
    char *result = NULL;
    if (!a || !b || !out || !pa || !pb)
        goto done;
    snprintf(a, max, "%s/%s", output[0] == '/' ? "" : cwd, output);
    snprintf(b, max, "%s/%s", cwd, path);
    size_t na = push_components(a, pa, 0), nb = push_components(b, pb, 0);
    if (na)
        na--; /* the output's directory */
    size_t common = 0;
    while (common < na && common < nb && strcmp(pa[common], pb[common]) == 0)
        common++;
    out[0] = 0;
    for (size_t i = common; i < na; i++)
        strcat(out, "../");
    for (size_t i = common; i < nb; i++) {
        strcat(out, pb[i]);
        if (i + 1 < nb)
            strcat(out, "/");
    }
    result = strdup(out);
done:
    free(a);
    free(b);
    free(out);
    free(pa);
    free(pb);
    return result;
}
