/* Shared by the cmocka tests: case names module::case (the function is
 * module_case), main's run of the group or of one case, a temporary folder
 * per test program, configs written there from text, a file read whole, a
 * made-up cell's method named as a run stores it, and a report that must
 * build. Include after <cmocka.h>. */
#ifndef SL_TEST_H
#define SL_TEST_H
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "config.h"
#include "method.h"
#include "report.h"
#include "store.h"

#define SL_CASE(module, fn) { #module "::" #fn, module##_##fn, NULL, NULL, NULL }

/* The program's temporary folder (made by sl_test_setup, removed by
 * sl_test_teardown: pass them to cmocka_run_group_tests_name). */
static char sl_test_dir[] = "/tmp/shadowlab-test-XXXXXX";

/* main(argc, argv) of a test program: run the group `tests` (with the
 * group's setup and teardown), or with a case name as the one argument only
 * that case, still inside the group's setup and teardown (ctest runs each
 * module::case on its own this way: tests/CMakeLists.txt). A name that is not
 * exactly one case's fails, so a renamed case cannot pass by running nothing. */
#define sl_run_group(argc, argv, name, tests, setup, teardown)                                        \
    sl_run_group_n((argc), (argv), (name), (tests), sizeof(tests) / sizeof((tests)[0]), (setup), (teardown))

static inline int sl_run_group_n(int argc, char **argv, const char *name, const struct CMUnitTest *tests,
                                 size_t n, CMFixtureFunction setup, CMFixtureFunction teardown)
{
    if (argc > 2) {
        fprintf(stderr, "usage: %s [module::case]\n", argv[0]);
        return 2;
    }
    if (argc == 2) {
        size_t hits = 0;
        for (size_t i = 0; i < n; i++)
            hits += strcmp(tests[i].name, argv[1]) == 0;
        /* cmocka's filter is a glob matched against the whole name: a name
         * with no wildcard in it matches only itself */
        if (hits != 1 || strpbrk(argv[1], "*?")) {
            fprintf(stderr, "%s: %s case named '%s'; the cases:\n", argv[0], hits > 1 ? "more than one" : "no",
                    argv[1]);
            for (size_t i = 0; i < n; i++)
                fprintf(stderr, "  %s\n", tests[i].name);
            return 2;
        }
        cmocka_set_test_filter(argv[1]);
    }
    return _cmocka_run_group_tests(name, tests, n, setup, teardown);
}

static inline int sl_test_setup(void **st)
{
    (void)st;
    return mkdtemp(sl_test_dir) ? 0 : -1;
}

static inline int sl_test_teardown(void **st)
{
    (void)st;
    char cmd[200];
    snprintf(cmd, sizeof cmd, "rm -rf %s", sl_test_dir);
    return system(cmd) == 0 ? 0 : -1;
}

/* Write `text` as <dir>/<name> and load it as a config, which must be valid. */
/* Writes text to dir/name (the test fails if it cannot). */
static inline void sl_test_write(const char *dir, const char *name, const char *text)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fputs(text, f);
    assert_int_equal(fclose(f), 0);
}

static inline void sl_test_config(const char *name, const char *text, struct sl_config *c)
{
    char path[300];
    snprintf(path, sizeof path, "%s/%s", sl_test_dir, name);
    sl_test_write(sl_test_dir, name, text);
    struct sl_diag d;
    enum sl_err e = sl_config_load(path, c, &d);
    if (e)
        fprintf(stderr, "%s:%d '%s': %s\n", d.file, d.line, d.key, d.msg);
    assert_int_equal(e, SL_OK);
}

/* The whole of the file at path as a string (free it), NULL if it cannot be
 * read. */
static inline char *sl_test_slurp(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *s = malloc((size_t)n + 1);
    if (s && fread(s, 1, (size_t)n, f) != (size_t)n) {
        free(s);
        s = NULL;
    }
    if (s)
        s[n] = '\0';
    fclose(f);
    return s;
}

/* A cell's method, with where it comes from as a run stores it (cells.family,
 * beside: harness/results/cellcols.h): the method's own metadata, "" for a
 * name that is no method. */
static inline void sl_test_cell_method(struct sl_cell_record *c, const char *method)
{
    const struct sl_method *m = sl_method_find(method);
    snprintf(c->method, sizeof c->method, "%s", method);
    snprintf(c->family, sizeof c->family, "%s", sl_method_family(m));
    snprintf(c->beside, sizeof c->beside, "%s", sl_method_beside(m));
}

/* The report of `in` written to out (gnuplot from PATH), which must build:
 * the diagnostic printed when it does not. */
static inline void sl_test_report(const struct sl_report_input *in, const char *out)
{
    struct sl_diag d;
    memset(&d, 0, sizeof d);
    enum sl_err e = sl_report_build(in, out, NULL, &d);
    if (e)
        fprintf(stderr, "%s: %s: %s\n", d.file, d.key, d.msg);
    assert_int_equal(e, SL_OK);
}

#endif
