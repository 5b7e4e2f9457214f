/*
 * techsrc.c — see techsrc.h.
 * Invariants: the lookup's projection is sl_frame_project's, operation for
 * operation: cglm's glm_mat4_mulv sums m[3] + m[2] z + m[1] y + m[0] x in
 * that order, each product rounded before its sum unless the C build fuses
 * them (__FMA__: then fma, as cglm does), all `precise` so the GLSL compiler
 * may not fuse or reorder; the divisions by w are correctly rounded (a
 * driver's a / b may be off by an ulp or two: the quotient is corrected
 * against its exact fma residual). A point's home texel is floor(u) + g of
 * the u the CPU computes, never floor of a rounded u + g. Lines 1 to
 * 999,999 of every package shader are the package's file and nothing else.
 */
#include "techsrc.h"
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#if defined(__FMA__)
#define SL_CPU_FMA 1   /* cglm fuses its products (glmm_fmadd): so does the lookup */
#else
#define SL_CPU_FMA 0
#endif

/* The lookup's main, after the package (source string 2). */
static const char lookup_main[] =
    "#ifdef SL_COUNT_TAPS\n"
    "#undef texture\n"
    "#undef texelFetch\n"
    "#undef textureLod\n"
    "#undef textureGrad\n"
    "#endif\n"
    "uniform sampler2D sl_gpos;\n"
    "uniform sampler2D sl_gnrm;\n"
    "uniform usampler2D sl_gmask;\n"
    "uniform mat4 sl_frame_vp;\n"
    "uniform float sl_frame_size;\n"
    "uniform int sl_guard;\n"
    "layout(location = 0) out float sl_visibility;\n"
    "// a / b correctly rounded: the quotient nearest among the driver's and its\n"
    "// neighbours, by the exact residual a - q b (one fma)\n"
    "float sl_div(float a, float b)\n"
    "{\n"
    "    precise float q = a / b;\n"
    "    for (int k = 0; k < 2; k++) {\n"
    "        precise float r = abs(fma(-q, b, a));\n"
    "        float up = uintBitsToFloat(floatBitsToUint(q) + 1u);\n"
    "        float dn = uintBitsToFloat(floatBitsToUint(q) - 1u);\n"
    "        precise float ru = abs(fma(-up, b, a));\n"
    "        precise float rd = abs(fma(-dn, b, a));\n"
    "        if (ru < r) { q = up; r = ru; }\n"
    "        if (rd < r) q = dn;\n"
    "    }\n"
    "    return q;\n"
    "}\n"
    "void main()\n"
    "{\n"
    "    ivec2 px = ivec2(gl_FragCoord.xy);\n"
    "    if (texelFetch(sl_gmask, px, 0).r == 0u)\n"
    "        discard;\n"
    "    sl_pixel = px;\n"
    "    vec3 p = texelFetch(sl_gpos, px, 0).xyz;\n"
    "    vec3 n = texelFetch(sl_gnrm, px, 0).xyz;\n"
    "    precise vec4 c = sl_frame_vp[3];\n"
    "#if SL_CPU_FMA\n"
    "    c = fma(sl_frame_vp[2], vec4(p.z), c);\n"
    "    c = fma(sl_frame_vp[1], vec4(p.y), c);\n"
    "    c = fma(sl_frame_vp[0], vec4(p.x), c);\n"
    "#else\n"
    "    c = c + sl_frame_vp[2] * p.z;\n"
    "    c = c + sl_frame_vp[1] * p.y;\n"
    "    c = c + sl_frame_vp[0] * p.x;\n"
    "#endif\n"
    "    if (c.w != 1.0) {\n"
    "        c.x = sl_div(c.x, c.w);\n"
    "        c.y = sl_div(c.y, c.w);\n"
    "        c.z = sl_div(c.z, c.w);\n"
    "    }\n"
    "    precise float u = (c.x * 0.5 + 0.5) * sl_frame_size;\n"
    "    precise float v = (c.y * 0.5 + 0.5) * sl_frame_size;\n"
    "    sl_home_texel = ivec2(int(floor(u)), int(floor(v))) + ivec2(sl_guard);\n"
    "    precise vec2 mp = vec2(u + float(sl_guard), v + float(sl_guard));\n"
    "    sl_map_pos = mp;\n"
    "    vec2 uv = mp / sl_map_size;\n"
    "    vec3 toward = sl_persp != 0 ? normalize(sl_light_pos - p) : -sl_light_dir;\n"
    "    float sl_v = sl_lookup(p, n, uv, c.z, dot(n, toward));\n"
    "    // not finite (NaN, +-inf: read from the bits, which no folding of\n"
    "    // isnan removes): -1, a value no clamped visibility takes\n"
    "#ifdef SL_COUNT_TAPS\n"
    "    sl_visibility = float(sl_taps);\n"
    "#else\n"
    "    sl_visibility = (floatBitsToUint(sl_v) & 0x7f800000u) == 0x7f800000u ? -1.0 : clamp(sl_v, 0.0, 1.0);\n"
    "#endif\n"
    "}\n";

/* A growing string; oom sticks. */
struct sbuf { char *s; size_t n, cap; int oom; };

static void sb_printf(struct sbuf *b, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void sb_printf(struct sbuf *b, const char *fmt, ...)
{
    if (b->oom)
        return;
    for (;;) {
        va_list ap;
        va_start(ap, fmt);
        int k = vsnprintf(b->s ? b->s + b->n : NULL, b->s ? b->cap - b->n : 0, fmt, ap);
        va_end(ap);
        if (k < 0) {
            b->oom = 1;
            return;
        }
        if (b->s && b->n + (size_t)k < b->cap) {
            b->n += (size_t)k;
            return;
        }
        size_t cap = b->cap ? 2 * b->cap : 4096;
        while (cap < b->n + (size_t)k + 1)
            cap *= 2;
        char *p = realloc(b->s, cap);
        if (!p) {
            b->oom = 1;
            return;
        }
        b->s = p;
        b->cap = cap;
    }
}

static const char *glsl_type(enum sl_param_type t)
{
    return t == SL_PARAM_INT ? "int" : t == SL_PARAM_FLOAT ? "float" : "bool";
}

static void params_decl(struct sbuf *b, const struct sl_technique *t)
{
    for (int i = 0; i < t->nparams; i++)
        sb_printf(b, "uniform %s %s;\n", glsl_type(t->param[i].type), t->param[i].name);
}

static char *map_source(const struct sl_technique *t)
{
    struct sbuf b = {0};
    sb_printf(&b, "#version 450 core\n#line %d 0\n"
                  "in vec3 sl_world;\n"
                  "uniform mat4 sl_light_vp;\n"
                  "uniform int sl_persp;\n", SL_TECHSRC_LINE_PRELUDE);
    for (int i = 0; i < t->nmaps; i++)
        sb_printf(&b, "layout(location = %d) out vec4 out_%s;\n", i, t->map[i].name);
    params_decl(&b, t);
    sb_printf(&b, "void sl_map(float depth);\n#line 1 1\n%s\n#line %d 2\n"
                  "uniform float sl_empty;\n"
                  "void main()\n"
                  "{\n"
                  "    sl_map(sl_empty >= 0.0 ? sl_empty : gl_FragCoord.z);\n"
                  "}\n", t->map_src, SL_TECHSRC_LINE_MAIN);
    if (b.oom) {
        free(b.s);
        return NULL;
    }
    return b.s;
}

/* The texel reads of the lookup, counted (SL_TECHSRC_LOOKUP_TAPS): each
 * sampling call the package makes goes through a function that counts it
 * and calls the built-in. An object-like macro renames the call, so every
 * overload the wrappers declare keeps its arity; the calls whose offset or
 * component must be a constant expression (textureOffset, texelFetchOffset,
 * textureGather, ...) cannot pass through a function and are not counted. */
static const char taps_prelude[] =
    "#define SL_COUNT_TAPS 1\n"
    "int sl_taps = 0;\n"
    "vec4 sl_tap_texture(sampler2D s, vec2 p) { sl_taps++; return texture(s, p); }\n"
    "vec4 sl_tap_texture(sampler2D s, vec2 p, float b) { sl_taps++; return texture(s, p, b); }\n"
    "vec4 sl_tap_texelFetch(sampler2D s, ivec2 p, int l) { sl_taps++; return texelFetch(s, p, l); }\n"
    "vec4 sl_tap_textureLod(sampler2D s, vec2 p, float l) { sl_taps++; return textureLod(s, p, l); }\n"
    "vec4 sl_tap_textureGrad(sampler2D s, vec2 p, vec2 dx, vec2 dy)"
    " { sl_taps++; return textureGrad(s, p, dx, dy); }\n"
    "#define texture sl_tap_texture\n"
    "#define texelFetch sl_tap_texelFetch\n"
    "#define textureLod sl_tap_textureLod\n"
    "#define textureGrad sl_tap_textureGrad\n";

static char *lookup_source(const struct sl_technique *t, int taps)
{
    struct sbuf b = {0};
    sb_printf(&b, "#version 450 core\n#line %d 0\n#define SL_CPU_FMA %d\n", SL_TECHSRC_LINE_PRELUDE, SL_CPU_FMA);
    for (int i = 0; i < t->nmaps; i++)
        sb_printf(&b, "uniform sampler2D %s;\n", t->map[i].name);
    sb_printf(&b, "uniform mat4 sl_light_vp;\n"
                  "uniform vec3 sl_light_dir;\n"
                  "uniform vec3 sl_light_pos;\n"
                  "uniform int sl_persp;\n"
                  "uniform vec2 sl_texel;\n"
                  "uniform float sl_map_size;\n"
                  "uniform float sl_texel_world;\n"
                  "uniform float sl_depth_range;\n"
                  "uniform float sl_light_width;\n");
    params_decl(&b, t);
    if (taps)
        sb_printf(&b, "%s", taps_prelude);
    /* initialised here: a compiler that sees sl_lookup read them before
     * main writes them would warn (Mesa: "used uninitialized") */
    sb_printf(&b, "ivec2 sl_home_texel = ivec2(0);\n"
                  "vec2 sl_map_pos = vec2(0.0);\n"
                  "ivec2 sl_pixel = ivec2(0);\n"
                  "float sl_lookup(vec3 world, vec3 normal, vec2 uv, float depth, float ndotl);\n"
                  "#line 1 1\n%s\n#line %d 2\n%s", t->lookup_src, SL_TECHSRC_LINE_MAIN, lookup_main);
    if (b.oom) {
        free(b.s);
        return NULL;
    }
    return b.s;
}

/* "1:12(5): error: x" (Mesa), "1(12) : error C0000: x" (NVIDIA), "ERROR:
 * 1:12: x" or "WARNING: 1:12: x" (glslang, others): the source string, the line and where the message
 * starts; 0 if the line is none of these. */
static int log_line(const char *s, int *str, int *line, const char **msg)
{
    if (!strncmp(s, "ERROR: ", 7))
        s += 7;
    else if (!strncmp(s, "WARNING: ", 9))
        s += 9;
    char *e;
    long a = strtol(s, &e, 10);
    if (e == s)
        return 0;
    long b;
    if (*e == ':') {
        const char *q = e + 1;
        b = strtol(q, &e, 10);
        if (e == q)
            return 0;
        if (*e == '(') {
            while (*e && *e != ')')
                e++;
            if (*e)
                e++;
        }
    } else if (*e == '(') {
        const char *q = e + 1;
        b = strtol(q, &e, 10);
        if (e == q || *e != ')')
            return 0;
        e++;
    } else {
        return 0;
    }
    while (*e == ' ' || *e == ':')
        e++;
    *str = (int)a;
    *line = (int)b;
    *msg = e;
    return 1;
}

char *sl_techsrc(const struct sl_technique *t, enum sl_techsrc_stage stage)
{
    return stage == SL_TECHSRC_MAP ? map_source(t) : lookup_source(t, stage == SL_TECHSRC_LOOKUP_TAPS);
}

/* One message of a log: its line in the package file (0: the harness's),
 * whether an error, its text. */
struct logmsg {
    int line, error;
    char text[160];
};

#define LOG_ERRORS 4     /* errors told, the first of them in d's line */
#define LOG_WARNINGS 2   /* warnings told after them */

enum sl_err sl_techsrc_log_error(const char *file, const char *log, struct sl_diag *d)
{
    struct logmsg err[LOG_ERRORS], warn[LOG_WARNINGS], harness = {0};
    int ne = 0, nw = 0, more = 0;
    const char *first = NULL;
    size_t first_n = 0;
    for (const char *s = log; s && *s;) {
        size_t n = strcspn(s, "\n");
        char line[600];
        snprintf(line, sizeof line, "%.*s", (int)(n < sizeof line ? n : sizeof line - 1), s);
        if (!first && n) {
            first = s;
            first_n = n;
        }
        s += n + (s[n] == '\n');
        int str, ln;
        const char *msg;
        if (!log_line(line, &str, &ln, &msg) || !*msg)
            continue;
        /* glslang's prefix says the kind; Mesa's and NVIDIA's message does */
        int is_err = !strncmp(line, "ERROR: ", 7) || !strncmp(msg, "error", 5);
        int is_warn = !strncmp(line, "WARNING: ", 9) || !strncmp(msg, "warning", 7);
        if (!is_err && !is_warn)
            continue;
        if (strstr(msg, "compilation terminated"))
            continue;   /* glslang's note after its last error */
        if (!strncmp(msg, "'' : ", 5))
            for (msg += 5; *msg == ' ';)
                msg++;   /* glslang's token of a syntax error, when it has none */
        const int own = (str == 0 || str == 1) && ln >= 1 && ln < SL_TECHSRC_LINE_PRELUDE;
        struct logmsg m = {own ? ln : 0, is_err, ""};
        snprintf(m.text, sizeof m.text, "%s%s", is_err && strncmp(msg, "error", 5) ? "error: " :
                 is_warn && strncmp(msg, "warning", 7) ? "warning: " : "", msg);
        for (size_t e = strlen(m.text); e > 0 && m.text[e - 1] == ' '; e--)
            m.text[e - 1] = '\0';   /* glslang ends its messages with a space */
        if (!own) {
            if (is_err && !harness.error)
                harness = m;
        } else if (is_err && ne < LOG_ERRORS) {
            err[ne++] = m;
        } else if (!is_err && nw < LOG_WARNINGS) {
            warn[nw++] = m;
        } else {
            more++;
        }
    }
    if (!ne && harness.error)
        return sl_fail(d, SL_E_PACKAGE, file, 0, NULL, "GLSL: %s", harness.text);
    if (!ne) {
        /* no line named: the log's first line, and the next when it goes on
         * there (glslang: "Linking fragment stage: No function definition
         * (body) found:" and the function on the next line) */
        const char *next = first ? first + first_n + (first[first_n] == '\n') : NULL;
        while (next && (*next == ' ' || *next == '\t'))
            next++;
        size_t next_n = next ? strcspn(next, "\n") : 0;
        const int goes_on = first && first_n > 1 && first[first_n - 1] == ' ' && first[first_n - 2] == ':';
        return sl_fail(d, SL_E_PACKAGE, file, 0, NULL, "GLSL: %.*s%.*s", (int)(first_n < 300 ? first_n : 300),
                       first ? first : "(no log)", goes_on ? (int)(next_n < 150 ? next_n : 150) : 0,
                       goes_on ? next : "");
    }
    char text[sizeof d->msg];
    int k = snprintf(text, sizeof text, "GLSL: %s", err[0].text);
    for (int i = 1; i < ne + nw && k < (int)sizeof text; i++) {
        const struct logmsg *m = i < ne ? &err[i] : &warn[i - ne];
        k += snprintf(text + k, sizeof text - (size_t)k, "; line %d: %s", m->line, m->text);
    }
    if (more && k < (int)sizeof text)
        snprintf(text + k, sizeof text - (size_t)k, "; %d more", more);
    return sl_fail(d, SL_E_PACKAGE, file, err[0].line, NULL, "%s", text);
}
