/*
 * yamlfile.c — see yamlfile.h.
 * Invariants: the binding visits the tree in the file's order and stops at
 * the first error, as libcyaml's loader stopped at the first bad event, so
 * a file with several errors names the same first one; every allocation is
 * linked into the output (and a sequence's count written) before its
 * value is read, so cyaml_free frees a half-bound output whole; every
 * error leaves *out NULL and names file (or -D value), line and key.
 */
#define _POSIX_C_SOURCE 200809L
#include "yamlfile.h"
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include "suggest.h"
#include "util.h"

struct bind {
    const struct sl_yaml_pos *t;
    enum sl_err               kind;
    struct sl_diag           *d;
    const struct sl_ynode    *whole;   /* the first integer not in decimal digits (reported last) */
};

/* Fail naming node n's source (the file, or the -D value it came from),
 * the line (0 for a -D value's node) and n's key path, or `key` if given. */
static enum sl_err fail_at(struct bind *b, const struct sl_ynode *n, int line, const char *key, const char *fmt, ...)
    __attribute__((format(printf, 5, 6)));
static enum sl_err fail_at(struct bind *b, const struct sl_ynode *n, int line, const char *key, const char *fmt, ...)
{
    /* 256: libcyaml's texts (a value quoted whole) were cut there */
    char msg[256], path[96];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    if (!key)
        sl_ynode_path(n, path, sizeof path);
    else
        snprintf(path, sizeof path, "%s", key);
    return sl_fail(b->d, b->kind, sl_ynode_source(b->t, n), n && n->origin ? 0 : line, path[0] ? path : NULL, "%s",
                   msg);
}

/* "a.b" + ".c", or "c" at the top */
static void key_path(const struct sl_ynode *map, const char *name, char *buf, size_t n)
{
    size_t k = sl_ynode_path(map, buf, n);
    snprintf(buf + k, n - k, "%s%s", k ? "." : "", name);
}

/* Is t a whole number in decimal ([+-]digits)? libcyaml read integers with
 * strtoll(.., 0) and ignored what follows the digits: "7.9" and "1e3"
 * loaded as 7 and 1, "010" as 8. */
static int is_decimal(const char *t)
{
    if (*t == '+' || *t == '-')
        t++;
    if (!*t || (t[0] == '0' && t[1]))
        return 0;
    for (; *t; t++)
        if (*t < '0' || *t > '9')
            return 0;
    return 1;
}

/* An integer of `size` bytes, as the host lays out that C type. */
static int put_int(uint8_t *data, uint64_t v, size_t size)
{
    uint8_t u8 = (uint8_t)v;
    uint16_t u16 = (uint16_t)v;
    uint32_t u32 = (uint32_t)v;
    switch (size) {
    case 1: memcpy(data, &u8, 1); return 1;
    case 2: memcpy(data, &u16, 2); return 1;
    case 4: memcpy(data, &u32, 4); return 1;
    case 8: memcpy(data, &v, 8); return 1;
    }
    return 0;
}

static const char *type_name(cyaml_type_e t)
{
    switch (t) {
    case CYAML_INT: return "INT";
    case CYAML_UINT: return "UINT";
    case CYAML_BOOL: return "BOOL";
    case CYAML_ENUM: return "ENUM";
    case CYAML_FLAGS: return "FLAGS";
    case CYAML_FLOAT: return "FLOAT";
    case CYAML_STRING: return "STRING";
    case CYAML_MAPPING: return "MAPPING";
    case CYAML_BITFIELD: return "BITFIELD";
    case CYAML_SEQUENCE: return "SEQUENCE";
    case CYAML_SEQUENCE_FIXED: return "SEQUENCE_FIXED";
    default: return "IGNORE";
    }
}

/* What a value of schema type t is, in the words a config's author uses
 * (the messages say "expected <this>, got <what the file has>"; libcyaml's
 * own "Expecting SEQUENCE, got event: SCALAR" named libyaml's events). */
static const char *type_words(cyaml_type_e t)
{
    switch (t) {
    case CYAML_INT: return "a whole number";
    case CYAML_UINT: return "a whole number, 0 or more";
    case CYAML_BOOL: return "true or false";
    case CYAML_FLOAT: return "a number";
    case CYAML_STRING: return "a word or a quoted text";
    case CYAML_MAPPING: return "a mapping (key: value lines)";
    case CYAML_SEQUENCE:
    case CYAML_SEQUENCE_FIXED: return "a list ([a, b] or '- a' lines)";
    default: return "a single value";
    }
}

/* What node n is, for "got ...": a scalar quoted with its text (cut at
 * 60 bytes), else the kind of node. */
static const char *node_words(const struct sl_ynode *n, char *buf, size_t size)
{
    if (n->kind == SL_YSCALAR)
        snprintf(buf, size, "'%.60s'%s", n->text, strlen(n->text) > 60 ? "..." : "");
    else
        snprintf(buf, size, "%s", n->kind == SL_YSEQ ? "a list" : "a mapping (key: value lines)");
    return buf;
}

/* A scalar into data, as libcyaml read each type (its texts too). */
static enum sl_err read_scalar(struct bind *b, const cyaml_schema_value_t *s, const struct sl_ynode *n, uint8_t *data)
{
    const char *v = n->text;
    char *end = NULL;
    switch (s->type) {
    case CYAML_INT: {
        if (s->data_size == 0 || s->data_size > 8)
            break;
        int64_t max = (int64_t)((UINT64_MAX >> ((8 - s->data_size) * 8)) / 2), min = -max - 1;
        errno = 0;
        long long x = strtoll(v, &end, 0);
        if (end == v || errno == ERANGE || x < min || x > max)
            return fail_at(b, n, n->line, NULL, "expected %s, got '%s'", type_words(s->type), v);
        if (!b->whole && !is_decimal(v))
            b->whole = n;
        return put_int(data, (uint64_t)x, s->data_size) ? SL_OK : fail_at(b, n, n->line, NULL, "%s", "bad schema");
    }
    case CYAML_UINT: {
        if (s->data_size == 0 || s->data_size > 8)
            break;
        errno = 0;
        unsigned long long x = strtoull(v, &end, 0);
        /* strtoull takes "-1" as 2^64 - 1: a sign is refused first */
        if (end == v || errno == ERANGE || v[strspn(v, " \t")] == '-')
            return fail_at(b, n, n->line, NULL, "expected %s, got '%s'", type_words(s->type), v);
        if (x > (~(uint64_t)0) >> ((8 - s->data_size) * 8))
            return fail_at(b, n, n->line, NULL, "expected %s of at most %llu, got '%s'", type_words(s->type),
                           (unsigned long long)((~(uint64_t)0) >> ((8 - s->data_size) * 8)), v);
        if (!b->whole && !is_decimal(v))
            b->whole = n;
        return put_int(data, (uint64_t)x, s->data_size) ? SL_OK : fail_at(b, n, n->line, NULL, "%s", "bad schema");
    }
    case CYAML_BOOL: {
        /* libcyaml: one of these words (any case) is false, anything else true */
        static const char *const no[] = {"false", "no", "off", "disable", "0"};
        int x = 1;
        for (size_t i = 0; i < sizeof no / sizeof no[0]; i++)
            if (strcasecmp(v, no[i]) == 0)
                x = 0;
        if (put_int(data, (uint64_t)x, s->data_size))
            return SL_OK;
        break;
    }
    case CYAML_FLOAT:
        errno = 0;
        if (s->data_size == sizeof(float)) {
            float x = strtof(v, &end);
            if (end == v)
                return fail_at(b, n, n->line, NULL, "expected %s, got '%s'", type_words(s->type), v);
            if (errno == ERANGE && (s->flags & CYAML_FLAG_STRICT))
                return fail_at(b, n, n->line, NULL, "expected %s, got '%s': too %s for a float", type_words(s->type),
                               v, x == HUGE_VALF || x == -HUGE_VALF ? "large" : "small");
            memcpy(data, &x, sizeof x);
            return SL_OK;
        }
        if (s->data_size == sizeof(double)) {
            double x = strtod(v, &end);
            if (end == v)
                return fail_at(b, n, n->line, NULL, "expected %s, got '%s'", type_words(s->type), v);
            if (errno == ERANGE && (s->flags & CYAML_FLAG_STRICT))
                return fail_at(b, n, n->line, NULL, "expected %s, got '%s': out of a double's range",
                               type_words(s->type), v);
            memcpy(data, &x, sizeof x);
            return SL_OK;
        }
        break;
    case CYAML_STRING: {
        size_t len = strlen(v);
        if (len < s->string.min)
            return fail_at(b, n, n->line, NULL, "expected a text of at least %u characters, got '%s'",
                           (unsigned)s->string.min, v);
        if (len > s->string.max)
            return fail_at(b, n, n->line, NULL, "expected a text of at most %u characters, got '%.60s%s' (%zu)",
                           (unsigned)s->string.max, v, len > 60 ? "..." : "", len);
        memcpy(data, v, len + 1);
        return SL_OK;
    }
    default:
        break;
    }
    return fail_at(b, n, n->line, NULL, "the schema's %s of %u bytes is not read", type_name(s->type),
                   (unsigned)s->data_size);
}

static enum sl_err bind_value(struct bind *b, const cyaml_schema_value_t *s, const struct sl_ynode *n,
                              uint8_t *data, uint8_t *count, size_t count_size);

/* A mapping's pairs into data, by the schema's fields. */
static enum sl_err bind_map(struct bind *b, const cyaml_schema_value_t *s, const struct sl_ynode *n, uint8_t *data)
{
    const cyaml_schema_field_t *f = s->mapping.fields;
    unsigned nf = 0;
    while (f && f[nf].key)
        nf++;
    unsigned char seen[256];
    if (nf > sizeof seen)
        return fail_at(b, n, n->line, NULL, "the schema's mapping has more than %zu fields", sizeof seen);
    memset(seen, 0, nf);
    char key[160];
    for (unsigned i = 0; i < n->n; i++) {
        const struct sl_ynode *k = n->kid[2 * i], *v = n->kid[2 * i + 1];
        if (v->taken)
            continue;
        if (k->kind != SL_YSCALAR) {
            sl_ynode_path(n, key, sizeof key);
            return fail_at(b, k, k->line, key, "a key is a plain word, not a mapping or a list");
        }
        key_path(n, k->text, key, sizeof key);
        unsigned j = 0;
        while (j < nf && strcmp(f[j].key, k->text) != 0)
            j++;
        if (j == nf) {
            struct sl_suggest sg;
            char hint[96];
            sl_suggest_init(&sg, k->text);
            for (unsigned q = 0; q < nf; q++)
                sl_suggest_add(&sg, f[q].key);
            return fail_at(b, k, k->line, key, "unknown key '%s'%s", k->text, sl_suggest_text(&sg, hint, sizeof hint));
        }
        if (seen[j])
            return fail_at(b, k, k->line, key, "the key '%s' is given twice", k->text);
        seen[j] = 1;
        enum sl_err e = bind_value(b, &f[j].value, v, data + f[j].data_offset, data + f[j].count_offset,
                                   f[j].count_size);
        if (e)
            return e;
    }
    for (unsigned j = 0; j < nf; j++)
        if (!seen[j] && !(f[j].value.flags & CYAML_FLAG_OPTIONAL)) {
            key_path(n, f[j].key, key, sizeof key);
            /* the line of the mapping; the top level's is the whole file */
            return fail_at(b, n, n->parent ? n->line : 0, key, "missing required key");
        }
    return SL_OK;
}

/* A sequence's entries into a growing array whose pointer is at data and
 * whose count is at count (count_size bytes). */
static enum sl_err bind_seq(struct bind *b, const cyaml_schema_value_t *s, const struct sl_ynode *n, uint8_t *data,
                            uint8_t *count, size_t count_size)
{
    if (!(s->flags & CYAML_FLAG_POINTER) || !count)
        return fail_at(b, n, n->line, NULL, "the schema's list is not read here");
    uint8_t *base = NULL;
    size_t es = s->data_size;
    for (unsigned i = 0; i < n->n; i++) {
        const struct sl_ynode *v = n->kid[i];
        if (i + 1 > s->sequence.max) {
            /* named by the list, at the line of the first entry too many */
            char key[96];
            sl_ynode_path(n, key, sizeof key);
            return fail_at(b, v, v->line, key, "more than %u entries: at most %u are allowed",
                           (unsigned)s->sequence.max, (unsigned)s->sequence.max);
        }
        uint8_t *grown = realloc(base, (i + 1) * es);
        if (!grown)
            return sl_fail(b->d, SL_E_NOMEM, sl_ynode_source(b->t, n), 0, NULL, "binding the YAML tree");
        base = grown;
        memset(base + i * es, 0, es);
        memcpy(data, &base, sizeof base);
        if (!put_int(count, i + 1, count_size))
            return fail_at(b, n, n->line, NULL, "the schema's count of %zu bytes is not read", count_size);
        enum sl_err e = bind_value(b, s->sequence.entry, v, base + i * es, NULL, 0);
        if (e)
            return e;
    }
    if (n->n < s->sequence.min)
        return fail_at(b, n, n->line, NULL, "expected a list of at least %u entr%s, got %u", (unsigned)s->sequence.min,
                       s->sequence.min == 1 ? "y" : "ies", n->n);
    return SL_OK;
}

static enum sl_err bind_value(struct bind *b, const cyaml_schema_value_t *s, const struct sl_ynode *n,
                              uint8_t *data, uint8_t *count, size_t count_size)
{
    int want = s->type == CYAML_MAPPING ? SL_YMAP : s->type == CYAML_SEQUENCE ? SL_YSEQ : SL_YSCALAR;
    if (n->kind != want) {
        char got[80];
        return fail_at(b, n, n->line, NULL, "expected %s, got %s", type_words(s->type), node_words(n, got, sizeof got));
    }
    if (s->type == CYAML_SEQUENCE)
        return bind_seq(b, s, n, data, count, count_size);
    if (s->flags & CYAML_FLAG_POINTER) {
        size_t size = s->type == CYAML_STRING ? strlen(n->text) + 1 : s->data_size;
        void *p = calloc(1, size ? size : 1);
        if (!p)
            return sl_fail(b->d, SL_E_NOMEM, sl_ynode_source(b->t, n), 0, NULL, "binding the YAML tree");
        memcpy(data, &p, sizeof p);
        data = p;
    }
    if (s->type == CYAML_MAPPING)
        return bind_map(b, s, n, data);
    return read_scalar(b, s, n, data);
}

static const cyaml_config_t *cy_config(void)
{
    static const cyaml_config_t c = {.mem_fn = cyaml_mem, .log_level = CYAML_LOG_ERROR};
    return &c;
}

enum sl_err sl_yaml_bind(const struct sl_yaml_pos *t, const cyaml_schema_value_t *schema, void **out,
                         enum sl_err kind, struct sl_diag *d)
{
    *out = NULL;
    const struct sl_ynode *root = sl_ytree_root(t);
    const char *file = sl_ytree_file(t);
    if (!root)
        return sl_fail(d, kind, file, 0, NULL, "empty file: no YAML mapping");
    if (root->kind != SL_YMAP)
        return sl_fail(d, kind, file, root->line, NULL, "the file is %s: it must be a YAML mapping (key: value lines)",
                       root->kind == SL_YSEQ ? "a sequence" : "a scalar");
    if (schema->type != CYAML_MAPPING || !(schema->flags & CYAML_FLAG_POINTER))
        return sl_fail(d, kind, file, 0, NULL, "the schema's top level is not a mapping read by pointer");
    struct bind b = {t, kind, d, NULL};
    void *data = NULL;
    enum sl_err e = bind_value(&b, schema, root, (uint8_t *)&data, NULL, 0);
    if (!e && b.whole) {
        /* after the rest, as before: the first error of another kind wins */
        e = fail_at(&b, b.whole, b.whole->line, NULL,
                    "'%.31s' is not a whole number (an integer in decimal digits is expected)", b.whole->text);
    }
    if (e) {
        cyaml_free(cy_config(), schema, data, 0);
        return e;
    }
    *out = data;
    return SL_OK;
}

enum sl_err sl_yaml_load(const char *path, const cyaml_schema_value_t *schema, void **out,
                         struct sl_yaml_pos **pos, size_t max_bytes, enum sl_err kind, struct sl_diag *d)
{
    *out = NULL;
    *pos = NULL;
    struct sl_yaml_pos *t;
    enum sl_err e = sl_ytree_read(path, max_bytes, kind, &t, d);
    if (e)
        return e;
    e = sl_yaml_bind(t, schema, out, kind, d);
    if (e) {
        sl_ytree_free(t);
        return e;
    }
    *pos = t;
    return SL_OK;
}

void sl_yaml_free(const cyaml_schema_value_t *schema, void *data, struct sl_yaml_pos *pos)
{
    if (data)
        cyaml_free(cy_config(), schema, data, 0);
    sl_ytree_free(pos);
}

int sl_yaml_line(const struct sl_yaml_pos *pos, const char *path)
{
    if (!pos || !path || !path[0])
        return 0;
    return sl_ynode_line(sl_ytree_find(pos, path));
}

enum sl_err sl_yaml_bad(struct sl_diag *d, enum sl_err kind, const char *file,
                        const struct sl_yaml_pos *ix, const char *key, const char *fmt, ...)
{
    char msg[400];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    return sl_fail(d, kind, file, sl_yaml_line(ix, key), key, "%s", msg);
}

enum sl_err sl_yaml_ref_check(struct sl_diag *d, enum sl_err kind, const char *file,
                              const struct sl_yaml_pos *ix, const char *key, const char *target)
{
    const char *bad = sl_file_type_bad(target);
    return bad ? sl_yaml_bad(d, kind, file, ix, key, "%s is %s, not a regular file: refused unread", target, bad)
               : SL_OK;
}
