/*
 * session.h — what loading a config resolved besides its values: the
 * scenes its entries name (each file read once, by the load, which needs
 * them to check viewpoints, paths and lights) and the technique packages
 * its labels run (each a method, methods/package.h). Returned by the load
 * with the config (sl_config.session) and handed to the run with it, in
 * place of process-wide registries and second reads: two configs loaded in
 * one process (a test, the bench) each have their own, and a later search
 * path never finds an earlier config's package by name.
 *
 * Owns: the scenes not yet taken by a run, and the package set; both freed
 * by sl_config_free (sl_session_free).
 */
#ifndef SL_SESSION_H
#define SL_SESSION_H
#include "package.h"
#include "scene.h"

struct sl_session_scene {
    char   path[1024];       /* the file, as the config entry resolved it (sl_config_scene.path) */
    struct sl_scene scene;   /* as the load read it; valid while held */
    double ms_load;          /* what reading it took (the run's ms_scene) */
    int    held;             /* 0 once a run took it */
};

struct sl_session {
    struct sl_packages packages;
    struct sl_session_scene *scenes;   /* one per config scene entry */
    int nscenes;
};

/* A method a config may name: a built-in one (registry.c), else one of
 * the session's packages; NULL if neither (s may be NULL). */
const struct sl_method *sl_session_method(const struct sl_session *s, const char *name);

/* Room for n scenes (the load's entries); 0, or -1 when out of memory. */
int sl_session_reserve_scenes(struct sl_session *s, int n);

/* The scene of the file at path (a config entry's resolved path) for a
 * run, in *out (the caller owns it: sl_scene_free): the one the load read,
 * moved out of the session; when a run has already taken it (a config run
 * twice in one process) or the session has none (s NULL, a config made in
 * code), read from path as the load does. By path, not by entry: a caller
 * may drop or reorder a config's scene entries. *ms: what reading took. */
enum sl_err sl_session_take_scene(struct sl_session *s, const char *path, struct sl_scene *out, double *ms,
                                  struct sl_diag *d);

void sl_session_free(struct sl_session *s);

#endif
