/*
 * test_params.h — a method's parameters for a test: "key=value ..." (the
 * words a config writes), each given and checked as a config's are
 * (base/params.h), the rest at their declared defaults, then the method's
 * configure. Include after cmocka.h and method.h.
 */
#ifndef SL_TEST_PARAMS_H
#define SL_TEST_PARAMS_H
#include <stdio.h>
#include <string.h>

static inline void sl_test_params(const struct sl_method *m, struct sl_method_params *p, const char *spec)
{
    sl_method_params_init(m, p);
    char buf[256];
    snprintf(buf, sizeof buf, "%s", spec ? spec : "");
    struct sl_diag d;
    char *save = NULL;
    for (char *tok = strtok_r(buf, " ", &save); tok; tok = strtok_r(NULL, " ", &save)) {
        char *eq = strchr(tok, '=');
        assert_non_null(eq);
        *eq = '\0';
        assert_int_equal(sl_params_put_text(&p->values, tok, eq + 1, &d), SL_OK);
    }
    assert_int_equal(sl_method_configure(m, p, &d), SL_OK);
}

#endif
