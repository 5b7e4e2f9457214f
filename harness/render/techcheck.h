/*
 * techcheck.h — a technique package's shaders compiled without GL, by
 * glslang (the Khronos reference front end), so `shadowlab validate` and
 * the load of a config that is going to run find a package's GLSL errors
 * before any scene is read, any GL context made or any truth traced.
 *
 * What it does: compiles both fragment shaders as the run assembles them
 * (techsrc.h: the prelude, #version 450 core and its defines, the package's
 * file, the harness main) for the fragment stage of desktop GLSL 4.50 core,
 * links each (a function declared and never defined, a missing sl_lookup,
 * is a link error), and maps glslang's log to the package's file and line
 * (sl_techsrc_log_error): errors first, then warnings.
 *
 * Why glslang's library and not glslangValidator as a child: the library
 * is a component like any other the build checks for and links (Debian's
 * glslang-dev ships it static, so it adds no shared library to a process),
 * its log comes back as a string without a temporary file or a pipe, and
 * validate stays one process with no executable looked up on PATH.
 *
 * Does not: replace the driver's compile at run time (a driver may refuse
 * what glslang accepts, its limits or its extensions; techpass.h's errors
 * are mapped the same way), touch GL, own the technique.
 */
#ifndef SL_TECHCHECK_H
#define SL_TECHCHECK_H
#include "sl_error.h"
#include "technique.h"

/* Compile and link t's map and lookup shaders. SL_OK, or SL_E_PACKAGE
 * naming the shader file and the line of the package's first error
 * (SL_E_NOMEM, SL_E_GL if glslang cannot start). */
enum sl_err sl_techcheck(const struct sl_technique *t, struct sl_diag *d);

#endif
