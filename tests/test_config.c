/* config::* — experiment files: the default loads with every default filled,
 * and each bad file yields its error id, line and key. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>
#include "sl_test.h"
#include "config.h"
#include "method.h"

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
    assert_int_equal(c.runs, 1);
    assert_int_equal(c.warmup, 0);
    assert_int_equal(c.nmaps, 2);
    assert_int_equal(c.maps[0], 1024);
    assert_int_equal(c.maps[1], 2048);
    assert_int_equal(c.nregions, 4);
    assert_int_equal(c.regions[3], 0);
    assert_int_equal(c.nmethods, 1);
    assert_string_equal(c.methods[0].method->name, "nsm");
    assert_int_equal(c.methods[0].params.self_shadow, SL_SELF_FRONT_FACES);
    assert_true(c.threads >= 1);
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
    assert_int_equal(b.methods[0].params.self_shadow, sl_self_shadow_parse("slope"));
    assert_true(b.methods[0].params.bias > 0.0099f && b.methods[0].params.bias < 0.0101f);
    assert_int_equal(b.viewport_w[0], 256);
    assert_int_equal(b.viewport_h[0], 128);
    assert_int_equal(b.exr, 1);
    assert_int_equal(b.threads, 3);
    assert_string_equal(b.path, "configs/default.yaml");
    assert_true(a.hash != b.hash);
    assert_int_equal(sl_config_load_with("configs/default.yaml", ok, 6, &c, &d), SL_OK);
    assert_true(b.hash == c.hash);   /* the same overrides: the same study (--resume finds it) */
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
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        memset(&d, 0, sizeof d);
        assert_int_not_equal(sl_config_load_with("configs/default.yaml", &bad[i].ov, 1, &c, &d), SL_OK);
        char src[200];
        snprintf(src, sizeof src, "-D %s", bad[i].ov);
        assert_string_equal(d.file, src);
        assert_string_equal(d.key, bad[i].key);
        assert_non_null(strstr(d.msg, bad[i].msg));
    }
}

int main(int argc, char **argv)
{
    const struct CMUnitTest tests[] = {
        SL_CASE(config, default_loads),
        SL_CASE(config, written_reads_back),
        SL_CASE(config, bad_inputs),
        SL_CASE(config, syntax_error_has_line),
        SL_CASE(config, overrides),
    };
    return sl_run_group(argc, argv, "config", tests, NULL, NULL);
}
