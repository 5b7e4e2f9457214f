/*
 * glfn.c — see glfn.h: the GL entry points shadowlab calls, looked up once
 * through OSMesa.
 */
#include "glfn.h"
#include <GL/osmesa.h>
#include <string.h>

#define SL_GL_DEF(type, name) type sl_##name;
SL_GL_FUNCS(SL_GL_DEF)
#undef SL_GL_DEF

const char *sl_glfn_load(void)
{
#define SL_GL_LOAD(type, name)                                    \
    {                                                             \
        OSMESAproc p_ = OSMesaGetProcAddress(#name);              \
        if (!p_)                                                  \
            return #name;                                         \
        memcpy(&sl_##name, &p_, sizeof p_);                       \
    }
    SL_GL_FUNCS(SL_GL_LOAD)
#undef SL_GL_LOAD
    return NULL;
}
