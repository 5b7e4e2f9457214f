/*
 * glegl.h — the EGL backend behind glctx.h (built with SL_HAVE_EGL): device
 * choice, a surfaceless 4.5 core context, entry points through
 * eglGetProcAddress. Private to the render stage's context code.
 */
#ifndef SL_GLEGL_H
#define SL_GLEGL_H
#include "glctx.h"

/* Fills g->egl_display, g->egl_ctx, g->device and the entry points. */
enum sl_err sl_egl_open(struct sl_gl *g, struct sl_diag *d);
void        sl_egl_close(struct sl_gl *g);

#endif
