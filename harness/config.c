/*
 * config.c — see config.h.
 * Invariants: sl_config_load either fills *out completely (every default
 * explicit, every name resolved) or returns an error with a place; the cyaml
 * tree never escapes this file.
 */
#define _POSIX_C_SOURCE 200809L
#include "config.h"
#include <cyaml/cyaml.h>
#include <errno.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <yaml.h>
#include "scene.h"
#include "util.h"

/* ---- raw schema (what libcyaml fills) ---- */

struct raw_viewport { unsigned width, height; };
struct raw_method {
    char  *label;
    char  *method;
    char  *self_shadow;
    float *bias;
    float *slope;
};
struct raw_outputs { bool *overlays; unsigned *overlay_contour; };
struct raw_config {
    char *name;
    char *scene;
    char **viewpoints; unsigned viewpoints_count;
    struct raw_viewport *viewports; unsigned viewports_count;
    unsigned *map_sizes; unsigned map_sizes_count;
    unsigned *contours; unsigned contours_count;
    struct raw_method *methods; unsigned methods_count;
    struct raw_outputs *outputs;
    unsigned *threads;
};

static const cyaml_schema_value_t str_schema = {
    CYAML_VALUE_STRING(CYAML_FLAG_POINTER, char, 1, 63),
};
static const cyaml_schema_value_t uint_schema = {
    CYAML_VALUE_UINT(CYAML_FLAG_DEFAULT, unsigned),
};
static const cyaml_schema_field_t viewport_fields[] = {
    CYAML_FIELD_UINT("width", CYAML_FLAG_DEFAULT, struct raw_viewport, width),
    CYAML_FIELD_UINT("height", CYAML_FLAG_DEFAULT, struct raw_viewport, height),
    CYAML_FIELD_END,
};
static const cyaml_schema_value_t viewport_schema = {
    CYAML_VALUE_MAPPING(CYAML_FLAG_DEFAULT, struct raw_viewport, viewport_fields),
};
static const cyaml_schema_field_t method_fields[] = {
    CYAML_FIELD_STRING_PTR("label", CYAML_FLAG_POINTER | CYAML_FLAG_OPTIONAL, struct raw_method, label, 1, 47),
    CYAML_FIELD_STRING_PTR("method", CYAML_FLAG_POINTER, struct raw_method, method, 1, 63),
    CYAML_FIELD_STRING_PTR("self_shadow", CYAML_FLAG_POINTER | CYAML_FLAG_OPTIONAL, struct raw_method, self_shadow, 1, 63),
    CYAML_FIELD_FLOAT_PTR("bias", CYAML_FLAG_POINTER | CYAML_FLAG_OPTIONAL, struct raw_method, bias),
    CYAML_FIELD_FLOAT_PTR("slope", CYAML_FLAG_POINTER | CYAML_FLAG_OPTIONAL, struct raw_method, slope),
    CYAML_FIELD_END,
};
static const cyaml_schema_value_t method_schema = {
    CYAML_VALUE_MAPPING(CYAML_FLAG_DEFAULT, struct raw_method, method_fields),
};
static const cyaml_schema_field_t outputs_fields[] = {
    CYAML_FIELD_BOOL_PTR("overlays", CYAML_FLAG_POINTER | CYAML_FLAG_OPTIONAL, struct raw_outputs, overlays),
    CYAML_FIELD_UINT_PTR("overlay_contour", CYAML_FLAG_POINTER | CYAML_FLAG_OPTIONAL, struct raw_outputs, overlay_contour),
    CYAML_FIELD_END,
};
static const cyaml_schema_field_t config_fields[] = {
    CYAML_FIELD_STRING_PTR("name", CYAML_FLAG_POINTER | CYAML_FLAG_OPTIONAL, struct raw_config, name, 1, 63),
    CYAML_FIELD_STRING_PTR("scene", CYAML_FLAG_POINTER, struct raw_config, scene, 1, 63),
    CYAML_FIELD_SEQUENCE("viewpoints", CYAML_FLAG_POINTER | CYAML_FLAG_OPTIONAL, struct raw_config,
                         viewpoints, &str_schema, 1, SL_CFG_MAX),
    CYAML_FIELD_SEQUENCE("viewports", CYAML_FLAG_POINTER | CYAML_FLAG_OPTIONAL, struct raw_config,
                         viewports, &viewport_schema, 1, SL_CFG_MAX),
    CYAML_FIELD_SEQUENCE("map_sizes", CYAML_FLAG_POINTER, struct raw_config, map_sizes, &uint_schema,
                         1, SL_CFG_MAX),
    CYAML_FIELD_SEQUENCE("contours", CYAML_FLAG_POINTER | CYAML_FLAG_OPTIONAL, struct raw_config,
                         contours, &uint_schema, 1, SL_CFG_MAX - 1),
    CYAML_FIELD_SEQUENCE("methods", CYAML_FLAG_POINTER, struct raw_config, methods, &method_schema,
                         1, SL_CFG_MAX),
    CYAML_FIELD_MAPPING_PTR("outputs", CYAML_FLAG_POINTER | CYAML_FLAG_OPTIONAL, struct raw_config,
                            outputs, outputs_fields),
    CYAML_FIELD_UINT_PTR("threads", CYAML_FLAG_POINTER | CYAML_FLAG_OPTIONAL, struct raw_config, threads),
    CYAML_FIELD_END,
};
static const cyaml_schema_value_t config_schema = {
    CYAML_VALUE_MAPPING(CYAML_FLAG_POINTER, struct raw_config, config_fields),
};

/* ---- position index: dotted key path -> line, built with libyaml ---- */

struct pos_entry { char path[128]; int line; };
struct pos_index { struct pos_entry *e; int n, cap; };

static void pos_add(struct pos_index *ix, const char *path, int line)
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
static void pos_build(const char *path, struct pos_index *ix)
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

static int pos_line(const struct pos_index *ix, const char *path)
{
    for (int i = 0; i < ix->n; i++)
        if (strcmp(ix->e[i].path, path) == 0)
            return ix->e[i].line;
    return 0;
}

/* First path whose last component is key, at or after line `from`. */
static const struct pos_entry *pos_find_key(const struct pos_index *ix, const char *key, int from)
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

/* ---- validation ---- */

static enum sl_err bad(struct sl_diag *d, const char *file, const struct pos_index *ix,
                       const char *key, const char *fmt, ...) __attribute__((format(printf, 5, 6)));
static enum sl_err bad(struct sl_diag *d, const char *file, const struct pos_index *ix,
                       const char *key, const char *fmt, ...)
{
    char msg[400];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    return sl_fail(d, SL_E_CONFIG, file, pos_line(ix, key), key, "%s", msg);
}

static int is_pow2(unsigned v) { return v && !(v & (v - 1)); }

static enum sl_err validate(const struct raw_config *r, const char *file, const struct pos_index *ix,
                            struct sl_config *c, struct sl_diag *d)
{
    char key[96];
    snprintf(c->name, sizeof c->name, "%s", r->name ? r->name : "default");
    for (const char *p = c->name; *p; p++)
        if (!((*p >= 'a' && *p <= 'z') || (*p >= 'A' && *p <= 'Z') || (*p >= '0' && *p <= '9') ||
              *p == '-' || *p == '_' || *p == '.') || c->name[0] == '.')
            return bad(d, file, ix, "name", "'%s': use letters, digits, '-', '_' and '.' only", c->name);

    snprintf(c->scene, sizeof c->scene, "%s", r->scene);
    struct sl_scene s;
    struct sl_diag sd;
    if (sl_scene_build(c->scene, &s, &sd) != SL_OK) {
        char known[256] = "";
        for (int i = 0; i < sl_scene_count(); i++)
            snprintf(known + strlen(known), sizeof known - strlen(known), "%s%s", i ? ", " : "",
                     sl_scene_name(i));
        return bad(d, file, ix, "scene", "unknown scene '%s' (known: %s)", c->scene, known);
    }
    c->nviewpoints = (int)r->viewpoints_count;
    for (unsigned i = 0; i < r->viewpoints_count; i++) {
        snprintf(key, sizeof key, "viewpoints[%u]", i);
        if (sl_scene_find_viewpoint(&s, r->viewpoints[i]) < 0) {
            char known[256] = "";
            for (int k = 0; k < s.nvp; k++)
                snprintf(known + strlen(known), sizeof known - strlen(known), "%s%s", k ? ", " : "",
                         s.vp[k].name);
            sl_scene_free(&s);
            return bad(d, file, ix, key, "scene '%s' has no viewpoint '%s' (it has: %s)",
                       c->scene, r->viewpoints[i], known);
        }
        snprintf(c->viewpoints[i], sizeof c->viewpoints[i], "%s", r->viewpoints[i]);
    }
    sl_scene_free(&s);

    if (r->viewports_count == 0) {
        c->nviewports = 1;
        c->viewport_w[0] = c->viewport_h[0] = 1024;
    }
    for (unsigned i = 0; i < r->viewports_count; i++) {
        snprintf(key, sizeof key, "viewports[%u]", i);
        if (r->viewports[i].width < 16 || r->viewports[i].width > 8192 ||
            r->viewports[i].height < 16 || r->viewports[i].height > 8192)
            return bad(d, file, ix, key, "viewport %ux%u: width and height must be in 16..8192",
                       r->viewports[i].width, r->viewports[i].height);
        c->viewport_w[i] = (int)r->viewports[i].width;
        c->viewport_h[i] = (int)r->viewports[i].height;
        c->nviewports = (int)i + 1;
    }
    for (unsigned i = 0; i < r->map_sizes_count; i++) {
        snprintf(key, sizeof key, "map_sizes[%u]", i);
        unsigned m = r->map_sizes[i];
        if (!is_pow2(m) || m < 64 || m > 16384)
            return bad(d, file, ix, key, "map size %u: must be a power of two in 64..16384", m);
        c->maps[i] = (int)m;
    }
    c->nmaps = (int)r->map_sizes_count;

    static const unsigned default_contours[] = {2, 4, 6};
    const unsigned *ct = r->contours_count ? r->contours : default_contours;
    unsigned nct = r->contours_count ? r->contours_count : 3;
    for (unsigned i = 0; i < nct; i++) {
        snprintf(key, sizeof key, "contours[%u]", i);
        if (ct[i] == 0 || ct[i] % 2 || ct[i] > 64)
            return bad(d, file, ix, key, "contour thickness %u: must be even, 2..64 pixels", ct[i]);
        if (i && ct[i] <= ct[i - 1])
            return bad(d, file, ix, key, "contour thicknesses must increase");
        c->regions[i] = (int)ct[i];
    }
    c->regions[nct] = 0;
    c->nregions = (int)nct + 1;

    for (unsigned i = 0; i < r->methods_count; i++) {
        const struct raw_method *rm = &r->methods[i];
        struct sl_config_method *cm = &c->methods[i];
        snprintf(key, sizeof key, "methods[%u].method", i);
        cm->method = sl_method_find(rm->method);
        if (!cm->method) {
            char known[256] = "";
            for (int k = 0; k < sl_method_count(); k++)
                snprintf(known + strlen(known), sizeof known - strlen(known), "%s%s", k ? ", " : "",
                         sl_method_at(k)->name);
            return bad(d, file, ix, key, "unknown method '%s' (known: %s)", rm->method, known);
        }
        snprintf(cm->label, sizeof cm->label, "%s", rm->label ? rm->label : rm->method);
        snprintf(key, sizeof key, "methods[%u].label", i);
        for (const char *p = cm->label; *p; p++)
            if (!((*p >= 'a' && *p <= 'z') || (*p >= 'A' && *p <= 'Z') || (*p >= '0' && *p <= '9') ||
                  *p == '-' || *p == '_' || *p == '.'))
                return bad(d, file, ix, key, "label '%s': use letters, digits, '-', '_' and '.'", cm->label);
        for (unsigned k = 0; k < i; k++)
            if (strcmp(c->methods[k].label, cm->label) == 0)
                return bad(d, file, ix, rm->label ? key : (snprintf(key, sizeof key, "methods[%u]", i), key),
                           "label '%s' used twice: give each entry its own label", cm->label);
        struct sl_method_params *p = &cm->params;
        memset(p, 0, sizeof *p);
        if (rm->self_shadow) {
            p->set |= SL_PARAM_SELF_SHADOW;
            p->self_shadow = sl_self_shadow_parse(rm->self_shadow);
            snprintf(key, sizeof key, "methods[%u].self_shadow", i);
            if (p->self_shadow < 0)
                return bad(d, file, ix, key,
                           "unknown self-shadow policy '%s' (known: none, constant, slope, "
                           "front_faces, triangle_id)", rm->self_shadow);
        }
        if (rm->bias) {
            p->set |= SL_PARAM_BIAS;
            p->bias = *rm->bias;
        }
        if (rm->slope) {
            p->set |= SL_PARAM_SLOPE;
            p->slope = *rm->slope;
        }
        static const struct { unsigned bit; const char *name; } pk[] = {
            {SL_PARAM_SELF_SHADOW, "self_shadow"}, {SL_PARAM_BIAS, "bias"}, {SL_PARAM_SLOPE, "slope"},
        };
        for (size_t k = 0; k < sizeof pk / sizeof pk[0]; k++)
            if ((p->set & pk[k].bit) && !(cm->method->params_ok & pk[k].bit)) {
                snprintf(key, sizeof key, "methods[%u].%s", i, pk[k].name);
                return bad(d, file, ix, key, "method '%s' takes no parameter '%s'",
                           cm->method->name, pk[k].name);
            }
        struct sl_diag md;
        if (cm->method->configure(p, &md) != SL_OK) {
            snprintf(key, sizeof key, "methods[%u]%s%s", i, md.key[0] ? "." : "", md.key);
            int line = pos_line(ix, key);
            if (!line) {
                snprintf(key, sizeof key, "methods[%u]", i);
                line = pos_line(ix, key);
                snprintf(key, sizeof key, "methods[%u]%s%s", i, md.key[0] ? "." : "", md.key);
            }
            return sl_fail(d, SL_E_CONFIG, file, line, key, "%s", md.msg);
        }
    }
    c->nmethods = (int)r->methods_count;

    c->overlays = r->outputs && r->outputs->overlays ? *r->outputs->overlays : 1;
    c->overlay_contour = c->regions[0];
    if (r->outputs && r->outputs->overlay_contour) {
        unsigned t = *r->outputs->overlay_contour;
        int found = 0;
        for (int k = 0; k < c->nregions; k++)
            found |= c->regions[k] == (int)t;
        if (!found)
            return bad(d, file, ix, "outputs.overlay_contour",
                       "overlay_contour %u is not one of the contours (or 0: the whole image)", t);
        c->overlay_contour = (int)t;
    }
    long cores = sysconf(_SC_NPROCESSORS_ONLN);
    c->threads = r->threads && *r->threads ? (int)*r->threads : (int)(cores > 0 ? cores : 1);
    if (c->threads > 256)
        return bad(d, file, ix, "threads", "threads %d: at most 256", c->threads);
    return SL_OK;
}

enum sl_err sl_config_load(const char *path, struct sl_config *out, struct sl_diag *d)
{
    memset(out, 0, sizeof *out);
    snprintf(out->path, sizeof out->path, "%s", path);
    if (access(path, R_OK) != 0)
        return sl_fail(d, SL_E_IO, path, 0, NULL, "cannot read config: %s", strerror(errno));
    enum sl_err e = sl_hash_file(path, &out->hash, d);
    if (e)
        return e;
    struct cy_log lg;
    memset(&lg, 0, sizeof lg);
    struct raw_config *raw = NULL;
    const cyaml_config_t *cfg = cy_config(&lg);
    cyaml_err_t ce = cyaml_load_file(path, cfg, &config_schema, (cyaml_data_t **)&raw, NULL);
    struct pos_index ix = {0};
    pos_build(path, &ix);
    if (ce != CYAML_OK) {
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
            const struct pos_entry *pe = pos_find_key(&ix, k, line);
            snprintf(key, sizeof key, "%s", pe ? pe->path : k);
            line = pe ? pe->line : line;
            e = sl_fail(d, SL_E_CONFIG, path, line, key, "unknown key '%s'", k);
        } else if (is_missing) {
            size_t k = strlen(key);
            snprintf(key + k, sizeof key - k, "%s%s", k ? "." : "", lg.first + strlen(missing));
            line = lg.ntrace > 1 ? lg.trace_line[1] : 0;
            e = sl_fail(d, SL_E_CONFIG, path, line, key, "missing required key");
        } else {
            e = sl_fail(d, SL_E_CONFIG, path, line, key[0] ? key : NULL, "%s",
                        lg.first[0] ? lg.first : cyaml_strerror(ce));
        }
        free(ix.e);
        return e;
    }
    e = validate(raw, path, &ix, out, d);
    cyaml_free(cfg, &config_schema, raw, 0);
    free(ix.e);
    return e;
}

void sl_config_write(const struct sl_config *c, FILE *f)
{
    fprintf(f, "# filled-in config: every default explicit\n");
    fprintf(f, "name: %s\nscene: %s\n", c->name, c->scene);
    fprintf(f, "viewpoints: [");
    for (int i = 0; i < c->nviewpoints; i++)
        fprintf(f, "%s%s", i ? ", " : "", c->viewpoints[i]);
    fprintf(f, "]%s\n", c->nviewpoints ? "" : "   # all of the scene's");
    fprintf(f, "viewports:\n");
    for (int i = 0; i < c->nviewports; i++)
        fprintf(f, "  - {width: %d, height: %d}\n", c->viewport_w[i], c->viewport_h[i]);
    fprintf(f, "map_sizes: [");
    for (int i = 0; i < c->nmaps; i++)
        fprintf(f, "%s%d", i ? ", " : "", c->maps[i]);
    fprintf(f, "]\ncontours: [");
    for (int i = 0; i + 1 < c->nregions; i++)
        fprintf(f, "%s%d", i ? ", " : "", c->regions[i]);
    fprintf(f, "]\nmethods:\n");
    for (int i = 0; i < c->nmethods; i++) {
        const struct sl_method_params *p = &c->methods[i].params;
        fprintf(f, "  - {label: %s, method: %s", c->methods[i].label, c->methods[i].method->name);
        if (p->set & SL_PARAM_SELF_SHADOW)
            fprintf(f, ", self_shadow: %s", sl_self_shadow_name(p->self_shadow));
        if (p->set & SL_PARAM_BIAS)
            fprintf(f, ", bias: %g", (double)p->bias);
        if (p->set & SL_PARAM_SLOPE)
            fprintf(f, ", slope: %g", (double)p->slope);
        fprintf(f, "}\n");
    }
    fprintf(f, "outputs: {overlays: %s, overlay_contour: %d}\n", c->overlays ? "true" : "false",
            c->overlay_contour);
    fprintf(f, "threads: %d\n", c->threads);
}
