/* Technique packages (issue 36): the loader's errors name technique.yaml's
 * line and key; a GLSL error names the package file's line; nsm_glsl and
 * pcf look up hand-made texels with known answers; and nsm_glsl rendered
 * over a scene gives, at every pixel, the C depth layer's comparison (z <=
 * depth at sl_frame_texel), for a directional and a spot light. */
#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <unistd.h>
#include <sys/stat.h>
#include <cmocka.h>
#include "sl_test.h"
#include "fixture.h"
#include "lightfit.h"
#include "shadowmap.h"
#include "techcheck.h"
#include "techpass.h"
#include "techsrc.h"
#include "technique.h"

/* ---- packages written into the test folder ---- */

static const char good_map[] = "void sl_map(float z)\n{\n    out_depth = vec4(z);\n}\n";
static const char good_lookup[] =
    "float sl_lookup(vec3 w, vec3 n, vec2 uv, float z, float ndotl)\n"
    "{\n"
    "    return z <= texture(depth, uv).r ? 1.0 : 0.0;\n"
    "}\n";

/* A lookup whose line 6 is an error after lines 3 and 4 read the harness's
 * sl_map_pos and sl_home_texel (which a driver may warn about) */
static const char late_error[] =
    "float sl_lookup(vec3 w, vec3 n, vec2 uv, float z, float ndotl)\n"
    "{\n"
    "    vec2 p = sl_map_pos;\n"
    "    ivec2 h = sl_home_texel;\n"
    "    float x = p.x + float(h.y);\n"
    "    return x + undeclared_name;\n"
    "}\n";

/* <test dir>/<name>/ with technique.yaml = yaml and both shaders */
static void package(char *dir, size_t n, const char *name, const char *yaml, const char *lookup)
{
    snprintf(dir, n, "%s/%s", sl_test_dir, name);
    mkdir(dir, 0755);
    sl_test_write(dir, "technique.yaml", yaml);
    sl_test_write(dir, "map.glsl", good_map);
    sl_test_write(dir, "lookup.glsl", lookup ? lookup : good_lookup);
}

/* A package of name `name` whose lines are head + the rest below. */
#define HEAD(name) "name: " name "\nsummary: \"a test package\"\n"
#define MAPS "maps:\n  - {name: depth, format: r32f}\n"
#define SHADERS "map_shader: map.glsl\nlookup_shader: lookup.glsl\n"

/* The package must fail with SL_E_PACKAGE at `line`, 'key', the message holding `has`. */
static void expect_bad(const char *name, const char *yaml, int line, const char *key, const char *has)
{
    char dir[600];
    package(dir, sizeof dir, name, yaml, NULL);
    struct sl_technique t;
    struct sl_diag d;
    enum sl_err e = sl_tech_load(dir, &t, &d);
    char text[1200];
    sl_diag_format(&d, e, text, sizeof text);
    fprintf(stderr, "  %s: %s\n", name, text);
    assert_int_equal(e, SL_E_PACKAGE);
    char file[700];
    snprintf(file, sizeof file, "%s/technique.yaml", dir);
    assert_string_equal(d.file, file);
    assert_int_equal(d.line, line);
    assert_string_equal(d.key, key);
    assert_non_null(strstr(d.msg, has));
    /* the one line the CLI prints: FILE:LINE: 'KEY': message */
    char want[800];
    if (line)
        snprintf(want, sizeof want, "%s:%d: '%s': ", file, line, key);
    else
        snprintf(want, sizeof want, "%s: '%s': ", file, key);
    assert_true(strncmp(text, want, strlen(want)) == 0);
}

static void technique_loader_errors(void **st)
{
    (void)st;
    expect_bad("bad_type", HEAD("bad_type") MAPS SHADERS
               "params:\n  - {name: k, type: integer, default: 3}\n", 8, "params[0].type", "int, float or bool");
    expect_bad("bad_default", HEAD("bad_default") MAPS SHADERS
               "params:\n  - {name: k, type: int, default: 3}\n  - {name: r, type: int, default: 11, min: 1, max: 9}\n",
               9, "params[1].default", "outside [1, 9]");
    expect_bad("bad_int", HEAD("bad_int") MAPS SHADERS
               "params:\n  - {name: k, type: int, default: 2.5}\n", 8, "params[0].default", "is not a whole number");
    /* a name a config's method entry gives itself: the cascades' partitions would shadow it */
    expect_bad("entry_key", HEAD("entry_key") MAPS SHADERS
               "params:\n  - {name: partitions, type: int, default: 5}\n", 8, "params[0].name", "cascades");
    expect_bad("entry_key2", HEAD("entry_key2") MAPS SHADERS
               "params:\n  - {name: k, type: int, default: 1}\n  - {name: label, type: int, default: 1}\n", 9,
               "params[1].name", "method entry");
    expect_bad("unknown_key", HEAD("unknown_key") "colour: red\n" MAPS SHADERS, 3, "colour", "unknown key");
    expect_bad("dotdot", HEAD("dotdot") MAPS "map_shader: ../x/map.glsl\nlookup_shader: lookup.glsl\n", 5,
               "map_shader", "'..'");
    expect_bad("absolute", HEAD("absolute") MAPS "map_shader: /etc/passwd\nlookup_shader: lookup.glsl\n", 5,
               "map_shader", "absolute");
    expect_bad("missing_shader", HEAD("missing_shader") MAPS "map_shader: map.glsl\nlookup_shader: nope.glsl\n", 6,
               "lookup_shader", "not in the package folder");
    expect_bad("missing_key", HEAD("missing_key") MAPS "map_shader: map.glsl\n", 0, "lookup_shader", "missing");
    expect_bad("bad_name", "name: Bad-Name\nsummary: x\n" MAPS SHADERS, 1, "name", "[a-z]");
    expect_bad("bad_map_name", HEAD("bad_map_name") "maps:\n  - {name: 2depth, format: r32f}\n" SHADERS, 4,
               "maps[0].name", "GLSL identifier");
    expect_bad("bad_format", HEAD("bad_format") "maps:\n  - {name: depth, format: r8}\n" SHADERS, 4,
               "maps[0].format", "r32f");
    expect_bad("bad_blur", HEAD("bad_blur") "maps:\n  - {name: depth, format: r32f, post: blur, blur: radius}\n"
               SHADERS, 4, "maps[0].blur", "names no parameter");
    expect_bad("bad_reach", HEAD("bad_reach") MAPS SHADERS "reach: {texels: 1, param: width}\n", 7, "reach.param",
               "names no parameter");
    expect_bad("keyword", HEAD("keyword") MAPS SHADERS "params:\n  - {name: uniform, type: int, default: 1}\n", 8,
               "params[0].name", "keyword");
    /* a shader through a symbolic link is refused */
    char dir[600], link[700];
    package(dir, sizeof dir, "linked", HEAD("linked") MAPS "map_shader: map.glsl\nlookup_shader: l.glsl\n", NULL);
    snprintf(link, sizeof link, "%s/l.glsl", dir);
    assert_int_equal(symlink("/etc/hostname", link), 0);
    struct sl_technique t;
    struct sl_diag d;
    assert_int_equal(sl_tech_load(dir, &t, &d), SL_E_PACKAGE);
    assert_int_equal(d.line, 6);
    assert_string_equal(d.key, "lookup_shader");
    assert_non_null(strstr(d.msg, "symbolic link"));
}

/* The shipped packages load, with their reach and taps. */
static void technique_shipped(void **st)
{
    (void)st;
    struct sl_technique t;
    struct sl_diag d;
    assert_int_equal(sl_tech_load("techniques/pcf", &t, &d), SL_OK);
    assert_string_equal(t.name, "pcf");
    assert_int_equal(t.nparams, 3);
    struct sl_params v;
    sl_tech_defaults(&t, &v);
    assert_int_equal(v.n, 3);
    assert_true(v.v[0] == 3 && v.v[1] == 1 && v.v[2] == 0);   /* kernel 3, bias 1 texel, no disc */
    assert_int_equal(sl_tech_reach(&t, &v), 1);   /* a 3x3 box: one texel around the home texel */
    assert_true(sl_tech_taps(&t, &v) == 9);
    assert_int_equal(sl_params_put(&v, "kernel", 5, &d), SL_OK);
    assert_int_equal(sl_tech_reach(&t, &v), 2);
    assert_int_equal(sl_tech_guard(&t, &v), 2);
    assert_int_equal(sl_params_put(&v, "kernel", 1, &d), SL_OK);
    assert_int_equal(sl_tech_guard(&t, &v), 0);   /* kernel 1: the frame's own map, no band */
    assert_int_equal(sl_params_put(&v, "kernel", 5, &d), SL_OK);
    assert_true(sl_tech_taps(&t, &v) == 25);
    assert_int_equal(sl_params_put(&v, "kernel", 11, &d), SL_E_METHOD);
    assert_string_equal(d.key, "kernel");
    assert_int_equal(sl_params_put(&v, "kernel", 2.5, &d), SL_E_METHOD);
    assert_int_equal(sl_params_put(&v, "poisson", 2, &d), SL_E_METHOD);
    assert_int_equal(sl_params_put(&v, "nope", 1, &d), SL_E_METHOD);
    sl_tech_free(&t);
    assert_int_equal(sl_tech_load("techniques/nsm", &t, &d), SL_OK);
    assert_string_equal(t.name, "nsm_glsl");
    sl_tech_defaults(&t, &v);
    assert_int_equal(sl_tech_guard(&t, &v), 0);
    assert_true(sl_tech_taps(&t, &v) == 1);
    sl_tech_free(&t);
}

/* `trace: {between: [lo, hi]}`: a band 0 <= lo < hi <= 1 is read; any other
 * is refused naming technique.yaml, the line of `between` and the key. */
static void technique_trace_band(void **st)
{
    (void)st;
    char dir[600];
    package(dir, sizeof dir, "band_ok", HEAD("band_ok") MAPS SHADERS "trace:\n  between: [0.05, 0.95]\n", NULL);
    struct sl_technique t;
    struct sl_diag d;
    assert_int_equal(sl_tech_load(dir, &t, &d), SL_OK);
    assert_int_equal(t.trace, 1);
    assert_true(t.trace_lo == 0.05 && t.trace_hi == 0.95);
    sl_tech_free(&t);
    package(dir, sizeof dir, "band_none", HEAD("band_none") MAPS SHADERS, NULL);
    assert_int_equal(sl_tech_load(dir, &t, &d), SL_OK);
    assert_int_equal(t.trace, 0);
    sl_tech_free(&t);
    expect_bad("band_reversed", HEAD("band_reversed") MAPS SHADERS "trace:\n  between: [0.9, 0.1]\n", 8,
               "trace.between", "0 <= lo < hi <= 1");
    expect_bad("band_empty", HEAD("band_empty") MAPS SHADERS "trace:\n  between: [0.5, 0.5]\n", 8,
               "trace.between", "0 <= lo < hi <= 1");
    expect_bad("band_above", HEAD("band_above") MAPS SHADERS "trace:\n  between: [0.2, 1.5]\n", 8,
               "trace.between", "[0.2, 1.5]");
    expect_bad("band_below", HEAD("band_below") MAPS SHADERS "trace:\n  between: [-0.1, 0.5]\n", 8,
               "trace.between", "0 <= lo");
    expect_bad("band_nan", HEAD("band_nan") MAPS SHADERS "trace:\n  between: [.nan, 0.5]\n", 8,
               "trace.between[0]", "expected a number, got '.nan'");
    expect_bad("band_three", HEAD("band_three") MAPS SHADERS "trace:\n  between: [0.1, 0.5, 0.9]\n", 8,
               "trace.between", "at most 2");
    expect_bad("band_one", HEAD("band_one") MAPS SHADERS "trace:\n  between: [0.1]\n", 8,
               "trace.between", "expected a list of at least 2 entries, got 1");
    expect_bad("band_word", HEAD("band_word") MAPS SHADERS "trace:\n  between: [low, 0.5]\n", 8,
               "trace.between[0]", "expected a number, got 'low'");
    expect_bad("band_key", HEAD("band_key") MAPS SHADERS "trace:\n  within: [0.1, 0.5]\n", 8,
               "trace.within", "unknown key");
}

/* The search path and the set: one package a name (the same package found
 * twice is kept once, two different ones are an error naming both), a C
 * method's name refused. */
static void technique_set_scan(void **st)
{
    (void)st;
    char root[600], a[600], b[600], dir[700];
    snprintf(root, sizeof root, "%s/set", sl_test_dir);
    mkdir(root, 0755);
    snprintf(a, sizeof a, "%s/a", root);
    snprintf(b, sizeof b, "%s/b", root);
    mkdir(a, 0755);
    mkdir(b, 0755);
    snprintf(dir, sizeof dir, "%s/one", a);
    mkdir(dir, 0755);
    sl_test_write(dir, "technique.yaml", HEAD("twin") MAPS SHADERS);
    sl_test_write(dir, "map.glsl", good_map);
    sl_test_write(dir, "lookup.glsl", good_lookup);
    snprintf(dir, sizeof dir, "%s/two", b);   /* never read: b is a package itself (below) */
    mkdir(dir, 0755);
    sl_test_write(dir, "technique.yaml", HEAD("twin") "summary2: x\n" MAPS SHADERS);
    /* b is a package folder of its own, not a folder of packages */
    sl_test_write(b, "technique.yaml", HEAD("other") MAPS SHADERS);
    sl_test_write(b, "map.glsl", good_map);
    sl_test_write(b, "lookup.glsl", good_lookup);
    char dirs[SL_TECH_MAX_DIRS][1024];
    const char *origin[SL_TECH_MAX_DIRS];
    setenv("SHADOWLAB_TECHNIQUES", b, 1);
    const char *cfg[1] = {"a"};
    int n = sl_tech_dirs(cfg, 1, root, dirs, origin, SL_TECH_MAX_DIRS);
    unsetenv("SHADOWLAB_TECHNIQUES");
    assert_int_equal(n, 4);
    assert_string_equal(dirs[0], a);
    assert_string_equal(origin[0], "config");
    assert_string_equal(dirs[1], b);
    assert_string_equal(origin[1], "SHADOWLAB_TECHNIQUES");
    assert_string_equal(origin[2], "source tree");
    assert_string_equal(origin[3], "installed");
    struct sl_tech_set s;
    struct sl_diag d;
    const char *c_names[] = {"nsm", "pcf3", NULL};
    assert_int_equal(sl_tech_set_scan(&s, dirs, origin, n, c_names, &d), SL_OK);
    assert_non_null(sl_tech_find(&s, "twin"));
    assert_string_equal(sl_tech_find(&s, "twin")->origin, "config");
    assert_non_null(sl_tech_find(&s, "other"));
    assert_non_null(sl_tech_find(&s, "pcf"));        /* the source tree's */
    assert_non_null(sl_tech_find(&s, "nsm_glsl"));
    assert_string_equal(sl_tech_find(&s, "pcf")->origin, "source tree");
    sl_tech_set_free(&s);
    /* twin again in a folder after a: the same package byte for byte is
     * kept once; a different one is an error naming both files */
    char file[800], tdirs[2][1024];
    snprintf(tdirs[0], sizeof tdirs[0], "%s", a);
    snprintf(tdirs[1], sizeof tdirs[1], "%s/t", root);
    snprintf(dir, sizeof dir, "%s/t/twin", root);
    mkdir(tdirs[1], 0755);
    mkdir(dir, 0755);
    sl_test_write(dir, "technique.yaml", HEAD("twin") MAPS SHADERS);
    sl_test_write(dir, "map.glsl", good_map);
    sl_test_write(dir, "lookup.glsl", good_lookup);
    const char *torigin[2] = {"config", "SHADOWLAB_TECHNIQUES"};
    assert_int_equal(sl_tech_set_scan(&s, tdirs, torigin, 2, c_names, &d), SL_OK);
    assert_int_equal(s.n, 1);
    assert_string_equal(s.t[0].origin, "config");
    sl_tech_set_free(&s);
    sl_test_write(dir, "lookup.glsl", "// changed\n" "float sl_lookup(vec3 w, vec3 n, vec2 uv, float z, float l)\n"
                  "{\n    return 1.0;\n}\n");
    assert_int_equal(sl_tech_set_scan(&s, tdirs, torigin, 2, c_names, &d), SL_E_PACKAGE);
    snprintf(file, sizeof file, "%s/technique.yaml", dir);
    assert_string_equal(d.file, file);
    assert_int_equal(d.line, 1);
    assert_string_equal(d.key, "name");
    snprintf(file, sizeof file, "%s/one/technique.yaml (config)", a);
    assert_non_null(strstr(d.msg, file));
    assert_non_null(strstr(d.msg, "(SHADOWLAB_TECHNIQUES)"));
    assert_int_equal(s.n, 0);
    /* a package named like a C method */
    snprintf(dir, sizeof dir, "%s/c", root);
    mkdir(dir, 0755);
    sl_test_write(dir, "technique.yaml", "# shadows C\nname: nsm\nsummary: x\n" MAPS SHADERS);
    sl_test_write(dir, "map.glsl", good_map);
    sl_test_write(dir, "lookup.glsl", good_lookup);
    char cdirs[1][1024];
    snprintf(cdirs[0], sizeof cdirs[0], "%s", dir);
    assert_int_equal(sl_tech_set_scan(&s, cdirs, origin, 1, c_names, &d), SL_E_PACKAGE);
    assert_int_equal(d.line, 2);
    assert_string_equal(d.key, "name");
    assert_int_equal(s.n, 0);
}

/* ---- GL ---- */

/* One context at a time: the cases without a scene share this one, the
 * rendered case opens the fixture's after closing it. */
static struct sl_gl gl;
static int gl_is_open;
static int gl_open(void)
{
    struct sl_diag d;
    if (gl_is_open)
        return 1;
    if (sl_gl_init(&gl, &d)) {
        fprintf(stderr, "gl: %s\n", d.msg);
        return 0;
    }
    gl_is_open = 1;
    return 1;
}

static void gl_close(void)
{
    if (gl_is_open)
        sl_gl_free(&gl);
    gl_is_open = 0;
}

static void technique_glsl_error(void **st)
{
    (void)st;
    assert_true(gl_open());
    char dir[600];
    package(dir, sizeof dir, "glsl_bad", HEAD("glsl_bad") MAPS SHADERS,
            "float sl_lookup(vec3 w, vec3 n, vec2 uv, float z, float ndotl)\n"
            "{\n"
            "    float x = 1.0;\n"
            "    return x + undeclared_name;\n"
            "}\n");
    struct sl_technique t;
    struct sl_diag d;
    assert_int_equal(sl_tech_load(dir, &t, &d), SL_OK);
    struct sl_techpass p;
    enum sl_err e = sl_techpass_init(&p, &t, &d);
    char text[1200];
    sl_diag_format(&d, e, text, sizeof text);
    fprintf(stderr, "  %s\n", text);
    assert_int_equal(e, SL_E_PACKAGE);
    char file[700];
    snprintf(file, sizeof file, "%s/lookup.glsl", dir);
    assert_string_equal(d.file, file);
    assert_int_equal(d.line, 4);
    /* the driver's own words (Mesa: "`undeclared_name' undeclared") name the identifier */
    assert_true(strncmp(d.msg, "GLSL: ", 6) == 0);
    assert_non_null(strstr(d.msg, "undeclared_name"));
    sl_tech_free(&t);
    /* the error after reads of sl_map_pos and sl_home_texel: its own line */
    package(dir, sizeof dir, "late_error_gl", HEAD("late_error_gl") MAPS SHADERS, late_error);
    assert_int_equal(sl_tech_load(dir, &t, &d), SL_OK);
    e = sl_techpass_init(&p, &t, &d);
    sl_diag_format(&d, e, text, sizeof text);
    fprintf(stderr, "  %s\n", text);
    assert_int_equal(e, SL_E_PACKAGE);
    snprintf(file, sizeof file, "%s/lookup.glsl", dir);
    assert_string_equal(d.file, file);
    assert_int_equal(d.line, 6);
    assert_true(strncmp(d.msg, "GLSL: ", 6) == 0);
    assert_non_null(strstr(d.msg, "undeclared_name"));
    sl_tech_free(&t);
    /* the prelude and the harness main draw no word from the driver: a
     * shipped package's log names no line of theirs */
    static const char *const shipped[] = {"nsm", "pcf", "vsm", "esm", "evsm", "msm", "pcss", "vsm_rt", "msm_rt", NULL};
    for (int i = 0; shipped[i]; i++) {
        char pdir[64];
        snprintf(pdir, sizeof pdir, "techniques/%s", shipped[i]);
        assert_int_equal(sl_tech_load(pdir, &t, &d), SL_OK);
        for (int stage = 0; stage < 2; stage++) {
            char *src = sl_techsrc(&t, stage ? SL_TECHSRC_LOOKUP : SL_TECHSRC_MAP);
            assert_non_null(src);
            GLuint sh = glCreateShader(GL_FRAGMENT_SHADER);
            glShaderSource(sh, 1, (const char *const *)&src, NULL);
            glCompileShader(sh);
            GLint ok = 0;
            char log[4096] = "";
            glGetShaderiv(sh, GL_COMPILE_STATUS, &ok);
            glGetShaderInfoLog(sh, (GLsizei)sizeof log, NULL, log);
            glDeleteShader(sh);
            free(src);
            if (log[0])
                fprintf(stderr, "  %s %s log: %s\n", shipped[i], stage ? "lookup" : "map", log);
            assert_true(ok);
            assert_null(strstr(log, "1000"));   /* a prelude line: 1000000 on */
            assert_null(strstr(log, "2000"));   /* the harness main's: 2000000 on */
        }
        sl_tech_free(&t);
    }
    /* the log forms of both drivers */
    const char *mesa = "0:1000003(1): error: in prelude\n1:7(12): error: `q' undeclared\n";
    assert_int_equal(sl_techsrc_log_error("p/l.glsl", mesa, &d), SL_E_PACKAGE);
    assert_int_equal(d.line, 7);
    assert_string_equal(d.msg, "GLSL: error: `q' undeclared");
    assert_int_equal(sl_techsrc_log_error("p/l.glsl", "0:2000004(3): error: no function sl_lookup\n", &d),
                     SL_E_PACKAGE);
    assert_int_equal(d.line, 0);   /* the harness main's: the package file named, no line */
    assert_int_equal(sl_techsrc_log_error("p/l.glsl", "1(9) : error C1008: undefined variable \"q\"\n", &d),
                     SL_E_PACKAGE);
    assert_int_equal(d.line, 9);
    assert_string_equal(d.msg, "GLSL: error C1008: undefined variable \"q\"");
}

/* The log of a compile read back: errors first (every one, up to four),
 * then warnings, each at its line of the package file. */
static void technique_log_order(void **st)
{
    (void)st;
    struct sl_diag d;
    const char *mesa = "0:1000003(1): warning: in prelude\n"
                       "1:58(12): warning: `sl_map_pos' used uninitialized\n"
                       "1:67(5): error: `q' undeclared\n"
                       "1:70(5): error: `r' undeclared\n";
    assert_int_equal(sl_techsrc_log_error("p/l.glsl", mesa, &d), SL_E_PACKAGE);
    assert_int_equal(d.line, 67);
    assert_string_equal(d.msg, "GLSL: error: `q' undeclared; line 70: error: `r' undeclared; "
                               "line 58: warning: `sl_map_pos' used uninitialized");
    const char *glslang = "WARNING: 1:3: 'x' : something\nERROR: 1:6: 'undeclared_name' : undeclared identifier\n"
                          "ERROR: 1:6: '' : compilation terminated\nERROR: 2 compilation errors.  No code generated.\n";
    assert_int_equal(sl_techsrc_log_error("p/l.glsl", glslang, &d), SL_E_PACKAGE);
    assert_int_equal(d.line, 6);
    assert_string_equal(d.msg, "GLSL: error: 'undeclared_name' : undeclared identifier; line 3: warning: 'x' : "
                               "something");
}

/* glslang, no GL: an error on line 6 after lines reading sl_map_pos and
 * sl_home_texel is reported at line 6 of the lookup; a typo in the map
 * shader at its line; a missing sl_lookup (the harness main's call) names
 * the file; every shipped package compiles. */
static void technique_glslang(void **st)
{
    (void)st;
    char dir[600], file[700];
    struct sl_technique t;
    struct sl_diag d;
    package(dir, sizeof dir, "late_error", HEAD("late_error") MAPS SHADERS, late_error);
    assert_int_equal(sl_tech_load(dir, &t, &d), SL_OK);
    enum sl_err e = sl_techcheck(&t, &d);
    char text[1200];
    sl_diag_format(&d, e, text, sizeof text);
    fprintf(stderr, "  %s\n", text);
    assert_int_equal(e, SL_E_PACKAGE);
    snprintf(file, sizeof file, "%s/lookup.glsl", dir);
    assert_string_equal(d.file, file);
    assert_int_equal(d.line, 6);
    assert_non_null(strstr(d.msg, "undeclared_name"));
    sl_tech_free(&t);
    package(dir, sizeof dir, "typo", HEAD("typo") MAPS SHADERS, NULL);
    sl_test_write(dir, "map.glsl", "void sl_map(float z)\n{\n    out_depth = vec4(z)\n}\n");   /* no ';' */
    assert_int_equal(sl_tech_load(dir, &t, &d), SL_OK);
    assert_int_equal(sl_techcheck(&t, &d), SL_E_PACKAGE);
    snprintf(file, sizeof file, "%s/map.glsl", dir);
    assert_string_equal(d.file, file);
    assert_true(d.line == 3 || d.line == 4);
    sl_tech_free(&t);
    package(dir, sizeof dir, "no_lookup", HEAD("no_lookup") MAPS SHADERS, "float other(float x) { return x; }\n");
    assert_int_equal(sl_tech_load(dir, &t, &d), SL_OK);
    assert_int_equal(sl_techcheck(&t, &d), SL_E_PACKAGE);
    snprintf(file, sizeof file, "%s/lookup.glsl", dir);
    assert_string_equal(d.file, file);
    fprintf(stderr, "  no sl_lookup: %s\n", d.msg);
    sl_tech_free(&t);
    static const char *const shipped[] = {"nsm", "pcf", "vsm", "esm", "evsm", "msm", "pcss", "vsm_rt", "msm_rt", NULL};
    for (int i = 0; shipped[i]; i++) {
        snprintf(dir, sizeof dir, "techniques/%s", shipped[i]);
        assert_int_equal(sl_tech_load(dir, &t, &d), SL_OK);
        e = sl_techcheck(&t, &d);
        if (e)
            fprintf(stderr, "  %s: %s:%d %s\n", shipped[i], d.file, d.line, d.msg);
        assert_int_equal(e, SL_OK);
        sl_tech_free(&t);
    }
}

/* A light frame of S x S texels over world x, y in [0, S): texel (i, j) is
 * the unit square at (i, j), window depth = world z (orthographic, w = 1). */
static void hand_frame(struct sl_light_frame *f, int S)
{
    memset(f, 0, sizeof *f);
    f->size = S;
    glm_mat4_identity(f->box.vp);
    f->box.vp[0][0] = 2.0f / (float)S;
    f->box.vp[1][1] = 2.0f / (float)S;
    f->box.vp[3][0] = -1.0f;
    f->box.vp[3][1] = -1.0f;
    f->dir[2] = 1.0f;
    f->texel_world = 1.0f;
    f->depth_range = 1.0f;
}

/* Look up points (x, y, z) in the package at dir with values set by
 * name=value pairs (NULL-terminated), over maps given as depth[S + 2g]^2
 * from a function of the frame's texel. */
struct hand { float x, y, z; };
static void hand_lookup(const char *dir, const char *const *set, const double *vals, float (*texel)(int i, int j),
                        const struct hand *pts, int np, const uint8_t *mask, float *vis)
{
    struct sl_technique t;
    struct sl_diag d;
    assert_int_equal(sl_tech_load(dir, &t, &d), SL_OK);
    struct sl_params v;
    sl_tech_defaults(&t, &v);
    for (int i = 0; set && set[i]; i++)
        assert_int_equal(sl_params_put(&v, set[i], vals[i], &d), SL_OK);
    struct sl_techpass p;
    if (sl_techpass_init(&p, &t, &d))
        fprintf(stderr, "%s:%d: %s\n", d.file, d.line, d.msg);
    assert_int_equal(sl_techpass_init(&p, &t, &d), SL_OK);
    struct sl_light_frame f;
    hand_frame(&f, 8);
    int g, N;
    assert_int_equal(sl_techpass_size(&p, &f, &v, &g, &N, &d), SL_OK);
    assert_int_equal(N, 8 + 2 * g);
    float *tex = malloc(sizeof(float) * (size_t)N * (size_t)N);
    for (int j = 0; j < N; j++)
        for (int i = 0; i < N; i++)
            tex[j * N + i] = texel(i - g, j - g);
    const float *maps[1] = {tex};
    assert_int_equal(sl_techpass_upload(&p, &f, &v, maps, &d), SL_OK);
    float *pos = calloc((size_t)np * 3, sizeof(float)), *nrm = calloc((size_t)np * 3, sizeof(float));
    for (int i = 0; i < np; i++) {
        pos[3 * i] = pts[i].x;
        pos[3 * i + 1] = pts[i].y;
        pos[3 * i + 2] = pts[i].z;
        nrm[3 * i + 2] = -1.0f;
    }
    assert_int_equal(sl_techpass_lookup(&p, &f, &v, pos, nrm, mask, np, 1, vis, &d), SL_OK);
    assert_int_equal(p.costs.guard, g);
    assert_int_equal(p.costs.map_size, N);
    free(pos);
    free(nrm);
    free(tex);
    sl_techpass_free(&p);
    sl_tech_free(&t);
}

/* texel (3, 5) at depth 0.5, every other empty */
static float one_texel(int i, int j)
{
    return i == 3 && j == 5 ? 0.5f : 1.0f;
}

/* around texel (3, 5): (2, 4), (3, 4), (4, 6) nearer (0.5), the rest at 0.9 */
static float three_of_nine(int i, int j)
{
    if ((i == 2 && j == 4) || (i == 3 && j == 4) || (i == 4 && j == 6))
        return 0.5f;
    return 0.9f;
}

static void technique_upload_lookups(void **st)
{
    (void)st;
    assert_true(gl_open());
    const struct hand pts[5] = {
        {3.5f, 5.5f, 0.4f},    /* in front of the texel: lit */
        {3.5f, 5.5f, 0.6f},    /* behind it: shadowed */
        {3.01f, 5.99f, 0.6f},  /* the same texel near its corner */
        {1.5f, 1.5f, 0.99f},   /* an empty texel: lit */
        {4.0f, 5.5f, 0.6f},    /* on the next texel's edge: that texel (floor), empty */
    };
    float vis[5];
    hand_lookup("techniques/nsm", NULL, NULL, one_texel, pts, 5, NULL, vis);
    const float want[5] = {1, 0, 0, 1, 1};
    for (int i = 0; i < 5; i++)
        assert_true(vis[i] == want[i]);
    /* pcf with kernel 1 is nsm (its guard band of 1 texel shifts the texels) */
    const char *k1[] = {"kernel", "bias", NULL};
    const double one[] = {1, 0};
    hand_lookup("techniques/pcf", k1, one, one_texel, pts, 5, NULL, vis);
    for (int i = 0; i < 5; i++)
        assert_true(vis[i] == want[i]);
    /* pcf 3x3: 3 of the 9 texels nearer than the point: 6/9 lit */
    const struct hand at[2] = {{3.5f, 5.5f, 0.6f}, {3.5f, 5.5f, 0.4f}};
    const char *b0[] = {"bias", NULL};
    const double zero[] = {0};
    hand_lookup("techniques/pcf", b0, zero, three_of_nine, at, 2, NULL, vis);
    assert_float_equal(vis[0], 6.0f / 9.0f, 1e-6f);
    assert_true(vis[1] == 1.0f);
    /* a mask: the first point skipped (0), the second looked up */
    const uint8_t mask[2] = {0, 1};
    hand_lookup("techniques/nsm", NULL, NULL, one_texel, pts, 2, mask, vis);
    assert_true(vis[0] == 0.0f);
    assert_true(vis[1] == 0.0f);
    hand_lookup("techniques/nsm", NULL, NULL, one_texel, pts, 2, NULL, vis);
    assert_true(vis[0] == 1.0f);
    /* the Poisson disc over empty texels: lit; over the nearer texel alone
     * with kernel 1 (radius 0.5 around the texel's centre): all taps in it */
    const char *pk[] = {"poisson", "kernel", "bias", NULL};
    const double pv[] = {1, 1, 0};
    hand_lookup("techniques/pcf", pk, pv, one_texel, pts, 4, NULL, vis);
    assert_true(vis[0] == 1.0f && vis[1] == 0.0f && vis[3] == 1.0f);
}

/* Post passes, formats, several maps, a float uniform: a package of two
 * maps, m1 (rg32f, blurred by `radius`) and m2 (rgba16f, linear, mipmaps). */
static void post_fill(int map, int i, int j, float *out)
{
    if (map == 0) {            /* g = 1 at the frame's texel (3, 5), else 0 */
        out[0] = 0.0f;
        out[1] = i == 3 && j == 5 ? 1.0f : 0.0f;
    } else {                   /* b = 0.25 everywhere */
        out[0] = out[1] = out[3] = 0.0f;
        out[2] = 0.25f;
    }
}

static void post_lookup(const char *dir, int radius, int which, double gain, const struct hand *pts, int np,
                        float *vis)
{
    struct sl_technique t;
    struct sl_diag d;
    assert_int_equal(sl_tech_load(dir, &t, &d), SL_OK);
    struct sl_params v;
    sl_tech_defaults(&t, &v);
    assert_int_equal(sl_params_put(&v, "radius", radius, &d), SL_OK);
    assert_int_equal(sl_params_put(&v, "which", which, &d), SL_OK);
    assert_int_equal(sl_params_put(&v, "gain", gain, &d), SL_OK);
    struct sl_techpass p;
    enum sl_err e = sl_techpass_init(&p, &t, &d);
    if (e)
        fprintf(stderr, "%s:%d: %s\n", d.file, d.line, d.msg);
    assert_int_equal(e, SL_OK);
    struct sl_light_frame f;
    hand_frame(&f, 8);
    int g, N;
    assert_int_equal(sl_techpass_size(&p, &f, &v, &g, &N, &d), SL_OK);
    assert_int_equal(g, radius);   /* reach 0 + the blur radius */
    const int ch[2] = {2, 4};
    float *tex[2];
    for (int m = 0; m < 2; m++) {
        tex[m] = calloc((size_t)N * (size_t)N * (size_t)ch[m], sizeof(float));
        for (int j = 0; j < N; j++)
            for (int i = 0; i < N; i++)
                post_fill(m, i - g, j - g, tex[m] + ((size_t)j * (size_t)N + (size_t)i) * (size_t)ch[m]);
    }
    const float *maps[2] = {tex[0], tex[1]};
    assert_int_equal(sl_techpass_upload(&p, &f, &v, maps, &d), SL_OK);
    float *pos = calloc((size_t)np * 3, sizeof(float)), *nrm = calloc((size_t)np * 3, sizeof(float));
    for (int i = 0; i < np; i++) {
        pos[3 * i] = pts[i].x;
        pos[3 * i + 1] = pts[i].y;
        pos[3 * i + 2] = pts[i].z;
        nrm[3 * i + 2] = -1.0f;
    }
    assert_int_equal(sl_techpass_lookup(&p, &f, &v, pos, nrm, NULL, np, 1, vis, &d), SL_OK);
    free(pos);
    free(nrm);
    free(tex[0]);
    free(tex[1]);
    sl_techpass_free(&p);
    sl_tech_free(&t);
}

static void technique_post_passes(void **st)
{
    (void)st;
    assert_true(gl_open());
    char dir[600];
    package(dir, sizeof dir, "posts",
            HEAD("posts")
            "maps:\n"
            "  - {name: m1, format: rg32f, post: blur, blur: radius}\n"
            "  - {name: m2, format: rgba16f, filter: linear, post: mipmaps}\n"
            SHADERS
            "params:\n"
            "  - {name: radius, type: int, default: 1, min: 0, max: 4}\n"
            "  - {name: which, type: int, default: 0, min: 0, max: 1}\n"
            "  - {name: gain, type: float, default: 1.0, min: 0, max: 10}\n",
            "float sl_lookup(vec3 w, vec3 n, vec2 uv, float z, float ndotl)\n"
            "{\n"
            "    ivec2 t = clamp(sl_home_texel, ivec2(0), textureSize(m1, 0) - 1);\n"
            "    if (which == 0)\n"
            "        return gain * texelFetch(m1, t, 0).g;\n"
            "    return gain * textureLod(m2, uv, 10.0).b;   // the top mip level: the mean\n"
            "}\n");
    sl_test_write(dir, "map.glsl", "void sl_map(float z)\n{\n    out_m1 = vec4(z);\n    out_m2 = vec4(z);\n}\n");
    const struct hand pts[4] = {
        {3.5f, 5.5f, 0.5f},   /* the texel itself */
        {4.5f, 6.5f, 0.5f},   /* a diagonal neighbour: inside the 3 x 3 box */
        {5.5f, 5.5f, 0.5f},   /* two texels off: outside it */
        {0.5f, 0.5f, 0.5f},   /* a corner of the frame, the guard band beyond */
    };
    float vis[4];
    post_lookup(dir, 1, 0, 1.0, pts, 4, vis);
    assert_float_equal(vis[0], 1.0f / 9.0f, 1e-6f);
    assert_float_equal(vis[1], 1.0f / 9.0f, 1e-6f);
    assert_true(vis[2] == 0.0f && vis[3] == 0.0f);
    post_lookup(dir, 1, 0, 2.0, pts, 4, vis);   /* the float uniform */
    assert_float_equal(vis[0], 2.0f / 9.0f, 1e-6f);
    post_lookup(dir, 2, 0, 1.0, pts, 4, vis);   /* 5 x 5 */
    assert_float_equal(vis[0], 1.0f / 25.0f, 1e-6f);
    assert_float_equal(vis[2], 1.0f / 25.0f, 1e-6f);
    post_lookup(dir, 0, 0, 1.0, pts, 4, vis);   /* radius 0: no blur */
    assert_true(vis[0] == 1.0f && vis[1] == 0.0f);
    post_lookup(dir, 1, 1, 1.0, pts, 4, vis);   /* the mipmaps of m2 */
    for (int i = 0; i < 4; i++)
        assert_float_equal(vis[i], 0.25f, 1e-6f);
}

static void technique_map_too_big(void **st)
{
    (void)st;
    assert_true(gl_open());
    struct sl_technique t;
    struct sl_diag d;
    assert_int_equal(sl_tech_load("techniques/pcf", &t, &d), SL_OK);
    struct sl_params v;
    sl_tech_defaults(&t, &v);
    struct sl_techpass p;
    assert_int_equal(sl_techpass_init(&p, &t, &d), SL_OK);
    struct sl_light_frame f;
    hand_frame(&f, 16384);
    int g, N;
    assert_int_equal(sl_techpass_size(&p, &f, &v, &g, &N, &d), SL_E_METHOD);
    assert_string_equal(d.key, "kernel");
    sl_techpass_free(&p);
    sl_tech_free(&t);
}

/* A package (nsm_glsl's shaders) rendered over a scene against the C depth
 * layer `layer`, every pixel: differences at most max_differ. set/set_vals:
 * parameter values (NULL-terminated names). */
static void rendered_case(const char *scene, int S, const char *pkg, int layer, const char *const *set,
                          const double *set_vals, size_t max_differ)
{
    gl_close();
    /* the fixture's context, mesh and G-buffer; no truth (nothing here traces) */
    struct fixture fx;
    struct sl_diag d;
    memset(&fx, 0, sizeof fx);
    enum sl_err fe = sl_scene_build(scene, &fx.scene, &d);
    if (!fe)
        fe = sl_gl_init(&fx.gl, &d);
    if (!fe)
        fe = sl_gl_mesh_upload(&fx.mesh, &fx.scene, &d);
    if (!fe)
        fe = sl_gbuffer_init(&fx.gp, &fx.scene, &d);
    if (fe)
        fprintf(stderr, "%s: %s\n", scene, d.msg);
    assert_int_equal(fe, SL_OK);
    struct sl_view v;
    assert_int_equal(sl_gbuffer_render(&fx.gp, &fx.mesh, &fx.scene, 0, 192, 160, &v, NULL, NULL, NULL, &d), SL_OK);
    struct sl_light_frame fr;
    memset(&fr, 0, sizeof fr);
    fr.size = S;
    memcpy(fr.dir, fx.scene.light_dir, sizeof fr.dir);
    sl_light_fit(&fx.scene, &v, &fr.box);
    fr.texel_world = fmaxf(fr.box.hi[0] - fr.box.lo[0], fr.box.hi[1] - fr.box.lo[1]) / (float)fr.size;
    fr.depth_range = fr.box.hi[2] - fr.box.lo[2];
    struct sl_shadowmap_pass sp;
    assert_int_equal(sl_shadowmap_init(&sp, &d), SL_OK);
    assert_int_equal(sl_shadowmap_render(&sp, &fx.mesh, &fr, SL_NEED(layer), &d), SL_OK);
    struct sl_technique t;
    assert_int_equal(sl_tech_load(pkg, &t, &d), SL_OK);
    struct sl_params vals;
    sl_tech_defaults(&t, &vals);
    for (int i = 0; set && set[i]; i++)
        assert_int_equal(sl_params_put(&vals, set[i], set_vals[i], &d), SL_OK);
    struct sl_techpass p;
    assert_int_equal(sl_techpass_init(&p, &t, &d), SL_OK);
    assert_int_equal(sl_techpass_render(&p, &fx.mesh, &fr, &vals, &d), SL_OK);
    const size_t n = (size_t)v.w * (size_t)v.h;
    uint8_t *mask = malloc(n);
    float *vis = malloc(n * sizeof(float));
    size_t looked = 0;
    for (size_t i = 0; i < n; i++) {
        mask[i] = v.cls[i] != SL_C_BACKGROUND;
        looked += mask[i];
    }
    assert_int_equal(sl_techpass_lookup(&p, &fr, &vals, v.pos, v.nrm, mask, v.w, v.h, vis, &d), SL_OK);
    assert_int_equal(p.costs.pixels, looked);
    assert_int_equal(p.costs.lookups, (uint64_t)llround(sl_tech_taps(&t, &vals) * (double)looked));
    assert_int_equal(p.costs.guard, sl_tech_guard(&t, &vals));
    assert_int_equal(p.costs.map_size, S + 2 * sl_tech_guard(&t, &vals));
    size_t lit = 0, shadowed = 0, differ = 0;
    const float *depth = fr.layer[layer].depth;
    for (size_t i = 0; i < n; i++) {
        if (!mask[i])
            continue;
        float u, w, z;
        sl_frame_project(&fr, v.pos + 3 * i, &u, &w, &z);
        int c_lit = z <= depth[sl_frame_texel(&fr, u, w)];
        lit += c_lit;
        shadowed += !c_lit;
        if ((vis[i] == 1.0f) != c_lit || (vis[i] != 0.0f && vis[i] != 1.0f)) {
            if (differ < 5)
                fprintf(stderr, "  %s pixel %zu: C %s, GLSL %g (u %.9g v %.9g z %.9g stored %.9g)\n", scene, i,
                        c_lit ? "lit" : "shadowed", vis[i], u, w, z, depth[sl_frame_texel(&fr, u, w)]);
            differ++;
        }
    }
    fprintf(stderr, "  %s %s: %zu pixels looked up, %zu lit, %zu shadowed, %zu differ; map %.2f ms, lookup %.2f ms\n",
            t.name, scene, looked, lit, shadowed, differ, p.costs.ms_map, p.costs.ms_lookup);
    assert_true(lit > 100 && shadowed > 100);
    assert_true(differ <= max_differ);
    free(mask);
    free(vis);
    sl_techpass_free(&p);
    sl_tech_free(&t);
    sl_shadowmap_free(&sp);
    sl_light_box_free(&fr.box);
    sl_frame_free(&fr);
    sl_view_free(&v);
    fixture_close(&fx);   /* rt zeroed: its free is a no-op */
}

static void technique_rendered_nsm(void **st)
{
    (void)st;
    rendered_case("primitives", 512, "techniques/nsm", SL_LAYER_DEPTH_ID, NULL, NULL, 0);
    rendered_case("scenes/primitives_spot.yaml", 512, "techniques/nsm", SL_LAYER_DEPTH_ID, NULL, NULL, 0);
    /* front faces culled: the C layer of Moderno's front_faces policy */
    char dir[600];
    snprintf(dir, sizeof dir, "%s/nsm_back", sl_test_dir);
    mkdir(dir, 0755);
    char cmd[1400];
    snprintf(cmd, sizeof cmd, "cp techniques/nsm/*.glsl %s/ && sed 's/^cull: none/cull: front/; "
             "s/^name: nsm_glsl/name: nsm_back/' techniques/nsm/technique.yaml > %s/technique.yaml", dir, dir);
    assert_int_equal(system(cmd), 0);
    rendered_case("primitives", 512, dir, SL_LAYER_DEPTH_ID_BACK, NULL, NULL, 0);
    rendered_case("scenes/trees.yaml", 512, dir, SL_LAYER_DEPTH_ID_BACK, NULL, NULL, 0);
}

/* pcf with kernel 1 and bias 0, rendered: its reach is 0 ((kernel - 1) / 2),
 * so no guard band and the frame's own matrix: the C depth layer's texel
 * and depth at every point, as the nsm package. */
static void technique_rendered_pcf(void **st)
{
    (void)st;
    const char *k1[] = {"kernel", "bias", NULL};
    const double one[] = {1, 0};
    rendered_case("primitives", 512, "techniques/pcf", SL_LAYER_DEPTH_ID, k1, one, 0);
}

/* The package's maps (level 0 of each, guard band included) and its
 * visibility over the view: tiles of at most max_px pixels, or one tile a
 * pass (max_px 0: every pass's area set past its target's). */
static void tiled_run(struct fixture *fx, const struct sl_view *v, const struct sl_light_frame *fr,
                      const struct sl_technique *t, const struct sl_params *vals, double max_px, float **maps,
                      float *vis, int *tiles)
{
    struct sl_diag d;
    struct sl_techpass p;
    assert_int_equal(sl_techpass_init(&p, t, &d), SL_OK);
    p.tile_max_px = max_px;
    for (int k = 0; k < SL_TECHPASS_KINDS && !max_px; k++)
        p.tile_px[k] = 1e18;
    assert_int_equal(sl_techpass_render(&p, &fx->mesh, fr, vals, &d), SL_OK);
    const int N = p.size;
    for (int i = 0; i < t->nmaps; i++) {
        maps[i] = malloc((size_t)N * (size_t)N * 4 * sizeof(float));
        glGetTextureImage(p.map_tex[i], 0, GL_RGBA, GL_FLOAT, (GLsizei)((size_t)N * N * 4 * sizeof(float)), maps[i]);
    }
    assert_int_equal(sl_techpass_lookup(&p, fr, vals, v->pos, v->nrm, NULL, v->w, v->h, vis, &d), SL_OK);
    *tiles = p.tiles;
    sl_techpass_free(&p);
}

/* Tiles change nothing: msm (four channels, blur, mipmaps) and pcss (a
 * blocker search over many texels) drawn in tiles of 64 pixels (the map
 * pass's scene drawn again in each) and in one tile a pass give the same
 * bits in every map texel and every visibility. */
static void technique_tiles(void **st)
{
    (void)st;
    gl_close();
    struct fixture fx;
    struct sl_diag d;
    memset(&fx, 0, sizeof fx);
    assert_int_equal(sl_scene_build("primitives", &fx.scene, &d), SL_OK);
    assert_int_equal(sl_gl_init(&fx.gl, &d), SL_OK);
    assert_int_equal(sl_gl_mesh_upload(&fx.mesh, &fx.scene, &d), SL_OK);
    assert_int_equal(sl_gbuffer_init(&fx.gp, &fx.scene, &d), SL_OK);
    struct sl_view v;
    assert_int_equal(sl_gbuffer_render(&fx.gp, &fx.mesh, &fx.scene, 0, 96, 80, &v, NULL, NULL, NULL, &d), SL_OK);
    struct sl_light_frame fr;
    memset(&fr, 0, sizeof fr);
    fr.size = 128;
    memcpy(fr.dir, fx.scene.light_dir, sizeof fr.dir);
    sl_light_fit(&fx.scene, &v, &fr.box);
    fr.texel_world = fmaxf(fr.box.hi[0] - fr.box.lo[0], fr.box.hi[1] - fr.box.lo[1]) / (float)fr.size;
    fr.depth_range = fr.box.hi[2] - fr.box.lo[2];
    const char *pkgs[] = {"techniques/msm", "techniques/pcss"};
    const size_t n = (size_t)v.w * (size_t)v.h;
    for (int k = 0; k < 2; k++) {
        struct sl_technique t;
        assert_int_equal(sl_tech_load(pkgs[k], &t, &d), SL_OK);
        struct sl_params vals;
        sl_tech_defaults(&t, &vals);
        const int blur = !isnan(sl_params_get(&vals, "blur"));
        if (blur)
            assert_int_equal(sl_params_put(&vals, "blur", 2, &d), SL_OK);
        float *maps[2][SL_TECH_MAX_MAPS] = {{0}}, *vis[2];
        int tiles[2];
        for (int r = 0; r < 2; r++) {
            vis[r] = malloc(n * sizeof(float));
            tiled_run(&fx, &v, &fr, &t, &vals, r ? 64.0 : 0.0, maps[r], vis[r], &tiles[r]);
        }
        const int N = fr.size + 2 * sl_tech_guard(&t, &vals);
        size_t mdiff = 0, vdiff = 0;
        for (int i = 0; i < t.nmaps; i++)
            mdiff += memcmp(maps[0][i], maps[1][i], (size_t)N * N * 4 * sizeof(float)) != 0;
        vdiff = memcmp(vis[0], vis[1], n * sizeof(float)) != 0;
        fprintf(stderr, "  %s: %d tiles against %d, maps differ: %zu, visibility differs: %zu\n", t.name, tiles[1],
                tiles[0], mdiff, vdiff);
        assert_int_equal(tiles[0], 3 + (blur ? 2 * t.nmaps : 0));
        assert_true(tiles[1] > 100);
        assert_int_equal(mdiff, 0);
        assert_int_equal(vdiff, 0);
        for (int r = 0; r < 2; r++) {
            for (int i = 0; i < t.nmaps; i++)
                free(maps[r][i]);
            free(vis[r]);
        }
        sl_tech_free(&t);
    }
    sl_light_box_free(&fr.box);
    sl_frame_free(&fr);
    sl_view_free(&v);
    fixture_close(&fx);
}

int main(int argc, char **argv)
{
    const struct CMUnitTest tests[] = {
        SL_CASE(technique, loader_errors),
        SL_CASE(technique, shipped),
        SL_CASE(technique, trace_band),
        SL_CASE(technique, set_scan),
        SL_CASE(technique, glsl_error),
        SL_CASE(technique, log_order),
        SL_CASE(technique, glslang),
        SL_CASE(technique, upload_lookups),
        SL_CASE(technique, post_passes),
        SL_CASE(technique, map_too_big),
        SL_CASE(technique, rendered_nsm),
        SL_CASE(technique, rendered_pcf),
        SL_CASE(technique, tiles),
    };
    int r = sl_run_group(argc, argv, "technique", tests, sl_test_setup, sl_test_teardown);
    gl_close();
    return r;
}
