/*
 * glbackend.h — the GL backends a config or the command line may choose
 * (gl: osmesa|egl, --gl), apart from the context itself (glctx.h), so a
 * config names one without seeing GL.
 *
 * Owns: nothing. Does not: open a context or load a library (glctx.c).
 */
#ifndef SL_GLBACKEND_H
#define SL_GLBACKEND_H

/* Zero is the default: OSMesa where built, else EGL. */
enum sl_gl_backend { SL_GL_DEFAULT = 0, SL_GL_OSMESA, SL_GL_EGL };

/* "osmesa", "egl" ("default" for SL_GL_DEFAULT). */
const char *sl_gl_backend_name(enum sl_gl_backend b);
/* "osmesa" or "egl" -> the backend; SL_GL_DEFAULT for anything else. */
enum sl_gl_backend sl_gl_backend_parse(const char *s);
/* SL_GL_DEFAULT -> $SHADOWLAB_GL when it names a backend, else OSMesa where
 * built, else EGL; others unchanged. The order of choice is so: --gl on the
 * command line, then the config's gl:, then SHADOWLAB_GL, then the build's. */
enum sl_gl_backend sl_gl_backend_resolve(enum sl_gl_backend b);
/* Whether this binary was built with that backend (SL_GL_DEFAULT: any). */
int sl_gl_backend_built(enum sl_gl_backend b);

#endif
