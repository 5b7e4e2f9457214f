/*
 * glfn.c — see glfn.h: the GL entry points shadowlab calls, looked up once
 * through the context's backend.
 */
#include "glfn.h"
#include <string.h>

#define SL_GL_DEF(name) __typeof__(sl_##name) sl_##name; /* typed by glfn.h */
SL_GL_FUNCS(SL_GL_DEF)
#undef SL_GL_DEF

const char *sl_glfn_load(sl_glfn_getproc getproc)
{
#define SL_GL_LOAD(name)                                          \
    {                                                             \
        sl_glproc p_ = getproc(#name);                            \
        if (!p_)                                                  \
            return #name;                                         \
        memcpy(&sl_##name, &p_, sizeof p_);                       \
    }
    SL_GL_FUNCS(SL_GL_LOAD)
#undef SL_GL_LOAD
    return NULL;
}
