/* vt-view: Wang packs named by scene materials (vtv_wang_scene.h). */
#include "vtv_wang_scene.h"

#include <epoxy/gl.h>
#include <stdlib.h>
#include <string.h>

int vtv_wang_scene_open(struct vtv_wang_scene *s, char *const *paths, uint32_t count,
                        struct vts_error *err)
{
    memset(s, 0, sizeof *s);
    if (count == 0)
        return 0;
    if (!(s->packs = calloc(count, sizeof *s->packs)))
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
    s->count = count;
    for (uint32_t i = 0; i < count; i++) {
        struct vtv_wang_scene_pack *p = &s->packs[i];
        if (!(p->store = vts_open(paths[i], err)) ||
            vt_wang_pack_open(p->store, &p->info, err) != 0)
            return err->status ? err->status : VTS_ERR_BAD_INPUT;
    }
    return 0;
}

int vtv_wang_scene_upload(struct vtv_wang_scene *s, struct vts_error *err)
{
    s->uploaded = true;
    for (uint32_t i = 0; i < s->count; i++) {
        int rc = vtv_wang_load_pack(s->packs[i].store, &s->packs[i].info, &s->packs[i].gl, err);
        if (rc)
            return rc;
    }
    return 0;
}

void vtv_wang_scene_bind(const struct vtv_wang_scene *s, unsigned prog,
                         const struct vtv_material *m)
{
    if (!s || m->wang == 0 || m->wang > s->count)
        return;
    const struct vtv_wang_scene_pack *p = &s->packs[m->wang - 1];
    const GLuint tex[3] = {p->gl.pack, p->gl.perm, p->gl.order};
    static const char *const names[3] = {"wang_pack", "wang_perm", "wang_order"};
    for (int k = 0; k < 3; k++) {
        glActiveTexture(GL_TEXTURE0 + VTV_WANG_UNIT + k);
        glBindTexture(GL_TEXTURE_2D, tex[k]);
        glUniform1i(glGetUniformLocation(prog, names[k]), VTV_WANG_UNIT + k);
    }
    glActiveTexture(GL_TEXTURE0);
    glUniform1ui(glGetUniformLocation(prog, "wang_n"), p->info.hash_n);
    glUniform1ui(glGetUniformLocation(prog, "wang_kh"), p->info.kh);
    glUniform1ui(glGetUniformLocation(prog, "wang_kv"), p->info.kv);
    glUniform1ui(glGetUniformLocation(prog, "wang_cols"), p->info.cols);
    glUniform1ui(glGetUniformLocation(prog, "wang_rows"), p->info.rows);
    glUniform1i(glGetUniformLocation(prog, "wang_corners"), p->info.corners);
    glUniform1i(glGetUniformLocation(prog, "wang_shuffled"), p->info.order != NULL);
    glUniform1f(glGetUniformLocation(prog, "wang_scale"), m->wang_scale);
}

void vtv_wang_scene_free(struct vtv_wang_scene *s)
{
    for (uint32_t i = 0; i < s->count; i++) {
        struct vtv_wang_scene_pack *p = &s->packs[i];
        if (s->uploaded) {
            GLuint tex[3] = {p->gl.pack, p->gl.perm, p->gl.order};
            glDeleteTextures(3, tex);
        }
        vt_wang_info_release(&p->info);
        vts_close(p->store);
    }
    free(s->packs);
    memset(s, 0, sizeof *s);
}
