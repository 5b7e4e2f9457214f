/*
 * registry.c — the plain table of methods. Adding a method: write
 * methods/<name>.c defining `const struct sl_method sl_method_<name>` (CMake
 * compiles every .c file of methods/) and add its two lines here
 * (doc/adding-a-method.md).
 */
#include <string.h>
#include "method.h"

extern const struct sl_method sl_method_nsm;
extern const struct sl_method sl_method_bgsm;
extern const struct sl_method sl_method_sgsm;
extern const struct sl_method sl_method_csm;
extern const struct sl_method sl_method_sgsm_adj;
extern const struct sl_method sl_method_csm_adj;
extern const struct sl_method sl_method_hertel;
extern const struct sl_method sl_method_hertel_exact;
extern const struct sl_method sl_method_coherence;
extern const struct sl_method sl_method_texel;
extern const struct sl_method sl_method_neighbours;
extern const struct sl_method sl_method_adjacency;
extern const struct sl_method sl_method_chain;
extern const struct sl_method sl_method_raytrace;
extern const struct sl_method sl_method_hard_point;
extern const struct sl_method sl_method_soft_mc;
extern const struct sl_method sl_method_point_map;
extern const struct sl_method sl_method_zpart;
extern const struct sl_method sl_method_lispsm;
extern const struct sl_method sl_method_external;

static const struct sl_method *const sl_methods[] = {
    &sl_method_nsm,
    &sl_method_coherence,
    &sl_method_texel,
    &sl_method_neighbours,
    &sl_method_adjacency,
    &sl_method_chain,
    &sl_method_bgsm,
    &sl_method_sgsm,
    &sl_method_sgsm_adj,
    &sl_method_csm,
    &sl_method_csm_adj,
    &sl_method_hertel,
    &sl_method_hertel_exact,
    &sl_method_raytrace,
    &sl_method_hard_point,
    &sl_method_soft_mc,
    &sl_method_point_map,
    &sl_method_zpart,
    &sl_method_lispsm,
    &sl_method_external,
    NULL,
};

const struct sl_method *sl_method_find(const char *name)
{
    for (int i = 0; sl_methods[i]; i++)
        if (strcmp(sl_methods[i]->name, name) == 0)
            return sl_methods[i];
    return NULL;   /* a technique package's: the config's session (plan/session.h) */
}

int sl_method_count(void)
{
    int n = 0;
    while (sl_methods[n])
        n++;
    return n;
}

const struct sl_method *sl_method_at(int i) { return sl_methods[i]; }

static const char *const sl_self_names[] = {
#define SL_SELF_TEXT(id, text) text,
    SL_SELF_SHADOW(SL_SELF_TEXT)
#undef SL_SELF_TEXT
};

const char *sl_self_shadow_name(enum sl_self_shadow s)
{
    return (s >= 0 && s < SL_SELF_COUNT) ? sl_self_names[s] : "?";
}

