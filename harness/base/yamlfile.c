/*
 * yamlfile.c — see yamlfile.h.
 * Invariant: every error leaves *out NULL and names file, line and key as
 * far as libcyaml's backtrace and our libyaml position index can tell.
 */
#define _POSIX_C_SOURCE 200809L
#include "yamlfile.h"
#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <stdint.h>
#include <sys/stat.h>
#include <unistd.h>
#include <yaml.h>
#include "util.h"

/* ---- position index: dotted key path -> line, built with libyaml ---- */

struct pos_entry { char path[128]; int line; };
struct sl_yaml_pos {
    struct pos_entry *e;
    int n, cap, max;      /* max: entries kept at most (see pos_build) */
    int root_line;        /* line of the top-level node, 0 if none */
    yaml_event_type_t root_type;
    int err_line;         /* libyaml's own error: line (0 if none) and text */
    char err[128];
    int int_line;         /* first integer key whose text is not a whole number: line, path, text */
    char int_path[128], int_text[32];
    int alias_line;       /* first alias (*name): line, path, anchor name; see pos_build */
    char alias_path[128], alias_name[32];
    int *slot;            /* hash of path -> entry index + 1 (0: empty), nslot a power of two */
    size_t nslot;
};

static uint64_t path_hash(const char *p)
{
    uint64_t h = 1469598103934665603ull;
    for (; *p; p++)
        h = (h ^ (unsigned char)*p) * 1099511628211ull;
    return h;
}

/* After pos_build: a lookup by path costs O(1), so a loader that asks the
 * line of every entry (4096 meshes) stays linear in the file. The first
 * entry of a path wins, as the linear search it replaces did. */
static void pos_hash(struct sl_yaml_pos *ix)
{
    size_t n = 16;
    while (n < 2 * (size_t)ix->n)
        n *= 2;
    ix->slot = calloc(n, sizeof *ix->slot);
    if (!ix->slot)
        return;   /* sl_yaml_line falls back to the linear search */
    ix->nslot = n;
    for (int i = 0; i < ix->n; i++) {
        size_t k = (size_t)path_hash(ix->e[i].path) & (n - 1);
        while (ix->slot[k] && strcmp(ix->e[ix->slot[k] - 1].path, ix->e[i].path) != 0)
            k = (k + 1) & (n - 1);
        if (!ix->slot[k])
            ix->slot[k] = i + 1;
    }
}

static void pos_add(struct sl_yaml_pos *ix, const char *path, int line)
{
    if (ix->n >= ix->max)
        return;
    if (ix->n == ix->cap) {
        int cap = ix->cap ? 2 * ix->cap : 64;
        void *p = realloc(ix->e, (size_t)cap * sizeof *ix->e);
        if (!p)
            return;
        ix->e = p;
        ix->cap = cap;
    }
    snprintf(ix->e[ix->n].path, sizeof ix->e[ix->n].path, "%s", path);
    ix->e[ix->n].line = line;
    ix->n++;
}

/* Is t a whole number in decimal ([+-]digits)? libcyaml reads integers with
 * strtoll(.., 0) and ignores what follows the digits: "7.9" and "1e3" would
 * load as 7 and 1, "010" as 8. */
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

/* The schema of the value under key in a mapping's schema (NULL if none). */
static const cyaml_schema_value_t *field_schema(const cyaml_schema_value_t *m, const char *key)
{
    if (!m || m->type != CYAML_MAPPING)
        return NULL;
    for (const cyaml_schema_field_t *f = m->mapping.fields; f && f->key; f++)
        if (strcmp(f->key, key) == 0)
            return &f->value;
    return NULL;
}

/* Walk the event stream keeping, per nesting level, the path, whether the
 * next scalar of a mapping is a key, and the schema of what comes next (so
 * that a scalar given where the schema wants an integer is checked to be a
 * whole number). Errors of the YAML syntax itself are left to libcyaml,
 * which reports them with their line; libyaml's own line is kept as a
 * fallback for errors libcyaml gives none for. The nesting is at most
 * SL_YAML_MAX_DEPTH here (sl_yaml_depth ran first) plus what -D overrides
 * graft, so the stack is fixed; levels past it are counted, not kept. The
 * index keeps at most ix->max entries, so a huge file costs bounded memory
 * here: the schema's entry limits (checked by libcyaml) reject such a file
 * anyway, and only its lines beyond the cap go unnamed. One pass, constant
 * work per event: linear in the file. */
static void pos_build(const unsigned char *text, size_t len, const cyaml_schema_value_t *schema,
                      struct sl_yaml_pos *ix)
{
    yaml_parser_t p;
    yaml_parser_initialize(&p);
    yaml_parser_set_input_string(&p, text, len);
    enum { NST = 2 * SL_YAML_MAX_DEPTH };
    struct {
        char path[128];
        int is_map, want_key, index;
        char key[64];
        const cyaml_schema_value_t *sv;   /* this container's schema */
        const cyaml_schema_value_t *next; /* a mapping's: the schema of the value of `key` */
    } st[NST];
    int depth = -1, over = 0;
    for (;;) {
        yaml_event_t ev;
        if (!yaml_parser_parse(&p, &ev)) {
            ix->err_line = (int)p.problem_mark.line + 1;
            snprintf(ix->err, sizeof ix->err, "%s", p.problem ? p.problem : "syntax error");
            break;
        }
        yaml_event_type_t t = ev.type;
        int line = (int)ev.start_mark.line + 1;
        if (depth < 0 && !ix->root_line && (t == YAML_SCALAR_EVENT || t == YAML_MAPPING_START_EVENT ||
                                            t == YAML_SEQUENCE_START_EVENT || t == YAML_ALIAS_EVENT)) {
            ix->root_line = line;
            ix->root_type = t;
        }
        int start = t == YAML_MAPPING_START_EVENT || t == YAML_SEQUENCE_START_EVENT;
        if (t == YAML_ALIAS_EVENT && !ix->alias_line) {
            /* refused by the loader: name the key it stands for */
            ix->alias_line = line;
            snprintf(ix->alias_name, sizeof ix->alias_name, "%s", (const char *)ev.data.alias.anchor);
            if (depth >= 0 && !over && st[depth].is_map)
                snprintf(ix->alias_path, sizeof ix->alias_path, "%s%s%s", st[depth].path,
                         st[depth].path[0] && !st[depth].want_key ? "." : "",
                         st[depth].want_key ? "" : st[depth].key);
            else if (depth >= 0 && !over)
                snprintf(ix->alias_path, sizeof ix->alias_path, "%s[%d]", st[depth].path, st[depth].index);
        }
        if (over) {   /* inside levels the stack does not keep */
            over += start;
            over -= t == YAML_MAPPING_END_EVENT || t == YAML_SEQUENCE_END_EVENT;
            yaml_event_delete(&ev);
            continue;
        }
        char here[128] = "";
        int is_value = 0;
        const cyaml_schema_value_t *vs = NULL;   /* the schema of this value */
        if (depth >= 0 && (t == YAML_SCALAR_EVENT || start)) {
            if (st[depth].is_map && st[depth].want_key && t == YAML_SCALAR_EVENT) {
                snprintf(st[depth].key, sizeof st[depth].key, "%s", (const char *)ev.data.scalar.value);
                snprintf(here, sizeof here, "%s%s%s", st[depth].path, st[depth].path[0] ? "." : "",
                         st[depth].key);
                pos_add(ix, here, line);
                st[depth].want_key = 0;
                st[depth].next = field_schema(st[depth].sv, st[depth].key);
            } else if (st[depth].is_map) {
                snprintf(here, sizeof here, "%s%s%s", st[depth].path, st[depth].path[0] ? "." : "",
                         st[depth].key);
                st[depth].want_key = 1;
                is_value = 1;
                vs = st[depth].next;
            } else {
                snprintf(here, sizeof here, "%s[%d]", st[depth].path, st[depth].index++);
                pos_add(ix, here, line);
                is_value = 1;
                vs = st[depth].sv && (st[depth].sv->type == CYAML_SEQUENCE ||
                                      st[depth].sv->type == CYAML_SEQUENCE_FIXED) ? st[depth].sv->sequence.entry
                                                                                  : NULL;
            }
        } else if (depth < 0) {
            is_value = 1;
            vs = schema;
        }
        if (t == YAML_SCALAR_EVENT && is_value && vs && (vs->type == CYAML_INT || vs->type == CYAML_UINT) &&
            !ix->int_line && !is_decimal((const char *)ev.data.scalar.value)) {
            ix->int_line = line;
            snprintf(ix->int_path, sizeof ix->int_path, "%s", here);
            snprintf(ix->int_text, sizeof ix->int_text, "%s", (const char *)ev.data.scalar.value);
        }
        if (start && is_value) {
            if (depth + 1 < NST) {
                depth++;
                snprintf(st[depth].path, sizeof st[depth].path, "%s", here);
                st[depth].is_map = t == YAML_MAPPING_START_EVENT;
                st[depth].want_key = 1;
                st[depth].index = 0;
                st[depth].key[0] = '\0';
                st[depth].sv = vs;
                st[depth].next = NULL;
            } else {
                over = 1;
            }
        } else if (t == YAML_MAPPING_END_EVENT || t == YAML_SEQUENCE_END_EVENT) {
            if (depth >= 0)
                depth--;
        }
        int end = t == YAML_STREAM_END_EVENT;
        yaml_event_delete(&ev);
        if (end)
            break;
    }
    yaml_parser_delete(&p);
}

int sl_yaml_depth(const unsigned char *text, size_t len, int max, int *line, char *key, size_t nkey)
{
    /* libyaml's scanner checks every open flow level ('[' or '{') for each
     * token it reads, so a file nested N deep costs N² before any schema
     * sees it (200,000 levels: minutes); stopping at the first level past
     * max costs at most a line's worth of tokens. Block nesting ("- - - x",
     * indentation) is counted the same way. */
    yaml_parser_t p;
    if (!yaml_parser_initialize(&p))
        return -1;
    yaml_parser_set_input_string(&p, text, len);
    int depth = 0, deepest = 0, top_map = 0, want_key = 1;
    *line = 0;
    if (key && nkey)
        key[0] = '\0';
    for (;;) {
        yaml_event_t ev;
        if (!yaml_parser_parse(&p, &ev))
            break;   /* a syntax error: the loader names it */
        yaml_event_type_t t = ev.type;
        if (depth == 0 && t == YAML_MAPPING_START_EVENT)
            top_map = 1;
        if (depth == 1 && top_map && (t == YAML_SCALAR_EVENT || t == YAML_ALIAS_EVENT ||
                                      t == YAML_MAPPING_START_EVENT || t == YAML_SEQUENCE_START_EVENT)) {
            /* the top-level key the nesting is under names it */
            if (want_key && t == YAML_SCALAR_EVENT && key && nkey)
                snprintf(key, nkey, "%s", (const char *)ev.data.scalar.value);
            want_key = !want_key;
        }
        if (t == YAML_MAPPING_START_EVENT || t == YAML_SEQUENCE_START_EVENT) {
            if (++depth > deepest)
                deepest = depth;
            if (depth > max) {
                *line = (int)ev.start_mark.line + 1;
                yaml_event_delete(&ev);
                break;
            }
        } else if (t == YAML_MAPPING_END_EVENT || t == YAML_SEQUENCE_END_EVENT) {
            depth--;
        }
        int end = t == YAML_STREAM_END_EVENT;
        yaml_event_delete(&ev);
        if (end)
            break;
    }
    yaml_parser_delete(&p);
    return deepest;
}

int sl_yaml_line(const struct sl_yaml_pos *ix, const char *path)
{
    if (!ix)
        return 0;
    if (ix->slot) {
        size_t k = (size_t)path_hash(path) & (ix->nslot - 1);
        for (; ix->slot[k]; k = (k + 1) & (ix->nslot - 1))
            if (strcmp(ix->e[ix->slot[k] - 1].path, path) == 0)
                return ix->e[ix->slot[k] - 1].line;
        return 0;
    }
    for (int i = 0; i < ix->n; i++)
        if (strcmp(ix->e[i].path, path) == 0)
            return ix->e[i].line;
    return 0;
}

/* First path whose last component is key, at or after line `from`. */
static const struct pos_entry *pos_find_key(const struct sl_yaml_pos *ix, const char *key, int from)
{
    size_t k = strlen(key);
    for (int pass = 0; pass < 2; pass++)
        for (int i = 0; i < ix->n; i++) {
            const char *p = ix->e[i].path;
            size_t n = strlen(p);
            if (n < k || strcmp(p + n - k, key) != 0 || (n > k && p[n - k - 1] != '.'))
                continue;
            if (pass == 0 && ix->e[i].line < from)
                continue;
            return &ix->e[i];
        }
    return NULL;
}

/* ---- libcyaml log capture ---- */

struct cy_log { char first[256]; char trace[8][128]; int trace_line[8]; int ntrace; };

static void cy_log_fn(cyaml_log_t level, void *ctx, const char *fmt, va_list args)
{
    struct cy_log *lg = ctx;
    if (level < CYAML_LOG_ERROR)
        return;
    char buf[256];
    vsnprintf(buf, sizeof buf, fmt, args);
    size_t n = strlen(buf);
    while (n && (buf[n - 1] == '\n' || buf[n - 1] == ' '))
        buf[--n] = '\0';
    const char *s = buf;
    if (strncmp(s, "Load: ", 6) == 0)
        s += 6;
    if (strncmp(s, "Backtrace:", 10) == 0)
        return;
    while (*s == ' ')
        s++;
    if (strncmp(s, "in ", 3) == 0) {
        if (lg->ntrace < 8) {
            /* "in mapping field 'maps' (line: 2, column: 7)" or "in sequence entry '2' (...)" */
            const char *q1 = strchr(s, '\''), *q2 = q1 ? strchr(q1 + 1, '\'') : NULL;
            const char *ln = strstr(s, "line: ");
            lg->trace[lg->ntrace][0] = '\0';
            if (q1 && q2) {
                int is_entry = strstr(s, "sequence entry") != NULL;
                int len = (int)(q2 - q1 - 1);
                if (is_entry) /* libcyaml counts entries from 1 here; paths count from 0 */
                    snprintf(lg->trace[lg->ntrace], 128, "[%d]", atoi(q1 + 1) - 1);
                else
                    snprintf(lg->trace[lg->ntrace], 128, "%.*s", len, q1 + 1);
            }
            lg->trace_line[lg->ntrace] = ln ? atoi(ln + 6) : 0;
            lg->ntrace++;
        }
        return;
    }
    if (!lg->first[0])
        snprintf(lg->first, sizeof lg->first, "%s", s);
}

static const cyaml_config_t *cy_config(struct cy_log *lg)
{
    static cyaml_config_t c;
    memset(&c, 0, sizeof c);
    c.log_fn = cy_log_fn;
    c.log_ctx = lg;
    c.mem_fn = cyaml_mem;
    c.log_level = CYAML_LOG_ERROR;
    c.flags = CYAML_CFG_NO_ALIAS;   /* refused before, by pos_build; never expanded */
    return &c;
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

/* Read the whole file, refusing it before reading when it is over
 * max_bytes (the caller's limit for its kind of file). */
static enum sl_err read_text(const char *path, size_t max_bytes, unsigned char **text, size_t *len,
                             enum sl_err kind, struct sl_diag *d)
{
    *text = NULL;
    *len = 0;
    int fd;
    long long size;
    enum sl_err e = sl_open_regular(path, &fd, &size, d);   /* no FIFO, device or folder */
    if (e)
        return e;
    if ((unsigned long long)size > (unsigned long long)max_bytes) {
        close(fd);
        return sl_fail(d, kind, path, 0, NULL, "file of %lld bytes: at most %zu MiB are read for this kind of file",
                       size, max_bytes >> 20);
    }
    /* +1 so a file that grew since fstat is seen as over the limit; the
     * reads stop there whatever the file does */
    size_t cap = (size_t)size + 1;
    unsigned char *buf = malloc(cap);
    if (!buf) {
        close(fd);
        return sl_fail(d, SL_E_NOMEM, path, 0, NULL, "reading the file");
    }
    size_t n = 0;
    int err = 0;
    while (n < cap) {
        ssize_t k = read(fd, buf + n, cap - n);
        if (k < 0 && errno == EINTR)
            continue;
        if (k < 0)
            err = errno;
        if (k <= 0)
            break;
        n += (size_t)k;
    }
    close(fd);
    if (err) {
        free(buf);
        return sl_fail(d, SL_E_IO, path, 0, NULL, "cannot read: %s", strerror(err));
    }
    if (n > (size_t)size) {
        free(buf);
        return sl_fail(d, kind, path, 0, NULL, "the file grew while being read");
    }
    *text = buf;
    *len = n;
    return SL_OK;
}

/* libyaml refuses bytes that are not UTF-8 text and control characters
 * without saying where; find the first such byte and name its line. */
static enum sl_err check_text(const char *path, const unsigned char *s, size_t n, enum sl_err kind,
                              struct sl_diag *d)
{
    int line = 1;
    size_t col0 = 0;
    for (size_t i = 0; i < n;) {
        unsigned c = s[i];
        if (c == '\n') {
            line++;
            col0 = ++i;
            continue;
        }
        if (c < 0x80) {
            if ((c < 0x20 && c != '\t' && c != '\r') || c == 0x7f)
                return sl_fail(d, kind, path, line, NULL, "%s (byte 0x%02x at column %zu): not YAML text",
                               c == 0 ? "NUL byte" : "control character", c, i - col0 + 1);
            i++;
            continue;
        }
        /* a UTF-8 sequence: lead byte, then 1..3 continuation bytes;
         * overlong forms and surrogates are refused as libyaml does */
        size_t k = c >= 0xc2 && c <= 0xdf ? 1 : c >= 0xe0 && c <= 0xef ? 2 : c >= 0xf0 && c <= 0xf4 ? 3 : 0;
        int ok = k > 0 && i + k < n;
        uint32_t cp = k == 1 ? c & 0x1f : k == 2 ? c & 0x0f : c & 0x07;
        for (size_t j = 1; ok && j <= k; j++) {
            if ((s[i + j] & 0xc0) != 0x80)
                ok = 0;
            cp = (cp << 6) | (s[i + j] & 0x3f);
        }
        if (ok && ((k == 2 && (cp < 0x800 || (cp >= 0xd800 && cp <= 0xdfff))) ||
                   (k == 3 && (cp < 0x10000 || cp > 0x10ffff))))
            ok = 0;
        if (!ok)
            return sl_fail(d, kind, path, line, NULL, "byte 0x%02x at column %zu is not UTF-8 text", c,
                           i - col0 + 1);
        i += k + 1;
    }
    return SL_OK;
}

static const char *event_name(yaml_event_type_t t)
{
    return t == YAML_SEQUENCE_START_EVENT ? "a sequence" : t == YAML_SCALAR_EVENT ? "a scalar"
         : t == YAML_ALIAS_EVENT ? "an alias" : "not a mapping";
}

enum sl_err sl_yaml_load(const char *path, const cyaml_schema_value_t *schema, void **out,
                         struct sl_yaml_pos **pos, size_t max_bytes, enum sl_err kind, struct sl_diag *d)
{
    return sl_yaml_load_edited(path, schema, out, pos, max_bytes, kind, NULL, NULL, d);
}

enum sl_err sl_yaml_load_edited(const char *path, const cyaml_schema_value_t *schema, void **out,
                                struct sl_yaml_pos **pos, size_t max_bytes, enum sl_err kind,
                                sl_yaml_edit_fn edit, void *edit_user, struct sl_diag *d)
{
    *out = NULL;
    *pos = NULL;
    unsigned char *text;
    size_t len;
    enum sl_err re = read_text(path, max_bytes, &text, &len, kind, d);
    if (!re)
        re = check_text(path, text, len, kind, d);
    int deep_line = 0;
    char deep_key[64];
    if (!re && sl_yaml_depth(text, len, SL_YAML_MAX_DEPTH, &deep_line, deep_key, sizeof deep_key) > SL_YAML_MAX_DEPTH)
        re = sl_fail(d, kind, path, deep_line, deep_key[0] ? deep_key : NULL, "nested more than %d levels deep: "
                     "refused before it is read further", SL_YAML_MAX_DEPTH);
    if (!re && edit)
        re = edit(&text, &len, edit_user, d);
    if (re) {
        free(text);
        return re;
    }
    struct cy_log lg;
    memset(&lg, 0, sizeof lg);
    const cyaml_config_t *cfg = cy_config(&lg);
    struct sl_yaml_pos *ix = calloc(1, sizeof *ix);
    if (!ix) {
        free(text);
        return sl_fail(d, SL_E_NOMEM, path, 0, NULL, "position index");
    }
    /* one entry per 64 bytes of the limit, at least 65536: far more than
     * the schemas' entry limits let through (132 bytes each) */
    ix->max = (int)(max_bytes / 64 > 65536 ? (max_bytes / 64 < (1u << 22) ? max_bytes / 64 : (1u << 22)) : 65536);
    pos_build(text, len, schema, ix);
    pos_hash(ix);
    if (ix->alias_line) {
        /* libcyaml would expand each alias into a copy of its anchor's
         * node: a 7 MB baseline of '- *c' lines took 3.2 GB and 22 s, and
         * the amplification has no bound. No file of shadowlab needs one. */
        free(text);
        enum sl_err e = sl_fail(d, kind, path, ix->alias_line, ix->alias_path[0] ? ix->alias_path : NULL,
                                "an alias (*%s): YAML anchors and aliases are not read, write the value "
                                "out (an alias can expand a small file into gigabytes)", ix->alias_name);
        free(ix->e);
        free(ix->slot);
        free(ix);
        return e;
    }
    cyaml_err_t ce = cyaml_load_data(text, len, cfg, schema, (cyaml_data_t **)out, NULL);
    free(text);
    if (ce == CYAML_OK && *out && ix->int_line) {
        cyaml_free(cfg, schema, *out, 0);
        *out = NULL;
        enum sl_err e = sl_fail(d, kind, path, ix->int_line, ix->int_path[0] ? ix->int_path : NULL,
                                "'%s' is not a whole number (an integer in decimal digits is expected)",
                                ix->int_text);
        free(ix->e);
        free(ix->slot);
        free(ix);
        return e;
    }
    if (ce == CYAML_OK && *out) {
        *pos = ix;
        return SL_OK;
    }
    if (ce == CYAML_OK) {
        /* an empty document loads as nothing at all */
        free(ix->e);
        free(ix->slot);
        free(ix);
        return sl_fail(d, kind, path, 0, NULL, "empty file: no YAML mapping");
    }
    *out = NULL;
    enum sl_err e;
    char key[96] = "";
    int line = 0;
    const char *missing = "Missing required mapping field: ";
    int is_missing = strncmp(lg.first, missing, strlen(missing)) == 0;
    /* outermost first: libcyaml prints the innermost frame first; for a
     * missing field the innermost frame is the last field it did read,
     * a sibling, so the path stops at the parent mapping */
    for (int i = lg.ntrace - 1; i >= (is_missing ? 1 : 0); i--) {
        const char *t = lg.trace[i];
        if (!t[0])
            continue;
        size_t k = strlen(key);
        snprintf(key + k, sizeof key - k, "%s%s", (k && t[0] != '[') ? "." : "", t);
    }
    if (lg.ntrace)
        line = lg.trace_line[0];
    const char *unexpected = "Unexpected key: ", *excessive = "Excessive entries";
    const char *expecting = "Expecting MAPPING, got event";
    if (lg.ntrace == 0 && strncmp(lg.first, expecting, strlen(expecting)) == 0) {
        /* the whole file is a sequence or a scalar */
        e = sl_fail(d, kind, path, ix->root_line, NULL, "the file is %s: it must be a YAML mapping (key: value lines)",
                    event_name(ix->root_type));
    } else if (strncmp(lg.first, excessive, strlen(excessive)) == 0) {
        /* libcyaml's frame is the entry it refused, one past the last it
         * kept: name the sequence, at the line of that entry */
        char *br = strrchr(key, '[');
        int max = 0;
        const char *mx = strchr(lg.first, '(');
        if (mx)
            max = atoi(mx + 1);
        char entry[128];
        snprintf(entry, sizeof entry, "%s[%d]", br ? (*br = '\0', key) : key, max);
        int eline = sl_yaml_line(ix, entry);
        e = sl_fail(d, kind, path, eline ? eline : line, key[0] ? key : NULL,
                    "more than %d entries: at most %d are allowed", max, max);
    } else if (strncmp(lg.first, unexpected, strlen(unexpected)) == 0) {
        const char *k = lg.first + strlen(unexpected);
        const struct pos_entry *pe = pos_find_key(ix, k, line);
        snprintf(key, sizeof key, "%s", pe ? pe->path : k);
        line = pe ? pe->line : line;
        e = sl_fail(d, kind, path, line, key, "unknown key '%s'", k);
    } else if (is_missing) {
        size_t k = strlen(key);
        snprintf(key + k, sizeof key - k, "%s%s", k ? "." : "", lg.first + strlen(missing));
        line = lg.ntrace > 1 ? lg.trace_line[1] : 0;
        e = sl_fail(d, kind, path, line, key, "missing required key");
    } else {
        if (!line && ix->err_line) /* libyaml's own error, which libcyaml gives no line for */
            line = ix->err_line;
        e = sl_fail(d, kind, path, line, key[0] ? key : NULL, "%s",
                    lg.first[0] ? lg.first : cyaml_strerror(ce));
    }
    free(ix->e);
    free(ix->slot);
    free(ix);
    return e;
}

void sl_yaml_free(const cyaml_schema_value_t *schema, void *data, struct sl_yaml_pos *pos)
{
    if (data) {
        struct cy_log lg;
        memset(&lg, 0, sizeof lg);
        cyaml_free(cy_config(&lg), schema, data, 0);
    }
    if (pos) {
        free(pos->e);
        free(pos->slot);
        free(pos);
    }
}
