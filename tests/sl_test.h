/* Shared by the cmocka tests: case names module::case (the function is
 * module_case), a temporary folder per test program, and configs written
 * there from text. Include after <cmocka.h>. */
#ifndef SL_TEST_H
#define SL_TEST_H
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "config.h"

#define SL_CASE(module, fn) { #module "::" #fn, module##_##fn, NULL, NULL, NULL }

/* The program's temporary folder (made by sl_test_setup, removed by
 * sl_test_teardown: pass them to cmocka_run_group_tests_name). */
static char sl_test_dir[] = "/tmp/shadowlab-test-XXXXXX";

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
static inline void sl_test_config(const char *name, const char *text, struct sl_config *c)
{
    char path[300];
    snprintf(path, sizeof path, "%s/%s", sl_test_dir, name);
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fputs(text, f);
    fclose(f);
    struct sl_diag d;
    enum sl_err e = sl_config_load(path, c, &d);
    if (e)
        fprintf(stderr, "%s:%d '%s': %s\n", d.file, d.line, d.key, d.msg);
    assert_int_equal(e, SL_OK);
}

#endif
