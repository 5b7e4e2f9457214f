/*
 * sl_error.c — see sl_error.h: error strings and diagnostics.
 * Invariant: nothing here prints; callers get an id and an sl_diag.
 */
#include "sl_error.h"
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

static const char *const sl_err_text[] = {
#define SL_ERR_TEXT(id, text) text,
    SL_ERRORS(SL_ERR_TEXT)
#undef SL_ERR_TEXT
};

const char *sl_err_str(enum sl_err e)
{
    return (e >= 0 && e < SL_ERR_COUNT) ? sl_err_text[e] : "unknown error";
}

enum sl_err sl_fail(struct sl_diag *d, enum sl_err e, const char *file, int line,
                    const char *key, const char *fmt, ...)
{
    if (!d)
        return e;
    memset(d, 0, sizeof *d);
    if (file)
        snprintf(d->file, sizeof d->file, "%s", file);
    d->line = line;
    if (key)
        snprintf(d->key, sizeof d->key, "%s", key);
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(d->msg, sizeof d->msg, fmt, ap);
    va_end(ap);
    return e;
}

void sl_diag_format(const struct sl_diag *d, enum sl_err e, char *buf, size_t n)
{
    size_t k = 0;
    buf[0] = '\0';
    if (d->file[0])
        k += (size_t)snprintf(buf + k, n - k, "%s:", d->file);
    if (d->line > 0 && k < n)
        k += (size_t)snprintf(buf + k, n - k, "%d:", d->line);
    if (k && k < n)
        k += (size_t)snprintf(buf + k, n - k, " ");
    if (d->key[0] && k < n)
        k += (size_t)snprintf(buf + k, n - k, "'%s': ", d->key);
    if (k < n)
        snprintf(buf + k, n - k, "%s (%s)", d->msg[0] ? d->msg : sl_err_str(e), sl_err_str(e));
}
