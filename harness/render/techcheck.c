/*
 * techcheck.c — see techcheck.h.
 * Invariants: glslang is started once a process (its built-in symbol tables
 * are built on the first compile and kept) and stopped at exit; the text
 * compiled is sl_techsrc's, byte for byte what the driver gets.
 */
#include "techcheck.h"
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <glslang/Include/glslang_c_interface.h>
#include <glslang/Public/resource_limits_c.h>
#include "techsrc.h"

static pthread_once_t started_once = PTHREAD_ONCE_INIT;
static int started;

static void stop(void)
{
    glslang_finalize_process();
}

static void start(void)
{
    started = glslang_initialize_process() != 0;
    if (started)
        atexit(stop);
}

/* src compiled and linked as a fragment shader; SL_OK or the mapped log. */
static enum sl_err check_one(const char *src, const char *file, struct sl_diag *d)
{
    const glslang_input_t in = {
        .language = GLSLANG_SOURCE_GLSL,
        .stage = GLSLANG_STAGE_FRAGMENT,
        .client = GLSLANG_CLIENT_NONE,   /* plain GLSL semantics, as glslangValidator without -G/-V */
        .target_language = GLSLANG_TARGET_NONE,
        .code = src,
        .default_version = 450,
        .default_profile = GLSLANG_CORE_PROFILE,
        .messages = GLSLANG_MSG_DEFAULT_BIT,
        .resource = glslang_default_resource(),
    };
    glslang_shader_t *sh = glslang_shader_create(&in);
    if (!sh)
        return sl_fail(d, SL_E_NOMEM, file, 0, NULL, "glslang: no shader");
    enum sl_err e = SL_OK;
    if (!glslang_shader_preprocess(sh, &in) || !glslang_shader_parse(sh, &in)) {
        e = sl_techsrc_log_error(file, glslang_shader_get_info_log(sh), d);
    } else {
        glslang_program_t *pr = glslang_program_create();
        if (!pr) {
            e = sl_fail(d, SL_E_NOMEM, file, 0, NULL, "glslang: no program");
        } else {
            glslang_program_add_shader(pr, sh);
            if (!glslang_program_link(pr, GLSLANG_MSG_DEFAULT_BIT))
                e = sl_techsrc_log_error(file, glslang_program_get_info_log(pr), d);
            glslang_program_delete(pr);
        }
    }
    glslang_shader_delete(sh);
    return e;
}

enum sl_err sl_techcheck(const struct sl_technique *t, struct sl_diag *d)
{
    pthread_once(&started_once, start);
    if (!started)
        return sl_fail(d, SL_E_GL, NULL, 0, NULL, "glslang did not start");
    const enum sl_techsrc_stage stage[2] = {SL_TECHSRC_MAP, SL_TECHSRC_LOOKUP};
    const char *const rel[2] = {t->map_shader, t->lookup_shader};
    for (int i = 0; i < 2; i++) {
        char file[1400];
        snprintf(file, sizeof file, "%s/%s", t->dir, rel[i]);
        char *src = sl_techsrc(t, stage[i]);
        if (!src)
            return sl_fail(d, SL_E_NOMEM, file, 0, NULL, "shader source");
        enum sl_err e = check_one(src, file, d);
        free(src);
        if (e)
            return e;
    }
    return SL_OK;
}
