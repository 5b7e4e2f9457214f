/*
 * sl_error.h — the closed list of error ids shadowlab functions return.
 *
 * One X-macro list gives the enum and the strings together, so tests assert on
 * ids rather than on message text. Library code returns an id and fills an
 * sl_diag with the place (file, line, key) and detail; only main() prints and
 * chooses the exit code (2 for bad input or usage, 1 for a failed check).
 */
#ifndef SL_ERROR_H
#define SL_ERROR_H
#include <stddef.h>
#ifdef __cplusplus
extern "C" {
#endif

#define SL_ERRORS(X)                                                        \
    X(SL_OK,            "ok")                                               \
    X(SL_E_USAGE,       "bad usage")                                        \
    X(SL_E_IO,          "cannot read or write a file")                      \
    X(SL_E_CONFIG,      "invalid config")                                   \
    X(SL_E_SCENE,       "unknown or invalid scene")                         \
    X(SL_E_METHOD,      "unknown method or bad method parameter")           \
    X(SL_E_BASELINE,    "invalid baseline file")                            \
    X(SL_E_PACKAGE,     "invalid technique package")                        \
    X(SL_E_OUTPUT,      "output directory not writable")                    \
    X(SL_E_GL,          "OpenGL failure")                                   \
    X(SL_E_EMBREE,      "Embree failure")                                   \
    X(SL_E_NOMEM,       "out of memory")                                    \
    X(SL_E_IMAGE,       "image write failure")                              \
    X(SL_E_INTERNAL,    "internal error")                                   \
    X(SL_E_DATA,        "invalid data file")                                \
    X(SL_E_STOPPED,     "stopped by a signal")

enum sl_err {
#define SL_ERR_ENUM(id, text) id,
    SL_ERRORS(SL_ERR_ENUM)
#undef SL_ERR_ENUM
    SL_ERR_COUNT
};

const char *sl_err_str(enum sl_err e);

/* Where a failure happened and why, for the one line main() prints. */
struct sl_diag {
    char file[256];   /* input file concerned, "" if none */
    int  line;        /* 1-based line in that file, 0 if unknown */
    char key[96];     /* config key or name concerned, "" if none */
    char msg[512];    /* human detail */
};

/* Fill d (may be NULL) and return e. */
enum sl_err sl_fail(struct sl_diag *d, enum sl_err e, const char *file, int line,
                    const char *key, const char *fmt, ...)
    __attribute__((format(printf, 6, 7)));

/* "file:line: key: msg (error id)" on one line into buf. */
void sl_diag_format(const struct sl_diag *d, enum sl_err e, char *buf, size_t n);

#ifdef __cplusplus
}
#endif
#endif
