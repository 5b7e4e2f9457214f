/*
 * cli.c — what the verbs share (cli.h): the one line an error prints and
 * the exit code of its id, and the option parser with the checks of the
 * values options take. A value is checked here as a config key's is, with
 * a message in the same form, so a bad option and a bad key read alike.
 */
#define _GNU_SOURCE   /* getopt_long */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "cli.h"
#include "config.h"

/* 2: bad input or usage (a config, a scene, a model, an option, a store or
 * file that cannot be read as what it should be); 3: a system failure (an
 * output that cannot be written, GL, Embree, memory, an internal error). */
static int exit_code(enum sl_err e)
{
    switch (e) {
    case SL_E_OUTPUT: case SL_E_GL: case SL_E_EMBREE: case SL_E_NOMEM: case SL_E_IMAGE: case SL_E_INTERNAL:
        return 3;
    default:
        return 2;
    }
}

int cli_fail(enum sl_err e, const struct sl_diag *d)
{
    char line[1200];
    sl_diag_format(d, e, line, sizeof line);
    fprintf(stderr, "shadowlab: %s\n", line);
    return exit_code(e);
}

void cli_note_left_out(const struct sl_config *c)
{
    for (int si = 0; si < c->nscenes; si++) {
        if (!c->scenes[si].left_out)
            continue;
        fprintf(stderr, "shadowlab: note: scene '%s' has %s light and names no methods list: it leaves out",
                c->scenes[si].name, sl_config_light_name(c->scenes[si].light_type));
        const char *sep = " ";
        for (int k = 0; k < c->nmethods; k++) {
            const char *why = sl_config_left_out_why(c, si, k);
            if (why) {
                fprintf(stderr, "%s%s (%s)", sep, c->methods[k].label, why);
                sep = ", ";
            }
        }
        fputc('\n', stderr);
    }
}

int cli_usage_error(const char *msg, const char *text)
{
    fprintf(stderr, "shadowlab: %s\n%s", msg, text);
    return 2;
}

int cli_opt_next(const struct cli_parser *p, int argc, char **argv)
{
    char shorts[64];
    snprintf(shorts, sizeof shorts, ":h%s", p->shorts);   /* ':' = say which value is missing */
    int c = getopt_long(argc, argv, shorts, p->longs, NULL);
    if (c == 'h') {
        fputs(p->help, stdout);
        return OPT_EXIT_OK;
    }
    if (c == '?' || c == ':') {
        char what[128];
        if (c == '?' && optopt && optopt < 256)   /* an unknown letter, maybe inside -abc */
            snprintf(what, sizeof what, "-%c", optopt);
        else
            snprintf(what, sizeof what, "%s", argv[optind - 1]);
        fprintf(stderr, "shadowlab %s: %s '%s'\n%s", p->verb, c == '?' ? "unknown option" : "missing value for",
                what, p->help);
        return OPT_EXIT_USAGE;
    }
    return c;
}

int cli_opt_exit(int c) { return c == OPT_EXIT_OK ? 0 : 2; }

/* -D KEY=VALUE, repeatable */
int cli_add_override(struct cli_overrides *o, const char *verb, const char *arg, const char *help)
{
    if (o->n == (int)(sizeof o->v / sizeof o->v[0]) || !strchr(arg, '=')) {
        fprintf(stderr, "shadowlab %s: -D wants KEY=VALUE (at most 64): '%s'\n%s", verb, arg, help);
        return 0;
    }
    o->v[o->n++] = arg;
    return 1;
}

/* An integer an option takes: decimal digits (a sign allowed), all of the
 * text, in lo..hi; no atoi (4294967297 would be 1) and no float ("7.9").
 * Returns 0 with msg in the form of a config key's ("'7.9' is not a whole
 * number", "... must be in 1..64"). */
int cli_opt_int(const char *s, long long lo, long long hi, long long *out, char *msg, size_t n)
{
    char *end;
    errno = 0;
    long long v = strtoll(s, &end, 10);
    if (end == s || *end || (*s != '-' && *s != '+' && (*s < '0' || *s > '9'))) {
        snprintf(msg, n, "'%s' is not a whole number (an integer in decimal digits is expected)", s);
        return 0;
    }
    if (errno == ERANGE || v < lo || v > hi) {
        snprintf(msg, n, "'%s' must be in %lld..%lld", s, lo, hi);
        return 0;
    }
    *out = v;
    return 1;
}

/* cli_usage_error for an integer option: "VERB: --OPT: MSG" */
int cli_opt_int_or_usage(const char *verb, const char *opt, const char *s, long long lo, long long hi,
                         long long *out, const char *help)
{
    char msg[200], line[300];
    if (cli_opt_int(s, lo, hi, out, msg, sizeof msg))
        return 1;
    snprintf(line, sizeof line, "%s: %s %s", verb, opt, msg);
    cli_usage_error(line, help);
    return 0;
}

/* "WxH", each a whole number in lo..hi */
int cli_parse_wxh(const char *s, long long lo, long long hi, int *w, int *h)
{
    char a[32];
    const char *x = strchr(s, 'x');
    long long vw, vh;
    char msg[200];
    if (!x || x == s || (size_t)(x - s) >= sizeof a)
        return 0;
    snprintf(a, sizeof a, "%.*s", (int)(x - s), s);
    if (!cli_opt_int(a, lo, hi, &vw, msg, sizeof msg) || !cli_opt_int(x + 1, lo, hi, &vh, msg, sizeof msg))
        return 0;
    *w = (int)vw;
    *h = (int)vh;
    return 1;
}
