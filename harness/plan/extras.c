/*
 * extras.c — method entries' extra keys taken out of a config's text
 * (extras.h): libyaml's events give each key's and value's byte range, so
 * a taken key is blanked in place and every other line stays where it was.
 */
#include "extras.h"
#include <stdio.h>
#include <string.h>
#include <yaml.h>

/* One key of the entry being read, with the range of key and value. */
struct seen {
    char   key[32];
    size_t from, to;          /* bytes [from, to): the key through its value */
    int    line;
    int    kind;              /* 0 scalar, 1 list of scalars, 2 anything else (a mapping, a nested list) */
    int    nvalues;
    int    toolong;           /* a value over 63 bytes, or a list over SL_EXTRA_VALUES */
    char   value[SL_EXTRA_VALUES][64];
};
#define SEEN_MAX 48

struct walk {
    yaml_parser_t p;
    yaml_event_t  ev;
    int           have;       /* ev holds an event */
    int           bad;        /* the parser failed: leave the text alone */
    int           ended;      /* the stream's end was read */
};

/* The next event; 0 at an error and after the stream's end (libyaml then
 * hands out empty events forever: a walk inside a node the text never
 * closed must stop there, not loop). */
static int next(struct walk *w)
{
    if (w->have)
        yaml_event_delete(&w->ev);
    w->have = 0;
    if (w->ended || w->bad)
        return 0;
    if (!yaml_parser_parse(&w->p, &w->ev)) {
        w->bad = 1;
        return 0;
    }
    w->have = 1;
    if (w->ev.type == YAML_STREAM_END_EVENT || w->ev.type == YAML_NO_EVENT)
        w->ended = 1;
    return w->ev.type != YAML_NO_EVENT;
}

/* Skip the node whose first event is current; on return the current event
 * is its last. */
static int skip_node(struct walk *w)
{
    int depth = 0;
    do {
        yaml_event_type_t t = w->ev.type;
        if (t == YAML_MAPPING_START_EVENT || t == YAML_SEQUENCE_START_EVENT)
            depth++;
        else if (t == YAML_MAPPING_END_EVENT || t == YAML_SEQUENCE_END_EVENT)
            depth--;
        if (depth == 0)
            return 1;
    } while (next(w));
    return 0;
}

static void blank(unsigned char *text, size_t len, size_t from, size_t to)
{
    for (size_t i = from; i < to && i < len; i++)
        if (text[i] != '\n' && text[i] != '\r')
            text[i] = ' ';
}

/* The value node of a key (current event its first): what it is, its
 * scalars, the byte where it ends. */
static int read_value(struct walk *w, struct seen *s)
{
    if (w->ev.type == YAML_SCALAR_EVENT) {
        s->kind = 0;
        s->nvalues = 1;
        if (w->ev.data.scalar.length >= sizeof s->value[0])
            s->toolong = 1;
        snprintf(s->value[0], sizeof s->value[0], "%s", (const char *)w->ev.data.scalar.value);
        s->to = w->ev.end_mark.index;
        return 1;
    }
    if (w->ev.type == YAML_SEQUENCE_START_EVENT) {
        s->kind = 1;
        s->nvalues = 0;
        while (next(w)) {
            if (w->ev.type == YAML_SEQUENCE_END_EVENT) {
                s->to = w->ev.end_mark.index;
                return 1;
            }
            if (w->ev.type != YAML_SCALAR_EVENT) {
                s->kind = 2;
                if (!skip_node(w))
                    return 0;
                continue;
            }
            if (s->nvalues == SL_EXTRA_VALUES || w->ev.data.scalar.length >= sizeof s->value[0])
                s->toolong = 1;
            else
                snprintf(s->value[s->nvalues++], sizeof s->value[0], "%s", (const char *)w->ev.data.scalar.value);
        }
        return 0;
    }
    s->kind = 2;
    if (!skip_node(w))
        return 0;
    s->to = w->ev.end_mark.index;
    return 1;
}

/* One entry of `methods:` (current event its MAPPING_START). */
static enum sl_err entry(struct walk *w, unsigned char *text, size_t len, int i, sl_extras_take_fn take,
                         void *user, struct sl_method_extras *out, const char *file, struct sl_diag *d)
{
    static struct seen seen[SEEN_MAX];   /* config loading is single-threaded */
    int n = 0;
    int flow = w->ev.data.mapping_start.style == YAML_FLOW_MAPPING_STYLE;
    char method[64] = "";
    while (next(w)) {
        if (w->ev.type == YAML_MAPPING_END_EVENT)
            break;
        struct seen tmp, *s = n < SEEN_MAX ? &seen[n] : &tmp;
        memset(s, 0, sizeof *s);
        int is_key = w->ev.type == YAML_SCALAR_EVENT;
        if (is_key) {
            snprintf(s->key, sizeof s->key, "%s", (const char *)w->ev.data.scalar.value);
            s->from = w->ev.start_mark.index;
            s->line = (int)w->ev.start_mark.line + 1;
        } else if (!skip_node(w)) {
            return SL_OK;
        }
        if (!next(w) || !read_value(w, s))
            return SL_OK;
        if (!is_key)
            continue;
        if (!strcmp(s->key, "method") && s->kind == 0)
            snprintf(method, sizeof method, "%s", s->value[0]);
        if (n < SEEN_MAX)
            n++;
    }
    if (w->bad)
        return SL_OK;
    struct sl_method_extras *x = &out[i];
    snprintf(x->method, sizeof x->method, "%s", method);
    for (int k = 0; k < n; k++) {
        struct seen *s = &seen[k];
        if (!strcmp(s->key, "method") || !strcmp(s->key, "label") || !strcmp(s->key, "light_frame"))
            continue;
        if (!take(method, s->key, s->kind == 1, user))
            continue;
        char key[80];
        snprintf(key, sizeof key, "methods[%d].%s", i, s->key);
        if (s->kind == 2)
            return sl_fail(d, SL_E_CONFIG, file, s->line, key,
                           "a value or a list of values (a sweep), not a mapping or a nested list");
        if (s->kind == 1 && s->nvalues == 0)
            return sl_fail(d, SL_E_CONFIG, file, s->line, key, "an empty list sweeps nothing");
        if (s->toolong)
            return sl_fail(d, SL_E_CONFIG, file, s->line, key, "at most %d values of at most 63 bytes each",
                           SL_EXTRA_VALUES);
        if (x->n == SL_EXTRA_KEYS)
            return sl_fail(d, SL_E_CONFIG, file, s->line, key, "more than %d parameters or sweeps in one entry",
                           SL_EXTRA_KEYS);
        struct sl_extra_key *e = &x->k[x->n++];
        snprintf(e->key, sizeof e->key, "%s", s->key);
        e->line = s->line;
        e->is_list = s->kind == 1;
        e->nvalues = s->nvalues;
        memcpy(e->value, s->value, sizeof e->value);
        /* the entry's comma goes with it in a flow mapping: the one
         * before it, or after it when it comes first */
        size_t from = s->from, to = s->to;
        if (flow) {
            size_t b = from;
            while (b > 0 && (text[b - 1] == ' ' || text[b - 1] == '\t' || text[b - 1] == '\n' || text[b - 1] == '\r'))
                b--;
            if (b > 0 && text[b - 1] == ',') {
                from = b - 1;
            } else {
                size_t a = to;
                while (a < len && (text[a] == ' ' || text[a] == '\t' || text[a] == '\n' || text[a] == '\r'))
                    a++;
                if (a < len && text[a] == ',')
                    to = a + 1;
            }
        }
        blank(text, len, from, to);
    }
    return SL_OK;
}

enum sl_err sl_extras_take(unsigned char *text, size_t len, sl_extras_take_fn take, void *user,
                           struct sl_method_extras *out, int max, const char *file, struct sl_diag *d)
{
    memset(out, 0, (size_t)max * sizeof *out);
    struct walk w;
    memset(&w, 0, sizeof w);
    if (!yaml_parser_initialize(&w.p))
        return SL_OK;
    yaml_parser_set_input_string(&w.p, text, len);
    enum sl_err e = SL_OK;
    int depth = 0, in_methods = 0, i = 0;
    int want_methods = 0;   /* the root mapping's last key was `methods` and its value is next */
    int root_key = 1;       /* at depth 1: the next scalar is a key */
    while (!e && next(&w)) {
        yaml_event_type_t t = w.ev.type;
        if (t == YAML_STREAM_END_EVENT || t == YAML_DOCUMENT_END_EVENT)
            break;
        if (depth == 1 && !in_methods) {
            /* the root mapping: key, value, key, value ... */
            if (root_key) {
                if (t == YAML_MAPPING_END_EVENT)
                    break;
                want_methods = t == YAML_SCALAR_EVENT && !strcmp((const char *)w.ev.data.scalar.value, "methods");
                if (t != YAML_SCALAR_EVENT && !skip_node(&w))
                    break;
                root_key = 0;
                continue;
            }
            root_key = 1;
            if (want_methods && t == YAML_SEQUENCE_START_EVENT) {
                in_methods = 1;
                continue;
            }
            if (!skip_node(&w))
                break;
            continue;
        }
        if (in_methods) {
            if (t == YAML_SEQUENCE_END_EVENT) {
                in_methods = 0;
                want_methods = 0;
                continue;
            }
            if (t == YAML_MAPPING_START_EVENT && i < max)
                e = entry(&w, text, len, i, take, user, out, file, d);
            else if (!skip_node(&w))
                break;
            i++;
            continue;
        }
        if (t == YAML_MAPPING_START_EVENT && depth == 0) {
            depth = 1;
            continue;
        }
        if (t == YAML_STREAM_START_EVENT || t == YAML_DOCUMENT_START_EVENT)
            continue;
        break;   /* the root is not a mapping: the loader says so */
    }
    if (w.have)
        yaml_event_delete(&w.ev);
    yaml_parser_delete(&w.p);
    return e;
}
