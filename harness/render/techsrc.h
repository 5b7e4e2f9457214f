/*
 * techsrc.h — a technique package's two fragment shaders as the harness
 * compiles them, and a compiler's log read back against the package's
 * files. GL-free: the run's driver (techpass.c) and the check at validate
 * (techcheck.c, glslang) compile the same text, so both report the same
 * lines.
 *
 * The text: `#version 450 core`, `#line SL_TECHSRC_LINE_PRELUDE 0`, the
 * prelude (the harness's uniforms, the maps' outputs or samplers, each
 * parameter's uniform; the lookup's also `#define SL_CPU_FMA`), `#line 1 1`,
 * the package's file, `#line SL_TECHSRC_LINE_MAIN 2`, the harness's main.
 * Lines 1 to SL_TECHSRC_LINE_PRELUDE - 1 of a log are therefore the
 * package file's own, whatever the prelude's length. The prelude reads and
 * writes nothing a compiler warns about (sl_home_texel, sl_map_pos and
 * sl_pixel are initialised where they are declared), so every warning of a log is the
 * package's.
 *
 * Does not: compile (techpass.h on the GL, techcheck.h with glslang), own
 * the technique.
 */
#ifndef SL_TECHSRC_H
#define SL_TECHSRC_H
#include "sl_error.h"
#include "technique.h"

#define SL_TECHSRC_LINE_PRELUDE 1000000   /* the prelude's first line (source string 0) */
#define SL_TECHSRC_LINE_MAIN 2000000      /* the harness main's (source string 2) */

/* SL_TECHSRC_LOOKUP_TAPS: the lookup whose output is the number of texel
 * reads (texture, texelFetch, textureLod, textureGrad calls) sl_lookup made
 * for the pixel, not its visibility (techpass.h, count_taps). */
enum sl_techsrc_stage { SL_TECHSRC_MAP, SL_TECHSRC_LOOKUP, SL_TECHSRC_LOOKUP_TAPS };

/* The fragment shader of t's map pass or lookup pass (malloc'd, NUL-
 * terminated); NULL when out of memory. */
char *sl_techsrc(const struct sl_technique *t, enum sl_techsrc_stage stage);

/* Map a compiler's info log to the package's file: errors first, every
 * one of them up to a few, then warnings, each with the file's line.
 * Understood: Mesa ("1:LINE(COL): error: ..."), NVIDIA ("1(LINE) : error
 * C0000: ..."), glslang and others ("ERROR: 1:LINE: ...", "WARNING:
 * 1:LINE: ..."). d gets file:LINE of the first error in the package's
 * lines and "GLSL: <its message>", then "; line N: <message>" for each
 * further error and warning; an error in the harness's lines only (a
 * missing sl_lookup) gives line 0 and that error; a log of no known form,
 * its first line. Returns SL_E_PACKAGE. */
enum sl_err sl_techsrc_log_error(const char *file, const char *log, struct sl_diag *d);

#endif
