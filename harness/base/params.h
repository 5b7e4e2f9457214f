/*
 * params.h — the one form in which anything that takes parameters declares
 * them (a C method, a technique package), and a checked set of values for
 * one use of it.
 *
 * A declaration says a parameter's name, type, default, range or choices,
 * doc and unit. A C method declares its own as a const array beside its
 * code (methods/method.h: `params`); a package's come from its
 * technique.yaml (render/technique.h). A config gives values by name: each
 * is parsed and checked against its declaration here, so every method's
 * parameters are refused, swept, written back, documented (doc/config.md,
 * `show method NAME`, `show technique NAME`) and completed alike.
 *
 * Owns: nothing (a set points at its declarations). Does not: know a
 * method, a package or a config; check one parameter against another
 * (that is the method's configure: e.g. nsm's bias applies to two of its
 * self-shadow policies only).
 */
#ifndef SL_PARAMS_H
#define SL_PARAMS_H
#include <stddef.h>
#include "sl_error.h"

#define SL_PARAM_NAME_MAX 40   /* names: at most 32 characters (a package's identifiers) */
#define SL_PARAM_MAX      24   /* parameters of one set: a package's 16 and its 2 cascades', or the
                                  config's settings (config.c: 18, room for a few more) */
#define SL_PARAM_CHOICES  8    /* words of a choice */

/* The types, each one line: the enum and the spelling a package's
 * technique.yaml, the config reference and `show` use. */
#define SL_PARAM_TYPES(X) X(INT, "int") X(FLOAT, "float") X(BOOL, "bool") X(CHOICE, "choice")
enum sl_param_type {
#define SL_PARAM_TYPE_ENUM(id, text) SL_PARAM_##id,
    SL_PARAM_TYPES(SL_PARAM_TYPE_ENUM)
#undef SL_PARAM_TYPE_ENUM
    SL_PARAM_TYPE_COUNT
};
extern const char *const sl_param_type_names[SL_PARAM_TYPE_COUNT];

/*
 * One parameter. Its value is a double: an int's and a bool's (0 or 1)
 * exactly, a choice's the index of its word. min and max bound an int or
 * a float (has_min/has_max: given; an unbounded side is -inf/+inf); a bool
 * is 0..1, a choice an index into its words. doc: one line for the config reference
 * and `show`; unit: what the number counts ("texels"), "" for none.
 */
struct sl_param {
    char               name[SL_PARAM_NAME_MAX];
    enum sl_param_type type;
    double             def;
    double             min, max;
    int                has_min, has_max;
    char               choice[SL_PARAM_CHOICES][16];   /* a choice's words, "" after the last */
    char               doc[200];
    char               unit[16];
};

/* Declaration helpers for a C method's const array (every field named, the
 * rest zero): an int or a float in [lo, hi], a bool, a choice of words. */
#define SL_PARAM_INT_DECL(nm, d, lo, hi, u, text) \
    {.name = nm, .type = SL_PARAM_INT, .def = (d), .min = (lo), .max = (hi), .has_min = 1, .has_max = 1, .doc = text, .unit = u}
#define SL_PARAM_FLOAT_DECL(nm, d, lo, hi, u, text) \
    {.name = nm, .type = SL_PARAM_FLOAT, .def = (d), .min = (lo), .max = (hi), .has_min = 1, .has_max = 1, .doc = text, .unit = u}
#define SL_PARAM_BOOL_DECL(nm, d, text) \
    {.name = nm, .type = SL_PARAM_BOOL, .def = (d), .min = 0, .max = 1, .doc = text}
#define SL_PARAM_CHOICE_DECL(nm, d, text, ...) \
    {.name = nm, .type = SL_PARAM_CHOICE, .def = (d), .min = 0, .choice = {__VA_ARGS__}, .doc = text}

/* The index of the parameter called name in decl[0..n), -1 if none. */
int sl_param_index(const struct sl_param *decl, int n, const char *name);

/* A value of p's type from its text as a config writes it: 0 and *x, else
 * why not (a phrase: "is not an int (decimal digits)"). Ranges are not
 * checked here (sl_params_put does). */
const char *sl_param_parse(const struct sl_param *p, const char *text, double *x);

/* The value x of p as a config writes it (the filled-in config, `show`):
 * an int "%d", a float "%.9g", a bool true/false, a choice its word. */
void sl_param_text(const struct sl_param *p, double x, char *buf, size_t n);
/* "[0, 1000]", "1..16", "4 or 9"-style range text; "" when unbounded. */
void sl_param_range_text(const struct sl_param *p, char *buf, size_t n);

/*
 * A set of values for one use of the declarations decl[0..n): every value
 * present (the defaults where none was given); `given` has bit k when the
 * config gave decl[k]; `off` has bit k when decl[k] does not apply to this
 * use (the method's configure says so: e.g. nsm's bias under front_faces),
 * so it is neither written back nor accepted from a config.
 */
struct sl_params {
    const struct sl_param *decl;
    int                    n;
    double                 v[SL_PARAM_MAX];
    unsigned               given, off;
};

/* The set of decl[0..n) at its defaults, nothing given (n <= SL_PARAM_MAX). */
void sl_params_init(struct sl_params *s, const struct sl_param *decl, int n);
/* Give parameter `name` the value x, checked against its declaration (an
 * int a whole number, a bool 0 or 1, a choice an index, in range), and
 * mark it given. Errors: SL_E_METHOD with the key `name` and why; no
 * such parameter names the ones there are. */
enum sl_err sl_params_put(struct sl_params *s, const char *name, double x, struct sl_diag *d);
/* The same from text (sl_param_parse, then sl_params_put). */
enum sl_err sl_params_put_text(struct sl_params *s, const char *name, const char *text, struct sl_diag *d);

/* The value of parameter `name`; a name the set does not declare is a
 * programming error: it returns NaN, which every range check refuses. */
double sl_params_get(const struct sl_params *s, const char *name);
int    sl_params_given(const struct sl_params *s, const char *name);
/* Set a value a configure derives (a dependent default), unchecked and not
 * marked given. */
void   sl_params_derive(struct sl_params *s, const char *name, double x);
/* Parameter `name` does not apply to this use: refused (SL_E_METHOD, key
 * name, "NAME applies to WHEN") if the config gave it, else marked off. */
enum sl_err sl_params_off(struct sl_params *s, const char *name, const char *when, struct sl_diag *d);

#endif
