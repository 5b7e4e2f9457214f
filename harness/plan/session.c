/*
 * session.c — the scenes and packages a config's load resolved (session.h).
 */
#include "session.h"
#include <stdlib.h>
#include <string.h>
#include "method.h"
#include "scenefile.h"
#include "util.h"

const struct sl_method *sl_session_method(const struct sl_session *s, const char *name)
{
    const struct sl_method *m = sl_method_find(name);
    return m ? m : sl_packages_find(s ? &s->packages : NULL, name);
}

int sl_session_reserve_scenes(struct sl_session *s, int n)
{
    if (n <= 0)
        return 0;
    s->scenes = sl_calloc((size_t)n, sizeof *s->scenes);
    return s->scenes ? 0 : -1;
}

enum sl_err sl_session_take_scene(struct sl_session *s, const char *path, struct sl_scene *out, double *ms,
                                  struct sl_diag *d)
{
    for (int i = 0; s && i < s->nscenes; i++) {
        struct sl_session_scene *ss = &s->scenes[i];
        if (ss->held && !strcmp(ss->path, path)) {
            *out = ss->scene;
            *ms = ss->ms_load;
            memset(&ss->scene, 0, sizeof ss->scene);
            ss->held = 0;
            return SL_OK;
        }
    }
    double t0 = sl_now();
    enum sl_err e = sl_scene_load(path, out, d);
    *ms = 1e3 * (sl_now() - t0);
    return e;
}

void sl_session_free(struct sl_session *s)
{
    sl_packages_free(&s->packages);
    for (int i = 0; i < s->nscenes; i++)
        if (s->scenes[i].held)
            sl_scene_free(&s->scenes[i].scene);
    free(s->scenes);
    s->scenes = NULL;
    s->nscenes = 0;
}
