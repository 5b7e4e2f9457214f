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
#include <unistd.h>
#include <yaml.h>
#include "util.h"

/* ---- position index: dotted key path -> line, built with libyaml ---- */

struct pos_entry { char path[128]; int line; };
struct sl_yaml_pos { struct pos_entry *e; int n, cap; };

static void pos_add(struct sl_yaml_pos *ix, const char *path, int line)
{
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

/* Walk the event stream keeping, per nesting level, the path and whether the
 * next scalar of a mapping is a key. Errors of the YAML syntax itself are
 * left to libcyaml, which reports them with their line. */
static void pos_build(const char *path, struct sl_yaml_pos *ix)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return;
    yaml_parser_t p;
    yaml_parser_initialize(&p);
    yaml_parser_set_input_file(&p, f);
    struct { char path[128]; int is_map, want_key, index; char key[64]; } st[32];
    int depth = -1;
    for (;;) {
        yaml_event_t ev;
        if (!yaml_parser_parse(&p, &ev))
            break;
        yaml_event_type_t t = ev.type;
        int line = (int)ev.start_mark.line + 1;
        char here[128] = "";
        int is_value = 0;
        if (depth >= 0 && (t == YAML_SCALAR_EVENT || t == YAML_MAPPING_START_EVENT ||
                           t == YAML_SEQUENCE_START_EVENT)) {
            if (st[depth].is_map && st[depth].want_key && t == YAML_SCALAR_EVENT) {
                snprintf(st[depth].key, sizeof st[depth].key, "%s", (const char *)ev.data.scalar.value);
                snprintf(here, sizeof here, "%s%s%s", st[depth].path, st[depth].path[0] ? "." : "",
                         st[depth].key);
                pos_add(ix, here, line);
                st[depth].want_key = 0;
            } else if (st[depth].is_map) {
                snprintf(here, sizeof here, "%s%s%s", st[depth].path, st[depth].path[0] ? "." : "",
                         st[depth].key);
                st[depth].want_key = 1;
                is_value = 1;
            } else {
                snprintf(here, sizeof here, "%s[%d]", st[depth].path, st[depth].index++);
                pos_add(ix, here, line);
                is_value = 1;
            }
        } else if (depth < 0) {
            is_value = 1;
        }
        if ((t == YAML_MAPPING_START_EVENT || t == YAML_SEQUENCE_START_EVENT) && is_value && depth < 31) {
            depth++;
            snprintf(st[depth].path, sizeof st[depth].path, "%s", here);
            st[depth].is_map = t == YAML_MAPPING_START_EVENT;
            st[depth].want_key = 1;
            st[depth].index = 0;
            st[depth].key[0] = '\0';
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
    fclose(f);
}

int sl_yaml_line(const struct sl_yaml_pos *ix, const char *path)
{
    if (!ix)
        return 0;
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
    c.flags = CYAML_CFG_DEFAULT;
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


enum sl_err sl_yaml_load(const char *path, const cyaml_schema_value_t *schema, void **out,
                         struct sl_yaml_pos **pos, enum sl_err kind, struct sl_diag *d)
{
    *out = NULL;
    *pos = NULL;
    if (access(path, R_OK) != 0)
        return sl_fail(d, SL_E_IO, path, 0, NULL, "cannot read: %s", strerror(errno));
    struct cy_log lg;
    memset(&lg, 0, sizeof lg);
    const cyaml_config_t *cfg = cy_config(&lg);
    struct sl_yaml_pos *ix = calloc(1, sizeof *ix);
    if (!ix)
        return sl_fail(d, SL_E_NOMEM, path, 0, NULL, "position index");
    pos_build(path, ix);
    cyaml_err_t ce = cyaml_load_file(path, cfg, schema, (cyaml_data_t **)out, NULL);
    if (ce == CYAML_OK && *out) {
        *pos = ix;
        return SL_OK;
    }
    if (ce == CYAML_OK) {
        /* an empty document loads as nothing at all */
        free(ix->e);
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
    const char *unexpected = "Unexpected key: ";
    if (strncmp(lg.first, unexpected, strlen(unexpected)) == 0) {
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
        e = sl_fail(d, kind, path, line, key[0] ? key : NULL, "%s",
                    lg.first[0] ? lg.first : cyaml_strerror(ce));
    }
    free(ix->e);
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
        free(pos);
    }
}
