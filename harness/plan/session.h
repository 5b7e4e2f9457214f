/*
 * session.h — what loading a config resolved besides its values: the
 * technique packages its labels run (each a method, methods/package.h).
 * Returned by the load with the config (sl_config.session) and handed to
 * the run with it, in place of a process-wide registry: two configs loaded
 * in one process (a test, the bench) each have their own packages, and a
 * later search path never finds an earlier config's package by name.
 *
 * Owns: the package set (freed by sl_config_free). A config that names no
 * package has none (session NULL).
 */
#ifndef SL_SESSION_H
#define SL_SESSION_H
#include "package.h"

struct sl_session {
    struct sl_packages packages;
};

/* A method a config may name: a built-in one (registry.c), else one of
 * the session's packages; NULL if neither (s may be NULL). */
const struct sl_method *sl_session_method(const struct sl_session *s, const char *name);

#endif
