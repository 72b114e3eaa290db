/* Path helpers of vt-obj2ply (tools/vt-obj2ply/vt-obj2ply.c). */
#ifndef VT_OBJ2PLY_PATH_H
#define VT_OBJ2PLY_PATH_H

/* Absolute, normalised form of path (realpath of its directory + its name). malloc'ed or NULL. */
char *vt_obj2ply_path_absolute(const char *path);

/* target relative to directory dir (both absolute). malloc'ed or NULL. */
char *vt_obj2ply_path_relative(const char *dir, const char *target);

#endif
