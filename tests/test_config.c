/* config::* — experiment files: the default loads with every default filled,
 * and each bad file yields its error id, line and key. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <cmocka.h>
#include "sl_test.h"

#include "config.h"
#include "reps.h"
#include "method.h"
#include "package.h"
#include "session.h"

/* a label's parameter by name (its value set: base/params.h) */
#define PV(cm, name) sl_params_get(&(cm).params.values, name)

static void config_default_loads(void **st)
{
    (void)st;
    struct sl_config c;
    struct sl_diag d;
    assert_int_equal(sl_config_load("configs/default.yaml", &c, &d), SL_OK);
    assert_int_equal(c.nscenes, 1);
    assert_string_equal(c.scenes[0].name, "primitives");
    assert_int_equal(c.scenes[0].nviewpoints, 3);
    assert_string_equal(c.scenes[0].viewpoints[2], "against");
    /* the default repetitions (reps.h): default.yaml gives none */
    assert_int_equal(c.rep_mode, SL_REP_ADAPTIVE);
    assert_int_equal(c.runs, 5);
    assert_int_equal(c.warmup, 1);
    assert_int_equal(c.nmaps, 2);
    assert_int_equal(c.maps[0], 1024);
    assert_int_equal(c.maps[1], 2048);
    assert_int_equal(c.nregions, 4);
    assert_int_equal(c.regions[3], 0);
    assert_int_equal(c.nmethods, 1);
    assert_string_equal(c.methods[0].method->name, "nsm");
    assert_int_equal(PV(c.methods[0], "self_shadow"), SL_SELF_FRONT_FACES);
    assert_true(c.threads >= 1);
    sl_config_free(&c);
}

/* The filled-in config written beside results reads back to the same plan. */
static void config_written_reads_back(void **st)
{
    (void)st;
    struct sl_config a, b;
    struct sl_diag d;
    assert_int_equal(sl_config_load("configs/default.yaml", &a, &d), SL_OK);
    char path[] = "/tmp/shadowlab-config-XXXXXX.yaml";
    int fd = mkstemps(path, 5);
    assert_true(fd >= 0);
    FILE *f = fdopen(fd, "w");
    sl_config_write(&a, f);
    fclose(f);
    assert_int_equal(sl_config_load(path, &b, &d), SL_OK);
    remove(path);
    assert_string_equal(a.scenes[0].path, b.scenes[0].path);
    assert_int_equal(a.scenes[0].nviewpoints, b.scenes[0].nviewpoints);
    assert_int_equal(a.nmaps, b.nmaps);
    assert_int_equal(a.nregions, b.nregions);
    assert_int_equal(a.nmethods, b.nmethods);
    assert_memory_equal(&a.methods[0].params, &b.methods[0].params, sizeof a.methods[0].params);
    sl_config_free(&a);
    sl_config_free(&b);
}

struct bad_case { const char *file; enum sl_err err; int line; const char *key; const char *msg_part; };

static const struct bad_case bad_cases[] = {
    {"tests/bad/unknown_key.yaml", SL_E_CONFIG, 5, "contour", "unknown key"},
    {"tests/bad/wrong_type.yaml", SL_E_CONFIG, 2, "map_sizes[1]", "big"},
    {"tests/bad/unknown_method.yaml", SL_E_CONFIG, 7, "methods[1].method", "perfect_shadows"},
    {"tests/bad/unknown_scene.yaml", SL_E_CONFIG, 2, "scenes[0].scene", "cathedral"},
    {"tests/bad/bad_map_size.yaml", SL_E_CONFIG, 4, "map_sizes[1]", "power of two"},
    {"tests/bad/unknown_viewpoint.yaml", SL_E_CONFIG, 2, "scenes[0].viewpoints[1]", "behind"},
    {"tests/bad/bad_param.yaml", SL_E_CONFIG, 7, "methods[0].bias", "front_faces"},
    {"tests/bad/unknown_policy.yaml", SL_E_CONFIG, 6, "methods[0].self_shadow", "magic"},
    {"tests/bad/duplicate_label.yaml", SL_E_CONFIG, 5, "methods[1].label", "used twice"},
    {"tests/bad/odd_contour.yaml", SL_E_CONFIG, 3, "contours[1]", "even"},
    {"tests/bad/syntax.yaml", SL_E_CONFIG, 0, NULL, ""},
    {"tests/bad/missing_methods.yaml", SL_E_CONFIG, 0, "methods", "missing required key"},
    {"tests/bad/soft_three_layers_hierarchical.yaml", SL_E_CONFIG, 6, "methods[0].layers", "search: linear"},
    {"tests/bad/no_such_file.yaml", SL_E_IO, 0, NULL, "cannot read"},
};

static void config_bad_inputs(void **st)
{
    (void)st;
    for (size_t i = 0; i < sizeof bad_cases / sizeof bad_cases[0]; i++) {
        const struct bad_case *bc = &bad_cases[i];
        struct sl_config c;
        struct sl_diag d;
        enum sl_err e = sl_config_load(bc->file, &c, &d);
        char line[1200];
        sl_diag_format(&d, e, line, sizeof line);
        printf("config::bad %s -> %s\n", bc->file, line);
        assert_int_equal(e, bc->err);
        assert_string_equal(d.file, bc->file);
        if (bc->line)
            assert_int_equal(d.line, bc->line);
        if (bc->key)
            assert_string_equal(d.key, bc->key);
        assert_non_null(strstr(d.msg, bc->msg_part));
        sl_config_free(&c);   /* a failed load holds nothing; one that passes must be freed */
    }
}

/* A syntax error still names a line. */
static void config_syntax_error_has_line(void **st)
{
    (void)st;
    struct sl_config c;
    struct sl_diag d;
    assert_int_equal(sl_config_load("tests/bad/syntax.yaml", &c, &d), SL_E_CONFIG);
    assert_true(d.line >= 2 && d.line <= 3);
    sl_config_free(&c);
}

/* -D overrides: applied by key path, checked as the file is, the error naming
 * the override; the hash follows the overrides. */
static void config_overrides(void **st)
{
    (void)st;
    struct sl_config a, b, c;
    struct sl_diag d;
    assert_int_equal(sl_config_load("configs/default.yaml", &a, &d), SL_OK);
    const char *ok[] = {"map_sizes=[512, 1024, 4096]", "methods[0].self_shadow=slope", "methods[0].bias=0.01",
                        "viewports=[{width: 256, height: 128}]", "outputs.exr=true", "threads=3"};
    assert_int_equal(sl_config_load_with("configs/default.yaml", ok, 6, &b, &d), SL_OK);
    assert_int_equal(b.nmaps, 3);
    assert_int_equal(b.maps[2], 4096);
    assert_int_equal(PV(b.methods[0], "self_shadow"), SL_SELF_SLOPE);
    assert_true(PV(b.methods[0], "bias") > 0.0099f && PV(b.methods[0], "bias") < 0.0101f);
    assert_int_equal(b.viewport_w[0], 256);
    assert_int_equal(b.viewport_h[0], 128);
    assert_int_equal(b.exr, 1);
    assert_int_equal(b.threads, 3);
    assert_string_equal(b.path, "configs/default.yaml");
    assert_true(a.hash != b.hash);
    assert_int_equal(sl_config_load_with("configs/default.yaml", ok, 6, &c, &d), SL_OK);
    assert_true(b.hash == c.hash);   /* the same overrides: the same study (--resume finds it) */
    sl_config_free(&c);
    assert_int_equal(sl_config_load_with("configs/default.yaml", NULL, 0, &c, &d), SL_OK);
    assert_true(a.hash == c.hash);
    static const struct { const char *ov, *key, *msg; } bad[] = {
        {"map_sizes=[100]", "map_sizes[0]", "power of two"},
        {"methods[0].bias=0.01", "methods[0].bias", "bias applies to"},
        {"methods[3].bias=1", "methods[3].bias", "has 1 entry"},
        {"seed=-1", "seed", ""},
        {"frobnicate=1", "frobnicate", "unknown key"},
        {"scenes[0].scene=nope", "scenes[0].scene", "unknown scene 'nope'"},
        {"name=[", "name", "not YAML"},
        {"map_sizes.x=1", "map_sizes.x", "not a mapping"},
        {"seed=7.9", "seed", "'7.9' is not a whole number"},
        {"methods[0].bias=[]", "methods[0].bias", "an empty list sweeps nothing"},
        {"repetitions.runs=0", "repetitions.runs", "0 is outside [1, 1000]"},
        {"methods[0]={label: x}", "methods[0].method", "missing required key"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        memset(&d, 0, sizeof d);
        sl_config_free(&c);
        assert_int_not_equal(sl_config_load_with("configs/default.yaml", &bad[i].ov, 1, &c, &d), SL_OK);
        char src[200];
        snprintf(src, sizeof src, "-D %s", bad[i].ov);
        assert_string_equal(d.file, src);
        assert_string_equal(d.key, bad[i].key);
        assert_non_null(strstr(d.msg, bad[i].msg));
        assert_int_equal(d.line, 0);   /* the override has no line of the file */
    }
    /* a key the file lacks is created (default.yaml gives no repetitions) */
    const char *mk[] = {"repetitions.runs=5"};
    sl_config_free(&c);
    assert_int_equal(sl_config_load_with("configs/default.yaml", mk, 1, &c, &d), SL_OK);
    assert_int_equal(c.runs, 5);
    assert_int_equal(c.warmup, 1);
    /* a sweep given by -D: one label per value */
    const char *sw[] = {"methods[0].self_shadow=slope", "methods[0].bias=[0.01, 0.02]"};
    sl_config_free(&c);
    assert_int_equal(sl_config_load_with("configs/default.yaml", sw, 2, &c, &d), SL_OK);
    assert_int_equal(c.nmethods, 2);
    assert_string_equal(c.methods[1].label, "nsm[bias=0.02]");
    /* the file's own error under -D keeps the file's line and name */
    const char *other[] = {"seed=3", "methods[0].self_shadow=slope"};
    memset(&d, 0, sizeof d);
    sl_config_free(&c);
    assert_int_equal(sl_config_load_with("tests/bad/bad_bias.yaml", other, 2, &c, &d), SL_E_CONFIG);
    assert_string_equal(d.file, "tests/bad/bad_bias.yaml");
    assert_int_equal(d.line, 4);
    assert_string_equal(d.key, "methods[0].bias");
    sl_config_free(&a);
    sl_config_free(&b);
    sl_config_free(&c);
}

/* A config written to a temporary file (the scene resolves by name). */
static void write_tmp(char *path, const char *text)
{
    strcpy(path, "/tmp/shadowlab-sweep-XXXXXX.yaml");
    int fd = mkstemps(path, 5);
    assert_true(fd >= 0);
    FILE *f = fdopen(fd, "w");
    fputs(text, f);
    fclose(f);
}

/* Repetitions left out: adaptive, at most 5 timed runs after the real one
 * (reps.h), written out in full; given, as given. */
static void config_repetitions_default(void **st)
{
    (void)st;
    char path[64];
    write_tmp(path, "name: reps\n"
                    "scenes: [{scene: primitives, viewpoints: [side]}]\n"
                    "map_sizes: [512]\n"
                    "methods: [{label: nsm, method: nsm}]\n");
    struct sl_config c;
    struct sl_diag d;
    memset(&d, 0, sizeof d);
    assert_int_equal(sl_config_load(path, &c, &d), SL_OK);
    assert_int_equal(c.rep_mode, SL_REP_ADAPTIVE);
    assert_int_equal(c.warmup, 1);
    assert_int_equal(c.runs, 5);
    assert_true(c.rep_spread == 0.1 && c.rep_budget_ms == 100.0 && c.rep_share == 0.3);
    char *buf = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&buf, &len);
    sl_config_write(&c, f);
    fclose(f);
    assert_non_null(strstr(buf, "\nrepetitions: {mode: adaptive, warmup: 1, runs: 5, spread: 0.1, budget_ms: 100, "
                                "share: 0.3}\n"));
    free(buf);
    write_tmp(path, "name: reps\n"
                    "scenes: [{scene: primitives, viewpoints: [side]}]\n"
                    "map_sizes: [512]\n"
                    "methods: [{label: nsm, method: nsm}]\n"
                    "repetitions: {mode: fixed, runs: 1}\n");
    sl_config_free(&c);
    assert_int_equal(sl_config_load(path, &c, &d), SL_OK);
    assert_int_equal(c.rep_mode, SL_REP_FIXED);
    assert_int_equal(c.warmup, 1);
    assert_int_equal(c.runs, 1);
    unlink(path);
    sl_config_free(&c);
}

/* Sweeps: a parameter given as a list is one label per value (several lists
 * multiply, the first varying slowest), each with its value; a scene's
 * list names the sweep by its entry's label; the flow mapping's other keys
 * keep their lines (an error after the sweep names its own line). */
static void config_sweeps(void **st)
{
    (void)st;
    char path[64];
    write_tmp(path, "name: sweep\n"
                    "scenes:\n"
                    "  - {scene: primitives, viewpoints: [side], methods: [b, plain]}\n"
                    "map_sizes: [512]\n"
                    "methods:\n"
                    "  - {label: b, method: nsm, self_shadow: constant, bias: [0.5, 1, 2]}\n"
                    "  - label: plain\n"
                    "    method: nsm\n"
                    "    self_shadow: [none, slope]\n"
                    "    slope: [1, 3]\n");
    struct sl_config c;
    struct sl_diag d;
    memset(&d, 0, sizeof d);
    enum sl_err e = sl_config_load(path, &c, &d);
    if (e)
        printf("%s:%d '%s': %s\n", d.file, d.line, d.key, d.msg);
    assert_int_equal(e, SL_E_CONFIG);   /* slope applies to self_shadow slope, not none */
    assert_string_equal(d.key, "methods[1].slope");
    write_tmp(path, "name: sweep\n"
                    "scenes:\n"
                    "  - {scene: primitives, viewpoints: [side], methods: [b, plain]}\n"
                    "map_sizes: [512]\n"
                    "methods:\n"
                    "  - {label: b, method: nsm, self_shadow: constant, bias: [0.5, 1, 2]}\n"
                    "  - label: plain\n"
                    "    method: nsm\n"
                    "    self_shadow: slope\n"
                    "    bias: [0, 0.25]\n"
                    "    slope: [1, 3]\n"
                    "  - {label: c, method: coherence, texels: 4}\n");
    memset(&d, 0, sizeof d);
    sl_config_free(&c);
    e = sl_config_load(path, &c, &d);
    if (e)
        printf("%s:%d '%s': %s\n", d.file, d.line, d.key, d.msg);
    assert_int_equal(e, SL_OK);
    assert_int_equal(c.nmethods, 3 + 4 + 1);
    assert_string_equal(c.methods[0].label, "b[bias=0.5]");
    assert_string_equal(c.methods[2].label, "b[bias=2]");
    assert_true(PV(c.methods[0], "bias") == 0.5f && PV(c.methods[1], "bias") == 1.0f && PV(c.methods[2], "bias") == 2.0f);
    assert_int_equal(PV(c.methods[0], "self_shadow"), SL_SELF_CONSTANT);
    assert_string_equal(c.methods[3].label, "plain[bias=0][slope=1]");
    assert_string_equal(c.methods[4].label, "plain[bias=0][slope=3]");
    assert_string_equal(c.methods[6].label, "plain[bias=0.25][slope=3]");
    assert_true(PV(c.methods[6], "bias") == 0.25f && PV(c.methods[6], "slope") == 3.0f);
    assert_string_equal(c.methods[7].label, "c");
    assert_int_equal(PV(c.methods[7], "texels"), 4);
    /* the scene named both sweeps by their labels: all seven, not c */
    assert_int_equal(c.scenes[0].method_mask, 0x7fu);
    /* the filled-in config names each label, and reads back to the same */
    char back[64];
    strcpy(back, "/tmp/shadowlab-sweep-XXXXXX.yaml");
    int fd = mkstemps(back, 5);
    assert_true(fd >= 0);
    FILE *f = fdopen(fd, "w");
    sl_config_write(&c, f);
    fclose(f);
    struct sl_config b;
    memset(&d, 0, sizeof d);
    e = sl_config_load(back, &b, &d);
    if (e)
        printf("%s:%d '%s': %s\n", d.file, d.line, d.key, d.msg);
    assert_int_equal(e, SL_OK);
    remove(back);
    assert_int_equal(b.nmethods, c.nmethods);
    for (int k = 0; k < c.nmethods; k++) {
        assert_string_equal(b.methods[k].label, c.methods[k].label);
        /* the same values, applying to the same; the written config names
         * every parameter that applies, so what was given is a subset of
         * what reads back as given (a default written out) */
        const struct sl_params *bv = &b.methods[k].params.values, *cv = &c.methods[k].params.values;
        assert_ptr_equal(bv->decl, cv->decl);
        assert_int_equal(bv->n, cv->n);
        assert_memory_equal(bv->v, cv->v, sizeof bv->v);
        assert_int_equal(bv->off, cv->off);
        assert_int_equal(bv->given & cv->given, cv->given);
        assert_ptr_equal(b.methods[k].params.tech, c.methods[k].params.tech);
    }
    /* an error after a blanked flow-mapping key keeps its line */
    write_tmp(path, "name: sweep\n"
                    "scenes:\n"
                    "  - {scene: primitives}\n"
                    "map_sizes: [512]\n"
                    "methods:\n"
                    "  - {label: b, method: nsm, self_shadow: constant, bias: [0.5, x]}\n");
    memset(&d, 0, sizeof d);
    sl_config_free(&c);
    assert_int_equal(sl_config_load(path, &c, &d), SL_E_CONFIG);
    assert_int_equal(d.line, 6);
    assert_string_equal(d.key, "methods[0].bias");
    assert_non_null(strstr(d.msg, "'x'"));
    write_tmp(path, "name: sweep\n"
                    "scenes:\n"
                    "  - {scene: primitives}\n"
                    "map_sizes: [512]\n"
                    "methods:\n"
                    "  - {label: b, method: nsm, self_shadow: constant, bias: [0.5, 1]}\n"
                    "  - {label: q, method: nsm, self_shadow: constant, bias: 1, texels: 4}\n");
    memset(&d, 0, sizeof d);
    sl_config_free(&c);
    assert_int_equal(sl_config_load(path, &c, &d), SL_E_CONFIG);
    assert_int_equal(d.line, 7);
    assert_string_equal(d.key, "methods[1].texels");
    /* a method entry the text never closes (fuzz_config's input): the
     * tree's parse names the syntax error, nothing is bound */
    write_tmp(path, "scenes: [{scene: primitives}]\nmap_sizes: [1024]\nmethods:\n  - label: nsm\n"
                    "    method: nsm\n    stives}]\nmap_sizes: [1024]\nmethods 2.0\n");
    memset(&d, 0, sizeof d);
    sl_config_free(&c);
    assert_int_equal(sl_config_load(path, &c, &d), SL_E_CONFIG);
    remove(path);
    sl_config_free(&b);
    sl_config_free(&c);
}

/* Technique packages (the source tree's techniques/): named like a method,
 * their parameters as keys, checked against the package's declaration at
 * their lines, swept like a C method's; a config's `techniques:` folder adds a
 * package. */
static void config_packages(void **st)
{
    (void)st;
    char path[64];
    write_tmp(path, "name: pk\n"
                    "scenes:\n"
                    "  - {scene: primitives}\n"
                    "map_sizes: [512]\n"
                    "methods:\n"
                    "  - {label: pcf, method: pcf, kernel: [1, 3, 5]}\n"
                    "  - method: pcf\n"
                    "    label: p7\n"
                    "    kernel: 7\n");
    struct sl_config c;
    struct sl_diag d;
    memset(&d, 0, sizeof d);
    enum sl_err e = sl_config_load(path, &c, &d);
    if (e)
        printf("%s:%d '%s': %s\n", d.file, d.line, d.key, d.msg);
    assert_int_equal(e, SL_OK);
    assert_int_equal(c.nmethods, 4);
    assert_string_equal(c.methods[1].label, "pcf[kernel=3]");
    assert_string_equal(c.methods[1].method->name, "pcf");
    assert_non_null(c.methods[1].params.tech);
    int k = sl_param_index(c.methods[1].params.values.decl, c.methods[1].params.values.n, "kernel");
    assert_true(k >= 0);
    assert_true(c.methods[0].params.values.v[k] == 1.0 && c.methods[2].params.values.v[k] == 5.0);
    assert_true(c.methods[3].params.values.v[k] == 7.0);
    sl_config_free(&c);
    assert_null(c.session);
    static const struct { const char *entry; const char *key; const char *msg; } bad[] = {
        {"  - {method: pcf, kernal: 3}\n", "methods[0].kernal", "no parameter 'kernal' (did you mean 'kernel'?)"},
        {"  - {method: pcf, kernel: 11}\n", "methods[0].kernel", "outside [1, 9]"},
        {"  - {method: pcf, kernel: 2.5}\n", "methods[0].kernel", "2.5"},
        {"  - {method: pcf, kernel: [3, x]}\n", "methods[0].kernel", "'x'"},
        {"  - {method: pcf, kernel: {a: 1}}\n", "methods[0].kernel", "not a mapping"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        char text[512];
        snprintf(text, sizeof text, "name: pk\nscenes:\n  - {scene: primitives}\nmap_sizes: [512]\nmethods:\n%s",
                 bad[i].entry);
        write_tmp(path, text);
        memset(&d, 0, sizeof d);
        e = sl_config_load(path, &c, &d);
        printf("config::packages %s -> %s:%d '%s': %s\n", bad[i].entry, d.file, d.line, d.key, d.msg);
        assert_int_equal(e, SL_E_CONFIG);
        assert_int_equal(d.line, 6);
        assert_string_equal(d.key, bad[i].key);
        assert_non_null(strstr(d.msg, bad[i].msg));
    }
    remove(path);
    sl_config_free(&c);
}

/* Each loaded config has its own packages (its session): a package found
 * in one config's `techniques:` folder is not found by another config
 * loaded later in the same process, the same package name loaded twice is
 * two methods, and freeing one config leaves the other's intact. */
static void config_sessions(void **st)
{
    (void)st;
    char dir[400], sh[600];
    snprintf(dir, sizeof dir, "%s/pk/mine", sl_test_dir);
    snprintf(sh, sizeof sh, "mkdir -p %s && cp techniques/pcf/*.glsl %s/ && "
             "sed 's/^name: pcf$/name: mine/' techniques/pcf/technique.yaml > %s/technique.yaml", dir, dir, dir);
    assert_int_equal(system(sh), 0);
    struct sl_config a, b, p1;
    struct sl_diag d;
    sl_test_config("sa.yaml", "scenes: [{scene: primitives}]\nmap_sizes: [512]\ntechniques: [pk]\n"
                   "methods: [{method: mine, kernel: 5}, {method: pcf}]\n", &a);
    assert_non_null(a.session);
    assert_string_equal(a.methods[0].method->name, "mine");
    assert_int_equal(sl_session_method(a.session, "nsm"), sl_method_find("nsm"));   /* built-ins: shared */
    /* a config without the folder: 'mine' is unknown to it */
    char path[400];
    snprintf(path, sizeof path, "%s/sb.yaml", sl_test_dir);
    write_tmp(path, "scenes: [{scene: primitives}]\nmap_sizes: [512]\nmethods: [{method: mine}]\n");
    memset(&d, 0, sizeof d);
    assert_int_equal(sl_config_load(path, &b, &d), SL_E_CONFIG);
    assert_string_equal(d.key, "methods[0].method");
    assert_non_null(strstr(d.msg, "unknown method 'mine'"));
    assert_null(b.session);
    /* pcf in two configs: two methods, each its own config's */
    sl_test_config("sp.yaml", "scenes: [{scene: primitives}]\nmap_sizes: [512]\nmethods: [{method: pcf}]\n", &p1);
    assert_true(p1.methods[0].method != a.methods[1].method);
    assert_ptr_equal(p1.methods[0].params.tech, sl_package_of(p1.methods[0].method));
    sl_config_free(&a);
    assert_string_equal(p1.methods[0].method->name, "pcf");   /* still there */
    assert_true(sl_method_param(&p1.methods[0].params, "kernel") == 3);
    sl_config_free(&p1);
    sl_config_free(&b);
}

/* <test dir>/<folder>/<sub>: the shipped pcf renamed `name`, with `extra`
 * appended to its technique.yaml. */
static void pcf_copy(const char *folder, const char *sub, const char *name, const char *extra)
{
    char dir[400], sh[1200];
    snprintf(dir, sizeof dir, "%s/%s/%s", sl_test_dir, folder, sub);
    snprintf(sh, sizeof sh, "mkdir -p %s && cp techniques/pcf/*.glsl %s/ && "
             "sed 's/^name: pcf$/name: %s/' techniques/pcf/technique.yaml > %s/technique.yaml && printf '%s' >> "
             "%s/technique.yaml", dir, dir, name, dir, extra, dir);
    assert_int_equal(system(sh), 0);
}

/* The load's error for config text (written as <test dir>/<name>). */
static enum sl_err load_bad(const char *name, const char *text, struct sl_diag *d)
{
    char path[400];
    snprintf(path, sizeof path, "%s/%s", sl_test_dir, name);
    sl_test_write(sl_test_dir, name, text);
    struct sl_config c;
    memset(d, 0, sizeof *d);
    enum sl_err e = sl_config_load(path, &c, d);
    printf("config::package_rules %s -> %s:%d '%s': %s\n", name, d->file, d->line, d->key, d->msg);
    if (!e)
        sl_config_free(&c);
    return e;
}

/* The name and value rules hold for a config's own `techniques:` folder as
 * for the other sources: a package named like a C method is refused even
 * when every entry names a C method (it would run under the package's
 * name); a parameter named like a cascade key is refused; two different
 * packages of one name along the path are an error naming both; swept
 * values that parse to one value are refused, a package's and a C
 * method's alike. */
static void config_package_rules(void **st)
{
    (void)st;
    struct sl_diag d;
    char want[600];
    pcf_copy("pn", "nsm", "nsm", "");
    enum sl_err e = load_bad("pn.yaml", "scenes: [{scene: primitives}]\nmap_sizes: [512]\ntechniques: [pn]\n"
                             "methods: [{method: nsm}]\n", &d);
    assert_int_equal(e, SL_E_PACKAGE);
    snprintf(want, sizeof want, "%s/pn/nsm/technique.yaml", sl_test_dir);
    assert_string_equal(d.file, want);
    assert_string_equal(d.key, "name");
    assert_true(d.line > 0);
    assert_non_null(strstr(d.msg, "C method"));

    pcf_copy("pp", "mine", "mine", "  - {name: partitions, type: int, default: 2, min: 1, max: 4}\n");
    e = load_bad("pp.yaml", "scenes: [{scene: primitives}]\nmap_sizes: [512]\ntechniques: [pp]\n"
                 "methods: [{method: mine}]\n", &d);
    assert_int_equal(e, SL_E_PACKAGE);
    snprintf(want, sizeof want, "%s/pp/mine/technique.yaml", sl_test_dir);
    assert_string_equal(d.file, want);
    assert_non_null(strstr(d.key, ".name"));
    assert_non_null(strstr(d.msg, "cascades"));

    /* two packages named twin: one in the config's folder, one beside it;
     * and the shipped pcf shadowed by a different pcf */
    pcf_copy("pt", "a", "twin", "");
    pcf_copy("pt", "b", "twin", "# another\n");
    e = load_bad("pt.yaml", "scenes: [{scene: primitives}]\nmap_sizes: [512]\ntechniques: [pt]\n"
                 "methods: [{method: twin}]\n", &d);
    assert_int_equal(e, SL_E_PACKAGE);
    snprintf(want, sizeof want, "%s/pt/b/technique.yaml", sl_test_dir);
    assert_string_equal(d.file, want);
    assert_string_equal(d.key, "name");
    snprintf(want, sizeof want, "%s/pt/a/technique.yaml", sl_test_dir);
    assert_non_null(strstr(d.msg, want));
    pcf_copy("pq", "pcf", "pcf", "# mine\n");
    e = load_bad("pq.yaml", "scenes: [{scene: primitives}]\nmap_sizes: [512]\ntechniques: [pq]\n"
                 "methods: [{method: pcf}]\n", &d);
    assert_int_equal(e, SL_E_PACKAGE);
    snprintf(want, sizeof want, "%s/pq/pcf/technique.yaml (config)", sl_test_dir);
    assert_non_null(strstr(d.msg, want));
    assert_non_null(strstr(d.msg, "(source tree)"));
    assert_non_null(strstr(d.file, "techniques/pcf/technique.yaml"));
    /* the same package twice (one folder named twice) is one package */
    pcf_copy("ps", "same", "same", "");
    struct sl_config c;
    sl_test_config("ps.yaml", "scenes: [{scene: primitives}]\nmap_sizes: [512]\ntechniques: [ps, ps/same]\n"
                   "methods: [{method: same}]\n", &c);
    sl_config_free(&c);

    /* sweeps: 0.5 and 0.50, 1 and 1.0 are one value */
    e = load_bad("sw.yaml", "scenes: [{scene: primitives}]\nmap_sizes: [512]\nmethods:\n"
                 "  - {method: pcf, kernel: 3, bias: [0.5, 2, 0.50]}\n", &d);
    assert_int_equal(e, SL_E_CONFIG);
    assert_int_equal(d.line, 4);
    assert_string_equal(d.key, "methods[0].bias");
    assert_non_null(strstr(d.msg, "'0.5' and '0.50'"));
    e = load_bad("sc.yaml", "scenes: [{scene: primitives}]\nmap_sizes: [512]\nmethods:\n"
                 "  - {method: nsm}\n  - {label: b, method: nsm, self_shadow: constant, bias: [1, 1.0]}\n", &d);
    assert_int_equal(e, SL_E_CONFIG);
    assert_int_equal(d.line, 5);
    assert_string_equal(d.key, "methods[1].bias");
}

/* What a config alone decides is checked at load, before any GL or truth:
 * a package's GLSL errors (glslang) at the package file's line, after
 * lines reading the harness's sl_map_pos and sl_home_texel; a guard band
 * too wide for a map size a scene runs the label at, naming the entry's
 * key and line (a scene that does not run the label at that size is not
 * refused). */
static void config_package_checks(void **st)
{
    (void)st;
    struct sl_diag d;
    char want[600];
    pcf_copy("pg", "late", "late", "");
    char dir[400];
    snprintf(dir, sizeof dir, "%s/pg/late", sl_test_dir);
    sl_test_write(dir, "lookup.glsl", "float sl_lookup(vec3 w, vec3 n, vec2 uv, float z, float ndotl)\n"
                                      "{\n"
                                      "    vec2 p = sl_map_pos;\n"
                                      "    ivec2 h = sl_home_texel;\n"
                                      "    float x = p.x + float(h.y);\n"
                                      "    return x + undeclared_name;\n"
                                      "}\n");
    enum sl_err e = load_bad("pg.yaml", "scenes: [{scene: primitives}]\nmap_sizes: [512]\ntechniques: [pg]\n"
                             "methods: [{method: late}]\n", &d);
    assert_int_equal(e, SL_E_PACKAGE);
    snprintf(want, sizeof want, "%s/lookup.glsl", dir);
    assert_string_equal(d.file, want);
    assert_int_equal(d.line, 6);
    assert_non_null(strstr(d.msg, "undeclared_name"));

    e = load_bad("gb.yaml", "scenes: [{scene: primitives}]\nmap_sizes: [1024, 16384]\nmethods:\n"
                 "  - {method: nsm}\n  - method: pcf\n    kernel: 9\n", &d);
    assert_int_equal(e, SL_E_CONFIG);
    assert_int_equal(d.line, 6);
    assert_string_equal(d.key, "methods[1].kernel");
    assert_non_null(strstr(d.msg, "16384 + 2 x 4 = 16392"));
    /* the same label where the 16384 scene does not run it: loads */
    struct sl_config c;
    sl_test_config("gb2.yaml", "scenes:\n  - {scene: primitives, map_sizes: [16384], methods: [nsm]}\n"
                   "  - {scene: bench, map_sizes: [1024]}\nmap_sizes: [1024]\nmethods:\n"
                   "  - {method: nsm}\n  - {method: pcf, kernel: 9}\n", &c);
    sl_config_free(&c);
}

/* outputs.aliasing: auto (the default) computes the aliasing error m only
 * where a method's study reads it (zpart, lispsm); true and false force it. */
static void config_aliasing_on_demand(void **st)
{
    (void)st;
    struct sl_config c;
    struct sl_diag d;
    assert_int_equal(sl_config_load("configs/default.yaml", &c, &d), SL_OK);
    assert_int_equal(c.aliasing, 0);   /* nsm alone */
    sl_config_free(&c);
    assert_int_equal(sl_config_load("configs/aliasing.yaml", &c, &d), SL_OK);
    assert_int_equal(c.aliasing, 1);   /* zpart, lispsm */
    const char *on[] = {"outputs.aliasing=true"};
    sl_config_free(&c);
    assert_int_equal(sl_config_load_with("configs/default.yaml", on, 1, &c, &d), SL_OK);
    assert_int_equal(c.aliasing, 1);
    const char *off[] = {"outputs.aliasing=false"};
    sl_config_free(&c);
    assert_int_equal(sl_config_load_with("configs/aliasing.yaml", off, 1, &c, &d), SL_OK);
    assert_int_equal(c.aliasing, 0);
    const char *bad[] = {"outputs.aliasing=sometimes"};
    sl_config_free(&c);
    assert_int_equal(sl_config_load_with("configs/default.yaml", bad, 1, &c, &d), SL_E_CONFIG);
    assert_string_equal(d.key, "outputs.aliasing");
    sl_config_free(&c);
}

int main(int argc, char **argv)
{
    const struct CMUnitTest tests[] = {
        SL_CASE(config, default_loads),
        SL_CASE(config, written_reads_back),
        SL_CASE(config, bad_inputs),
        SL_CASE(config, repetitions_default),
        SL_CASE(config, syntax_error_has_line),
        SL_CASE(config, overrides),
        SL_CASE(config, sweeps),
        SL_CASE(config, packages),
        SL_CASE(config, package_rules),
        SL_CASE(config, package_checks),
        SL_CASE(config, sessions),
        SL_CASE(config, aliasing_on_demand),
    };
    return sl_run_group(argc, argv, "config", tests, NULL, NULL);
}
