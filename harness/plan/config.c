/*
 * config.c — see config.h.
 * Invariants: sl_config_load either fills *out completely (every default
 * explicit, every name resolved) or returns an error with a place; the cyaml
 * tree never escapes this file.
 */
#define _POSIX_C_SOURCE 200809L
#define _DEFAULT_SOURCE   /* realpath */
#include "config.h"
#include <cyaml/cyaml.h>
#include "figures.h"
#include <errno.h>
#include <math.h>
#include <sys/stat.h>
#include <limits.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "method.h"
#include "reps.h"
#include "package.h"
#include "session.h"
#include "techcheck.h"
#include "scene.h"
#include "scenefile.h"
#include "suggest.h"
#include "util.h"
#include "yamlfile.h"

/* ---- raw schema (what libcyaml fills) ---- */

struct raw_viewport { unsigned width, height; };
struct raw_lframe { char *fit; bool *snap; };
struct raw_method {
    char  *label;
    char  *display;
    char  *method;
    struct raw_lframe *light_frame;
    /* every other key is a parameter of the method, taken from the entry
     * before the schema reads it (below: method_entry) */
};
struct raw_scene_ref {
    char *scene;
    char **viewpoints; unsigned viewpoints_count;
    char **paths; unsigned paths_count;
    unsigned *map_sizes; unsigned map_sizes_count;
    char **methods; unsigned methods_count;
};

static const cyaml_schema_value_t str_schema = {
    CYAML_VALUE_STRING(CYAML_FLAG_POINTER, char, 1, 63),
};
static const cyaml_schema_value_t path_schema = {
    CYAML_VALUE_STRING(CYAML_FLAG_POINTER, char, 1, 511),
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
static const cyaml_schema_field_t lframe_fields[] = {
    CYAML_FIELD_STRING_PTR("fit", CYAML_FLAG_POINTER | CYAML_FLAG_OPTIONAL, struct raw_lframe, fit, 1, 15),
    CYAML_FIELD_BOOL_PTR("snap", CYAML_FLAG_POINTER | CYAML_FLAG_OPTIONAL, struct raw_lframe, snap),
    CYAML_FIELD_END,
};
static const cyaml_schema_field_t method_fields[] = {
    CYAML_FIELD_MAPPING_PTR("light_frame", CYAML_FLAG_POINTER | CYAML_FLAG_OPTIONAL, struct raw_method, light_frame,
                            lframe_fields),
    CYAML_FIELD_STRING_PTR("label", CYAML_FLAG_POINTER | CYAML_FLAG_OPTIONAL, struct raw_method, label, 1, 47),
    CYAML_FIELD_STRING_PTR("display", CYAML_FLAG_POINTER | CYAML_FLAG_OPTIONAL, struct raw_method, display, 1, 47),
    CYAML_FIELD_STRING_PTR("method", CYAML_FLAG_POINTER, struct raw_method, method, 1, 63),
    CYAML_FIELD_END,
};
static const cyaml_schema_value_t method_schema = {
    CYAML_VALUE_MAPPING(CYAML_FLAG_DEFAULT, struct raw_method, method_fields),
};
static const cyaml_schema_field_t scene_ref_fields[] = {
    CYAML_FIELD_STRING_PTR("scene", CYAML_FLAG_POINTER, struct raw_scene_ref, scene, 1, 255),
    CYAML_FIELD_SEQUENCE("viewpoints", CYAML_FLAG_POINTER | CYAML_FLAG_OPTIONAL, struct raw_scene_ref,
                         viewpoints, &str_schema, 1, SL_MAX_VIEWPOINTS),
    CYAML_FIELD_SEQUENCE("paths", CYAML_FLAG_POINTER | CYAML_FLAG_OPTIONAL, struct raw_scene_ref,
                         paths, &str_schema, 1, SL_MAX_PATHS),
    CYAML_FIELD_SEQUENCE("map_sizes", CYAML_FLAG_POINTER | CYAML_FLAG_OPTIONAL, struct raw_scene_ref,
                         map_sizes, &uint_schema, 1, SL_CFG_MAX),
    CYAML_FIELD_SEQUENCE("methods", CYAML_FLAG_POINTER | CYAML_FLAG_OPTIONAL, struct raw_scene_ref,
                         methods, &str_schema, 1, SL_CFG_MAX),
    CYAML_FIELD_END,
};
static const cyaml_schema_value_t scene_ref_schema = {
    CYAML_VALUE_MAPPING(CYAML_FLAG_DEFAULT, struct raw_scene_ref, scene_ref_fields),
};
/* ---- the settings: the keys whose value is one scalar ----
 * One line each: the field of struct sl_config (config.h) it sets and its
 * declaration (base/params.h: the key's path, type, default, range or
 * words, doc), the one form every method's parameters take too. From this
 * line come the check of its value (take_settings: at its line, before the
 * schema binds the rest of the tree), its field, its text in the filled-in
 * config and its row in the reference; a group of them (outputs.*,
 * repetitions.*) is a mapping of those keys and no other. A new setting
 * is its line here, its field, and the code that reads it. What the
 * declaration cannot say is checked where it is resolved (check_outputs:
 * overlay_contour is one of the contours; check_threads: 0 is every core;
 * check_gl: default is SHADOWLAB_GL, else the build's). */
#define CONFIG_SETTINGS(X)                                                                                  \
    X(contour_from, SL_PARAM_CHOICE_DECL("contour_from", SL_CONTOUR_NSM,                                   \
        "nsm (default: one contour per view and map, from NSM's image, shared by every method) or own "     \
        "(each method's own image)", "nsm", "own"))                                                         \
    X(tables, SL_PARAM_BOOL_DECL("outputs.tables", 1, "table.md, table.tex, table-detail.tex, figures.csv (default true)")) \
    X(overlays, SL_PARAM_BOOL_DECL("outputs.overlays", 1, "an error-overlay PNG per cell (default true)"))  \
    X(overlay_contour, SL_PARAM_INT_DECL("outputs.overlay_contour", 0, 0, 64, "pixels",                     \
        "the contour thickness the overlays draw, one of contours or 0 for the whole image (default: the "  \
        "thinnest)"))                                                                                       \
    X(exr, SL_PARAM_BOOL_DECL("outputs.exr", 0, "the truth, verdicts and error as OpenEXR layers per cell (default false)")) \
    X(visibility, SL_PARAM_CHOICE_DECL("outputs.visibility", 0, "none (default) or exr: each cell's visibility as " \
        "scored, visibility/<cell>.exr (V; A 0, V NaN on background; Z linear depth), as `shadowlab grade` " \
        "reads it", "none", "exr"))                          \
    X(aliasing, SL_PARAM_CHOICE_DECL("outputs.aliasing", 2, "the aliasing error m per pixel: auto (default: where " \
        "a method that reads it runs: zpart, lispsm), true or false", "false", "true", "auto"))             \
    X(rep_mode, SL_PARAM_CHOICE_DECL("repetitions.mode", SL_REP_ADAPTIVE, "how often a timed stage runs: "  \
        "adaptive (default: until spread, runs, budget_ms or share stops it; a study costs at most 1 + share " \
        "times once), fixed (warmup + runs) or off (once)", "adaptive", "fixed", "off"))                        \
    X(warmup, SL_PARAM_INT_DECL("repetitions.warmup", 1, 0, 100, "", "mode fixed: untimed runs first (default 1)")) \
    X(runs, SL_PARAM_INT_DECL("repetitions.runs", 5, 1, 1000, "",                                           \
        "timed runs (median, min, max kept): fixed exactly, adaptive at most (default 5; one is marked "  \
        "\"timed once\")"))                                                             \
    X(rep_spread, SL_PARAM_FLOAT_DECL("repetitions.spread", 0.1, 0, 10, "",                                 \
        "adaptive: a stage stops once (max - min) / median of 3 or more timed runs is at most this " \
        "(default 0.1)"))                                                                                   \
    X(rep_budget_ms, SL_PARAM_FLOAT_DECL("repetitions.budget_ms", 100, 0, 1e6, "ms",                         \
        "adaptive: the most one stage's repetitions may take; a stage longer than this is timed once "  \
        "(default 100)"))                                                                                   \
    X(rep_share, SL_PARAM_FLOAT_DECL("repetitions.share", 0.3, 0, 100, "",                                  \
        "adaptive: all repetitions together at most this times the run's other wall time (default 0.3: " \
        "a study costs at most 1.3 times once)"))                                \
    X(seed, SL_PARAM_INT_DECL("seed", 1, 0, 4294967295.0, "", "for anything random (default 1)"))           \
    X(area_samples, SL_PARAM_INT_DECL("area_samples", 32, 2, 1024, "",                                      \
        "area lights: truth samples per side of the light (default 32: 1,024 a pixel)"))                   \
    X(threads, SL_PARAM_INT_DECL("threads", 0, 0, 256, "", "CPU threads (default 0: every core)"))          \
    X(gl, SL_PARAM_CHOICE_DECL("gl", SL_GL_DEFAULT, "the GL backend: osmesa or egl; default (the "  \
        "default): SHADOWLAB_GL, else osmesa", "default", "osmesa", "egl"))                                   \
    X(pass_seconds, SL_PARAM_FLOAT_DECL("limits.pass_seconds", 300, 0.1, 86400, "s",                       \
        "the longest a technique package's GL pass (map, post, lookup) may run: one running longer ends " \
        "the run, exit 2, naming the package and the pass (default 300)"))

static const struct sl_param config_settings[] = {
#define SETTING_DECL(field, decl) decl,
    CONFIG_SETTINGS(SETTING_DECL)
#undef SETTING_DECL
};
#define CONFIG_NSETTINGS ((int)(sizeof config_settings / sizeof config_settings[0]))
_Static_assert(sizeof config_settings / sizeof config_settings[0] <= SL_PARAM_MAX, "settings: at most SL_PARAM_MAX");

/* ---- the top-level keys ----
 * One line per key a config file may give, in the order the filled-in
 * config writes them; the only place a top-level key is listed. From this
 * list come struct raw_config (what libcyaml fills), its schema, its text
 * in the reference, and sl_config_write (one write_<key> function per key,
 * below: a key without one does not compile).
 *   X(key, kind, need, doc, type, args)
 * doc: the key's line in the reference (a SETTINGS group's row; "" for a
 * single setting, whose declaration has its text).
 *   UINT    an unsigned integer            type: unsigned
 *   STRING  1..max bytes                   type: char; args: max
 *   SEQ     a list of 1..max entries       type: an entry's; args: its schema, max
 *   MAP     a mapping of fields            type: the mapping's; args: its fields
 *   SETTINGS a setting (CONFIG_SETTINGS above), or a mapping of them: the
 *           declarations say all, and the schema never sees it
 * need: REQUIRED or OPTIONAL. The schema takes this order too; libcyaml's
 * field order shows only in which missing required key it names first
 * (scenes, then map_sizes, then methods).
 * Bespoke, beside the list:
 * - the checks and defaults (validate: one check_<concept> function each)
 *   run in an order of their own, not this one: a scene's own map sizes and
 *   methods draw on the top-level lists, and a config with several errors
 *   must keep naming the same first one;
 * - struct sl_config (config.h) holds resolved values, not one field per
 *   key: contours become regions (the whole image added), outputs and
 *   repetitions their fields, scenes their resolved files and masks. */
#define CONFIG_KEYS(X)                                                                             \
    X(name,         STRING, OPTIONAL, "the study's name: its folder under --out and its name in the store "   \
      "(default: default); letters, digits, -, _, .", char, 63)                                    \
    X(scenes,       SEQ,    REQUIRED, "the scenes, each by name (scenes/*.yaml; hard/tiny is "              \
      "scenes/hard/tiny.yaml) or by path (ending .yaml, relative to the config)",                 \
      struct raw_scene_ref, &scene_ref_schema, SL_CFG_MAX)                                         \
    X(viewports,    SEQ,    OPTIONAL, "the image sizes (default: one of 1024 x 1024)",                    \
      struct raw_viewport, &viewport_schema, SL_CFG_MAX)                                           \
    X(map_sizes,    SEQ,    REQUIRED, "shadow-map sizes: powers of two, 64..16384",                       \
      unsigned, &uint_schema, SL_CFG_MAX)                                                          \
    X(contours,     SEQ,    OPTIONAL, "contour thicknesses in pixels: even, 2..64, increasing (default "   \
      "[2, 4, 6]); the whole image is always added",                                               \
      unsigned, &uint_schema, SL_MAX_REGIONS - 1) /* + the whole image */                          \
    X(contour_from, SETTINGS, OPTIONAL, "", -)                                                        \
    X(methods,      SEQ,    REQUIRED, "the labelled methods; one method may appear under several labels, " \
      "and a parameter given as a list sweeps (one label per value)",                              \
      struct raw_method, &method_schema, SL_CFG_MAX)                                               \
    X(techniques,   SEQ,    OPTIONAL, "folders of technique packages, relative to the config (searched "   \
      "before SHADOWLAB_TECHNIQUES and the built-in ones)", char *, &path_schema, 8)               \
    X(outputs,      SETTINGS, OPTIONAL, "what a run writes beside the store", -)                      \
    X(repetitions,  SETTINGS, OPTIONAL, "how often the timed stages run (computed once, timed this often)", -) \
    X(seed,         SETTINGS, OPTIONAL, "", -)                                                        \
    X(area_samples, SETTINGS, OPTIONAL, "", -)                                                        \
    X(store,        STRING, OPTIONAL, "the results store, relative to the output root (default "           \
      "shadowlab.db); no \"..\", not absolute", char, 511)                                         \
    X(threads,      SETTINGS, OPTIONAL, "", -)                                                        \
    X(gl,           SETTINGS, OPTIONAL, "", -)                                                        \
    X(limits,       SETTINGS, OPTIONAL, "how long a technique package's pass may run", -)

#define CFG_RAW_UINT(key, type)                type *key;
#define CFG_RAW_STRING(key, type, max)         type *key;
#define CFG_RAW_SEQ(key, type, schema, max)    type *key; unsigned key##_count;
#define CFG_RAW_MAP(key, type, fields)         type *key;
#define CFG_RAW_SETTINGS(key, unused)          /* taken from the tree: config_settings */
struct raw_config {
#define RAW_KEY(key, kind, need, doc, ...) CFG_RAW_##kind(key, __VA_ARGS__)
    CONFIG_KEYS(RAW_KEY)
#undef RAW_KEY
};

#define CFG_REQUIRED CYAML_FLAG_POINTER
#define CFG_OPTIONAL (CYAML_FLAG_POINTER | CYAML_FLAG_OPTIONAL)
#define CFG_SCHEMA_UINT(key, need, type) CYAML_FIELD_UINT_PTR(#key, need, struct raw_config, key),
#define CFG_SCHEMA_STRING(key, need, type, max) CYAML_FIELD_STRING_PTR(#key, need, struct raw_config, key, 1, max),
#define CFG_SCHEMA_SEQ(key, need, type, schema, max) \
    CYAML_FIELD_SEQUENCE(#key, need, struct raw_config, key, schema, 1, max),
#define CFG_SCHEMA_MAP(key, need, type, fields) CYAML_FIELD_MAPPING_PTR(#key, need, struct raw_config, key, fields),
#define CFG_SCHEMA_SETTINGS(key, need, unused)
static const cyaml_schema_field_t config_fields[] = {
#define SCHEMA_KEY(key, kind, need, doc, ...) CFG_SCHEMA_##kind(key, CFG_##need, __VA_ARGS__)
    CONFIG_KEYS(SCHEMA_KEY)
#undef SCHEMA_KEY
    CYAML_FIELD_END,
};
static const cyaml_schema_value_t config_schema = {
    CYAML_VALUE_MAPPING(CYAML_FLAG_POINTER, struct raw_config, config_fields),
};

/* ---- the config reference: every key of the schema above, documented ----
 * `shadowlab help --config` (doc/config.md) and the man page's
 * CONFIGURATION section are written from the libcyaml schema itself, walked
 * key by key, with the one line of text each path has here, then each
 * built-in method's parameters from its declarations (base/params.h). A
 * schema key with no text here, or a text
 * for a key the schema has not, is an error of the generator, so the
 * reference cannot drift from what the parser takes. */
/* the top-level keys' text: their CONFIG_KEYS lines */
static const struct { const char *path, *doc; } top_docs[] = {
#define TOP_DOC(key, kind, need, doc, ...) {#key, doc},
    CONFIG_KEYS(TOP_DOC)
#undef TOP_DOC
};

/* the keys of a key's entries and mappings, by path */
static const struct { const char *path, *doc; } key_docs[] = {
    {"scenes[].scene", "the scene's name or path"},
    {"scenes[].viewpoints", "the scene's viewpoints to run (default: all of them)"},
    {"scenes[].paths", "the scene's paths of frames to run (errors over motion; default: none)"},
    {"scenes[].map_sizes", "this scene's own map sizes (default: the top-level map_sizes)"},
    {"scenes[].methods", "the labels this scene runs (default: every label that handles its light; validate and run name those left out; a label listed that cannot run under its light is an error)"},
    {"viewports[].width", "pixels, 16..8192"},
    {"viewports[].height", "pixels, 16..8192"},
    {"methods[].display", "the name LaTeX tables print for the label (default: the method's own display name when the label is the method's name, else the label); a sweep adds its [key=value]"},
    {"methods[].label", "the label tables and the store use (default: the method's name): letters, digits, -, _, . (not first)"},
    {"methods[].method", "a built-in method (shadowlab list methods) or a technique package (shadowlab list techniques); its parameters are keys of this entry too (below; shadowlab show method NAME, shadowlab show technique NAME)"},
    {"methods[].light_frame", "this label's own light frame (errors over motion)"},
    {"methods[].light_frame.fit", "tight (default: the view's receivers) or sphere (their bounding sphere: stable under camera rotation)"},
    {"methods[].light_frame.snap", "true: the frame moves in whole texels (no crawling under camera motion); default false"},
};

static const char *key_doc(const char *path)
{
    for (size_t i = 0; i < sizeof top_docs / sizeof top_docs[0]; i++)
        if (!strcmp(top_docs[i].path, path))
            return top_docs[i].doc[0] ? top_docs[i].doc : NULL;
    for (size_t i = 0; i < sizeof key_docs / sizeof key_docs[0]; i++)
        if (!strcmp(key_docs[i].path, path))
            return key_docs[i].doc;
    return NULL;
}

static const char *value_kind(const cyaml_schema_value_t *v)
{
    switch (v->type) {
    case CYAML_INT:
    case CYAML_UINT: return "integer";
    case CYAML_BOOL: return "true or false";
    case CYAML_FLOAT: return "number";
    case CYAML_STRING: return "text";
    case CYAML_MAPPING: return "mapping";
    case CYAML_SEQUENCE:
    case CYAML_SEQUENCE_FIXED: return "list";
    default: return "value";
    }
}

struct ref_walk {
    FILE *f;
    int   roff;
    int   seen[sizeof key_docs / sizeof key_docs[0]];
    char  missing[128];   /* the first schema path with no text */
};

static void ref_row(struct ref_walk *w, const char *path, const char *kind, int required, const char *doc)
{
    if (w->roff) {
        fprintf(w->f, ".TP\n.B %s\n(%s%s) ", path, kind, required ? ", required" : "");
        for (const char *p = doc; *p; p++) {   /* roff: a leading '.' or '\'' and every '\\' and '-' escaped */
            if (*p == '\\' || *p == '-')
                fputc('\\', w->f);
            fputc(*p, w->f);
        }
        fputc('\n', w->f);
    } else {
        fprintf(w->f, "| `%s` | %s%s | ", path, kind, required ? ", **required**" : "");
        for (const char *p = doc; *p; p++)
            fputs(*p == '|' ? "\\|" : (char[2]){*p, 0}, w->f);
        fputs(" |\n", w->f);
    }
}

static void ref_fields(struct ref_walk *w, const cyaml_schema_field_t *fl, const char *prefix, const char *only)
{
    for (; fl->key; fl++) {
        if (only && strcmp(fl->key, only))
            continue;
        char path[128];
        snprintf(path, sizeof path, "%s%s%s", prefix, prefix[0] ? "." : "", fl->key);
        const char *doc = key_doc(path);
        for (size_t i = 0; i < sizeof key_docs / sizeof key_docs[0]; i++)
            w->seen[i] |= !strcmp(key_docs[i].path, path);
        if (!doc) {
            if (!w->missing[0])
                snprintf(w->missing, sizeof w->missing, "%s", path);
            continue;
        }
        char kind[64];
        if (fl->value.type == CYAML_SEQUENCE || fl->value.type == CYAML_SEQUENCE_FIXED)
            snprintf(kind, sizeof kind, "list of %s", value_kind(fl->value.sequence.entry));
        else
            snprintf(kind, sizeof kind, "%s", value_kind(&fl->value));
        ref_row(w, path, kind, !(fl->value.flags & CYAML_FLAG_OPTIONAL), doc);
        if (fl->value.type == CYAML_MAPPING)
            ref_fields(w, fl->value.mapping.fields, path, NULL);
        else if ((fl->value.type == CYAML_SEQUENCE || fl->value.type == CYAML_SEQUENCE_FIXED) &&
                 fl->value.sequence.entry->type == CYAML_MAPPING) {
            char item[140];
            snprintf(item, sizeof item, "%s[]", path);
            ref_fields(w, fl->value.sequence.entry->mapping.fields, item, NULL);
        }
    }
}

/* The settings under top-level key `key` (CONFIG_SETTINGS): the key's own
 * declaration, or the group's row (its text in key_docs) and each of its
 * keys' declarations. */
static void ref_settings(struct ref_walk *w, const char *key)
{
    size_t n = strlen(key);
    for (int k = 0; k < CONFIG_NSETTINGS; k++) {
        const struct sl_param *p = &config_settings[k];
        if (!strcmp(p->name, key) || (!strncmp(p->name, key, n) && p->name[n] == '.')) {
            if (p->name[n] == '.' && (k == 0 || strncmp(config_settings[k - 1].name, p->name, n + 1))) {
                const char *doc = key_doc(key);   /* the group's own row, before its first key */
                for (size_t i = 0; i < sizeof key_docs / sizeof key_docs[0]; i++)
                    w->seen[i] |= !strcmp(key_docs[i].path, key);
                if (!doc && !w->missing[0])
                    snprintf(w->missing, sizeof w->missing, "%s", key);
                ref_row(w, key, "mapping", 0, doc ? doc : "");
            }
            char range[160], kind[200];
            sl_param_range_text(p, range, sizeof range);
            snprintf(kind, sizeof kind, "%s%s%s%s%s", sl_param_type_names[p->type], range[0] ? " " : "", range,
                     p->unit[0] ? " " : "", p->unit);
            ref_row(w, p->name, kind, 0, p->doc);
        }
    }
}

/* Each built-in method's parameters, from its declarations: the keys a
 * `methods:` entry naming it may give (a package's: show technique NAME). */
static void method_params_reference(FILE *f, int roff)
{
    if (roff)
        fputs(".PP\nThe parameters of the built-in methods, keys of a \\fBmethods\\fR entry naming the method:\n", f);
    else
        fputs("\nThe parameters of the built-in methods, keys of a `methods:` entry naming the method "
              "(`shadowlab show method NAME`; a package's: `shadowlab show technique NAME`):\n\n"
              "| method | key | value | default | meaning |\n|---|---|---|---|---|\n", f);
    for (int k = 0; k < sl_method_count(); k++) {
        const struct sl_method *m = sl_method_at(k);
        for (int j = 0; j < m->nparams; j++) {
            const struct sl_param *p = &m->params[j];
            char range[160], def[64], kind[200];
            sl_param_range_text(p, range, sizeof range);
            sl_param_text(p, p->def, def, sizeof def);
            snprintf(kind, sizeof kind, "%s%s%s%s%s", sl_param_type_names[p->type], range[0] ? " " : "", range,
                     p->unit[0] ? " " : "", p->unit);
            if (roff) {
                fprintf(f, ".TP\n.B %s.%s\n(%s, default %s) ", m->name, p->name, kind, def);
                for (const char *q = p->doc; *q; q++) {
                    if (*q == '\\' || *q == '-')
                        fputc('\\', f);
                    fputc(*q, f);
                }
                fputc('\n', f);
            } else {
                fprintf(f, "| `%s` | `%s` | %s | %s | ", m->name, p->name, kind, def);
                for (const char *q = p->doc; *q; q++)
                    fputs(*q == '|' ? "\\|" : (char[2]){*q, 0}, f);
                fputs(" |\n", f);
            }
        }
    }
}

enum sl_err sl_config_reference(FILE *f, int roff, struct sl_diag *d)
{
    struct ref_walk w = {.f = f, .roff = roff};
    if (!roff)
        fputs("| key | value | meaning |\n|---|---|---|\n", f);
    /* the keys in CONFIG_KEYS' order: the schema's, and the settings */
#define REF_KEY(key, kind, ...) REF_##kind(key)
#define REF_STRING(key) ref_fields(&w, config_fields, "", #key);
#define REF_SEQ(key) REF_STRING(key)
#define REF_MAP(key) REF_STRING(key)
#define REF_UINT(key) REF_STRING(key)
#define REF_SETTINGS(key) ref_settings(&w, #key);
    CONFIG_KEYS(REF_KEY)
#undef REF_KEY
#undef REF_STRING
#undef REF_SEQ
#undef REF_MAP
#undef REF_UINT
#undef REF_SETTINGS
    method_params_reference(f, roff);
    if (w.missing[0])
        return sl_fail(d, SL_E_USAGE, NULL, 0, w.missing,
                       "the config key '%s' has no text in the reference (key_docs, config.c)", w.missing);
    for (size_t i = 0; i < sizeof key_docs / sizeof key_docs[0]; i++)
        if (!w.seen[i])
            return sl_fail(d, SL_E_USAGE, NULL, 0, key_docs[i].path,
                           "the reference documents '%s', which the config schema has not (key_docs, config.c)",
                           key_docs[i].path);
    return SL_OK;
}

const char *sl_contour_from_name(int policy) { return policy == SL_CONTOUR_OWN ? "own" : "nsm"; }

static int is_pow2(unsigned v) { return v && !(v & (v - 1)); }

/* ---- validate: the checks, one function per concept ----
 * Each reads the raw config r, fills its part of c, and on a bad value
 * names file, line and key in d. They run in the order of `checks` in
 * validate: later ones read what earlier ones filled in (the scenes' lights,
 * the map sizes, the labels), and that order decides which error a config
 * with several reports. */
typedef enum sl_err check_fn(const struct raw_config *r, const char *file, const struct sl_yaml_pos *ix,
                             struct sl_config *c, struct sl_diag *d);

/* A name that names files: letters, digits, '-', '_' and '.' */
static int is_file_word(char ch)
{
    return (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') || ch == '-' ||
           ch == '_' || ch == '.';
}

static enum sl_err check_name(const struct raw_config *r, const char *file, const struct sl_yaml_pos *ix,
                              struct sl_config *c, struct sl_diag *d)
{
    snprintf(c->name, sizeof c->name, "%s", r->name ? r->name : "default");
    for (const char *p = c->name; *p; p++)
        if (!is_file_word(*p) || c->name[0] == '.')
            return sl_yaml_bad(d, SL_E_CONFIG, file, ix, "name", "'%s': use letters, digits, '-', '_' and '.' only", c->name);
    return SL_OK;
}

/* A scene entry's named viewpoints (default: all of the scene's, unless it
 * names paths). */
static enum sl_err scene_viewpoints(const struct raw_scene_ref *rs, unsigned si, const struct sl_scene *s,
                                    const char *file, const struct sl_yaml_pos *ix, struct sl_config_scene *cs,
                                    struct sl_diag *d)
{
    char key[96];
    cs->nviewpoints = (int)rs->viewpoints_count;
    for (unsigned i = 0; i < rs->viewpoints_count; i++) {
        snprintf(key, sizeof key, "scenes[%u].viewpoints[%u]", si, i);
        if (sl_scene_find_viewpoint(s, rs->viewpoints[i]) < 0) {
            char known[256] = "", hint[96];
            struct sl_suggest sg;
            sl_suggest_init(&sg, rs->viewpoints[i]);
            for (int k = 0; k < s->nvp; k++) {
                sl_known_add(known, sizeof known, s->vp[k].name);
                sl_suggest_add(&sg, s->vp[k].name);
            }
            return sl_yaml_bad(d, SL_E_CONFIG, file, ix, key, "scene '%s' has no viewpoint '%s'%s (it has: %s)",
                               rs->scene, rs->viewpoints[i], sl_suggest_text(&sg, hint, sizeof hint), known);
        }
        snprintf(cs->viewpoints[i], sizeof cs->viewpoints[i], "%s", rs->viewpoints[i]);
    }
    cs->nnamed = cs->nviewpoints;
    if (!cs->nviewpoints && !rs->paths_count) {
        cs->nnamed = cs->nviewpoints = s->nvp;
        for (int k = 0; k < s->nvp; k++)
            snprintf(cs->viewpoints[k], sizeof cs->viewpoints[k], "%s", s->vp[k].name);
    }
    return SL_OK;
}

/* A path's frames follow the viewpoints, in the path's order: each is a
 * view of the sweep (pathfile.h). */
static enum sl_err scene_paths(const struct raw_scene_ref *rs, unsigned si, const struct sl_scene *s,
                               const char *file, const struct sl_yaml_pos *ix, struct sl_config_scene *cs,
                               struct sl_diag *d)
{
    char key[96];
    for (unsigned i = 0; i < rs->paths_count; i++) {
        snprintf(key, sizeof key, "scenes[%u].paths[%u]", si, i);
        int p = sl_scene_find_path(s, rs->paths[i]);
        for (unsigned k = 0; p >= 0 && k < i; k++)
            if (strcmp(rs->paths[k], rs->paths[i]) == 0)
                p = -2;
        if (p < 0) {
            char known[256] = "";
            for (int k = 0; k < s->npaths; k++)
                sl_known_add(known, sizeof known, s->paths[k].name);
            return sl_yaml_bad(d, SL_E_CONFIG, file, ix, key, p == -2 ? "path '%s' listed twice"
                               : "scene '%s' has no path '%s' (it has: %s)", p == -2 ? rs->paths[i] : rs->scene,
                               rs->paths[i], known[0] ? known : "none");
        }
        snprintf(cs->paths[cs->npaths++], sizeof cs->paths[0], "%s", s->paths[p].name);
        for (int f = 0; f < s->paths[p].count; f++)
            snprintf(cs->viewpoints[cs->nviewpoints++], sizeof cs->viewpoints[0], "%s",
                     s->vp[s->paths[p].first + f].name);
    }
    return SL_OK;
}

/* Scene entry si: its file resolved and loaded, its views, its light. */
static enum sl_err check_scene(const struct raw_config *r, unsigned si, const char *cfg_dir, const char *file,
                               const struct sl_yaml_pos *ix, struct sl_config *c, struct sl_diag *d)
{
    const struct raw_scene_ref *rs = &r->scenes[si];
    struct sl_config_scene *cs = &c->scenes[si];
    char key[96];
    snprintf(cs->ref, sizeof cs->ref, "%s", rs->scene);
    snprintf(key, sizeof key, "scenes[%u].scene", si);
    struct sl_diag sd;
    /* a name resolves in the scenes folder; a path relative to this file */
    if (sl_scene_resolve(rs->scene, cfg_dir, cs->path, sizeof cs->path, &sd) != SL_OK) {
        char names[64][64], descr[64][160], known[512] = "", hint[96];
        struct sl_suggest sg;
        sl_suggest_init(&sg, rs->scene);
        int n = sl_scene_list(names, descr, 64);
        for (int i = 0; i < n; i++) {
            sl_known_add(known, sizeof known, names[i]);
            sl_suggest_add(&sg, names[i]);
        }
        /* sd says which paths were tried (scenefile.h) */
        return sl_yaml_bad(d, SL_E_CONFIG, file, ix, key, "unknown scene '%s'%s (known: %s; %s)", rs->scene,
                           sl_suggest_text(&sg, hint, sizeof hint), known, sd.msg);
    }
    enum sl_err re = sl_yaml_ref_check(d, SL_E_CONFIG, file, ix, key, cs->path);
    if (re)
        return re;
    /* read once, here: the session keeps it for the run (session.h) */
    struct sl_session_scene *ss = &c->session->scenes[si];
    double t0 = sl_now();
    if (sl_scene_load(cs->path, &ss->scene, &sd) != SL_OK) {
        /* the scene file's own error names its file, line and key */
        *d = sd;
        return SL_E_SCENE;
    }
    ss->ms_load = 1e3 * (sl_now() - t0);
    ss->held = 1;
    snprintf(ss->path, sizeof ss->path, "%s", cs->path);
    c->session->nscenes = (int)si + 1;
    const struct sl_scene *s = &ss->scene;
    snprintf(cs->name, sizeof cs->name, "%s", s->name);
    re = scene_viewpoints(rs, si, s, file, ix, cs, d);
    if (!re)
        re = scene_paths(rs, si, s, file, ix, cs, d);
    cs->light_type = s->light.type;
    if (re)
        return re;
    /* a scene listed twice is named at the entry's last viewpoint or path
     * when it lists any (cli::bad_input expects that key) */
    if (rs->paths_count)
        snprintf(key, sizeof key, "scenes[%u].paths[%u]", si, rs->paths_count - 1);
    else if (rs->viewpoints_count)
        snprintf(key, sizeof key, "scenes[%u].viewpoints[%u]", si, rs->viewpoints_count - 1);
    for (unsigned k = 0; k < si; k++)
        if (strcmp(c->scenes[k].path, cs->path) == 0)
            return sl_yaml_bad(d, SL_E_CONFIG, file, ix, key, "scene '%s' listed twice", rs->scene);
    return SL_OK;
}

static enum sl_err check_scenes(const struct raw_config *r, const char *file, const struct sl_yaml_pos *ix,
                                struct sl_config *c, struct sl_diag *d)
{
    char cfg_dir[512];
    sl_path_dir(file, cfg_dir, sizeof cfg_dir);
    if (sl_session_reserve_scenes(c->session, (int)r->scenes_count) != 0)
        return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "the config's scenes");
    for (unsigned si = 0; si < r->scenes_count; si++) {
        enum sl_err e = check_scene(r, si, cfg_dir, file, ix, c, d);
        if (e)
            return e;
    }
    c->nscenes = (int)r->scenes_count;
    return SL_OK;
}

static enum sl_err check_viewports(const struct raw_config *r, const char *file, const struct sl_yaml_pos *ix,
                                   struct sl_config *c, struct sl_diag *d)
{
    char key[96];
    if (r->viewports_count == 0) {
        c->nviewports = 1;
        c->viewport_w[0] = c->viewport_h[0] = 1024;
    }
    for (unsigned i = 0; i < r->viewports_count; i++) {
        snprintf(key, sizeof key, "viewports[%u]", i);
        if (r->viewports[i].width < 16 || r->viewports[i].width > 8192 ||
            r->viewports[i].height < 16 || r->viewports[i].height > 8192)
            return sl_yaml_bad(d, SL_E_CONFIG, file, ix, key, "viewport %ux%u: width and height must be in 16..8192",
                       r->viewports[i].width, r->viewports[i].height);
        c->viewport_w[i] = (int)r->viewports[i].width;
        c->viewport_h[i] = (int)r->viewports[i].height;
        c->nviewports = (int)i + 1;
    }
    return SL_OK;
}

static enum sl_err check_map_sizes(const struct raw_config *r, const char *file, const struct sl_yaml_pos *ix,
                                   struct sl_config *c, struct sl_diag *d)
{
    char key[96];
    for (unsigned i = 0; i < r->map_sizes_count; i++) {
        snprintf(key, sizeof key, "map_sizes[%u]", i);
        unsigned m = r->map_sizes[i];
        if (!is_pow2(m) || m < 64 || m > 16384)
            return sl_yaml_bad(d, SL_E_CONFIG, file, ix, key, "map size %u: must be a power of two in 64..16384", m);
        for (unsigned k = 0; k < i; k++)
            if (r->map_sizes[k] == m)
                return sl_yaml_bad(d, SL_E_CONFIG, file, ix, key, "map size %u listed twice", m);
        c->maps[i] = (int)m;
    }
    c->nmaps = (int)r->map_sizes_count;   /* distinct powers of two 64..16384: at most 9 */
    return SL_OK;
}

/* A scene may have map sizes of its own (e.g. one scene at 16384² in a
 * sweep at 512²): c->maps is then the union, and each scene's mask says
 * which of them it is swept at. */
static enum sl_err check_scene_map_sizes(const struct raw_config *r, const char *file,
                                         const struct sl_yaml_pos *ix, struct sl_config *c, struct sl_diag *d)
{
    char key[96];
    for (unsigned si = 0; si < r->scenes_count; si++) {
        const struct raw_scene_ref *rs = &r->scenes[si];
        struct sl_config_scene *cs = &c->scenes[si];
        cs->map_mask = rs->map_sizes_count ? 0u : (1u << c->nmaps) - 1u;
        for (unsigned i = 0; i < rs->map_sizes_count; i++) {
            snprintf(key, sizeof key, "scenes[%u].map_sizes[%u]", si, i);
            unsigned m = rs->map_sizes[i];
            if (!is_pow2(m) || m < 64 || m > 16384)
                return sl_yaml_bad(d, SL_E_CONFIG, file, ix, key, "map size %u: must be a power of two in 64..16384", m);
            int k = 0;
            while (k < c->nmaps && c->maps[k] != (int)m)
                k++;
            if (k == c->nmaps) {
                if (c->nmaps == SL_CFG_MAX)
                    return sl_yaml_bad(d, SL_E_CONFIG, file, ix, key, "more than %d map sizes in all", SL_CFG_MAX);
                c->maps[c->nmaps++] = (int)m;
            }
            if (cs->map_mask & (1u << k))
                return sl_yaml_bad(d, SL_E_CONFIG, file, ix, key, "map size %u listed twice", m);
            cs->map_mask |= 1u << k;
        }
    }
    return SL_OK;
}

/* The regions: the contours, then 0 (the whole image). */
static enum sl_err check_contours(const struct raw_config *r, const char *file, const struct sl_yaml_pos *ix,
                                  struct sl_config *c, struct sl_diag *d)
{
    char key[96];
    static const unsigned default_contours[] = {2, 4, 6};
    const unsigned *ct = r->contours_count ? r->contours : default_contours;
    unsigned nct = r->contours_count ? r->contours_count : 3;
    for (unsigned i = 0; i < nct; i++) {
        snprintf(key, sizeof key, "contours[%u]", i);
        if (ct[i] == 0 || ct[i] % 2 || ct[i] > 64)
            return sl_yaml_bad(d, SL_E_CONFIG, file, ix, key, "contour thickness %u: must be even, 2..64 pixels", ct[i]);
        if (i && ct[i] <= ct[i - 1])
            return sl_yaml_bad(d, SL_E_CONFIG, file, ix, key, "contour thicknesses must increase");
        c->regions[i] = (int)ct[i];
    }
    c->regions[nct] = 0;
    c->nregions = (int)nct + 1;
    return SL_OK;
}

/* Method entry i's label: its method's name unless given, then `suffix`
 * (a sweep's "[key=value]..."), into slot n of the config's labels; labels
 * name files, so no '..', no hidden file, and each is the config's only
 * one. */
static enum sl_err method_label(const struct raw_method *rm, unsigned i, int n, const char *suffix,
                                const char *file, const struct sl_yaml_pos *ix, struct sl_config *c,
                                struct sl_diag *d)
{
    struct sl_config_method *cm = &c->methods[n];
    char key[96];
    snprintf(cm->label, sizeof cm->label, "%s", rm->label ? rm->label : rm->method);
    snprintf(key, sizeof key, "methods[%u].label", i);
    if (cm->label[0] == '.')
        return sl_yaml_bad(d, SL_E_CONFIG, file, ix, key, "label '%s': must not start with '.'", cm->label);
    /* '[', ']', '=' and '+': a sweep's labels ("pcf[kernel=3]"), which the
     * filled-in config names one by one */
    for (const char *p = cm->label; *p; p++)
        if (!is_file_word(*p) && !strchr("[]=+", *p))
            return sl_yaml_bad(d, SL_E_CONFIG, file, ix, key,
                               "label '%s': use letters, digits, '-', '_', '.' (and a sweep's '[', ']', '=', '+')",
                               cm->label);
    if (strlen(cm->label) + strlen(suffix) >= sizeof cm->label)
        return sl_yaml_bad(d, SL_E_CONFIG, file, ix, rm->label ? key : (snprintf(key, sizeof key, "methods[%u]", i), key),
                           "label '%s%s': longer than %zu characters", cm->label, suffix, sizeof cm->label - 1);
    strcat(cm->label, suffix);
    /* the name people read in LaTeX tables: `display:` as given, else the
     * method's own when the label is the method's name, else the label */
    const char *disp = rm->display ? rm->display
                       : (!rm->label || !strcmp(rm->label, rm->method)) && cm->method && cm->method->display
                           ? cm->method->display
                                                                         : NULL;
    if (disp) {
        for (const char *p = disp; *p; p++)
            if ((unsigned char)*p < 0x20)
                return sl_yaml_bad(d, SL_E_CONFIG, file, ix, (snprintf(key, sizeof key, "methods[%u].display", i), key),
                                   "display '%s': one line of text, no control characters", disp);
        if (strlen(disp) + strlen(suffix) + 1 >= sizeof cm->display)
            return sl_yaml_bad(d, SL_E_CONFIG, file, ix, (snprintf(key, sizeof key, "methods[%u].display", i), key),
                               "display '%s%s': longer than %zu characters", disp, suffix, sizeof cm->display - 2);
        char buf[sizeof cm->display];
        snprintf(buf, sizeof buf, "%s%s%s", disp, suffix[0] ? " " : "", suffix);
        memcpy(cm->display, buf, sizeof buf);
    } else {
        _Static_assert(sizeof cm->label <= sizeof cm->display, "a label fits the display name");
        memcpy(cm->display, cm->label, strlen(cm->label) + 1);
    }
    for (int k = 0; k < n; k++)
        if (strcmp(c->methods[k].label, cm->label) == 0)
            return sl_yaml_bad(d, SL_E_CONFIG, file, ix, rm->label ? key : (snprintf(key, sizeof key, "methods[%u]", i), key),
                       "label '%s' used twice: give each entry its own label", cm->label);
    return SL_OK;
}

/* light_frame: a stabilised frame of this label's own (lightfit.h). */
static enum sl_err method_light_frame(const struct raw_method *rm, unsigned i, const char *file,
                                      const struct sl_yaml_pos *ix, struct sl_config_method *cm, struct sl_diag *d)
{
    char key[96];
    memset(&cm->frame_fit, 0, sizeof cm->frame_fit);
    if (!rm->light_frame)
        return SL_OK;
    const struct raw_lframe *lf = rm->light_frame;
    snprintf(key, sizeof key, "methods[%u].light_frame%s", i, lf->fit ? ".fit" : "");
    if (lf->fit && strcmp(lf->fit, "tight") && strcmp(lf->fit, "sphere"))
        return sl_yaml_bad(d, SL_E_CONFIG, file, ix, key, "fit '%s': tight or sphere", lf->fit);
    cm->frame_fit.fit = lf->fit && !strcmp(lf->fit, "sphere") ? SL_FIT_SPHERE : SL_FIT_TIGHT;
    cm->frame_fit.snap = lf->snap && *lf->snap;
    snprintf(key, sizeof key, "methods[%u].light_frame", i);
    if (cm->frame_fit.snap && cm->frame_fit.fit != SL_FIT_SPHERE)
        return sl_yaml_bad(d, SL_E_CONFIG, file, ix, key, "snap needs a fixed-size frame: fit: sphere "
                           "(a tight box changes its texel size from view to view)");
    if (cm->frame_fit.fit != SL_FIT_TIGHT && (cm->method->lights & SL_LIGHTS_AREA))
        return sl_yaml_bad(d, SL_E_CONFIG, file, ix, key, "method '%s' reads the area light's own "
                           "layers: light_frame applies to hard-shadow methods", cm->method->name);
    return SL_OK;
}

/* ---- a method entry's parameters ----
 * A method entry's keys but label, display, method and light_frame are
 * its method's parameters (declared: base/params.h), taken out of the
 * config's tree before it is bound (take_extras, marking the pairs
 * taken), each a value or a list of values (a sweep). They stay in the tree, which the loader hands down to
 * check_methods: entry_extras reads entry i's back, each with its line
 * and its values as written. */
#define SL_EXTRA_KEYS   16   /* taken keys per method entry */
#define SL_EXTRA_VALUES 16   /* values of one list */

struct sl_extra_key {
    char key[32];
    int  line;                          /* 1-based, of the key; 0 if a -D value gave it */
    int  is_list;                       /* written as a sequence (a sweep) */
    int  nvalues;                       /* 1 for a scalar */
    char value[SL_EXTRA_VALUES][64];    /* each as written (plain, quoted text unquoted) */
};

struct sl_method_extras {
    int  n;
    struct sl_extra_key k[SL_EXTRA_KEYS];
};

/* The method's own check of entry i's values against each other
 * (configure), its error named at the key's line. */
static enum sl_err method_configure(unsigned i, const struct sl_method_extras *x, const char *file,
                                    const struct sl_yaml_pos *ix, struct sl_config_method *cm, struct sl_diag *d)
{
    char key[96];
    struct sl_diag md;
    if (sl_method_configure(cm->method, &cm->params, &md) == SL_OK)
        return SL_OK;
    int line = 0;
    for (int k = 0; x && k < x->n && !line; k++)
        if (!strcmp(x->k[k].key, md.key))
            line = x->k[k].line;
    snprintf(key, sizeof key, "methods[%u]", i);
    if (!line)
        line = sl_yaml_line(ix, key);
    snprintf(key, sizeof key, "methods[%u]%s%s", i, md.key[0] ? "." : "", md.key);
    return sl_fail(d, SL_E_CONFIG, file, line, key, "%s", md.msg);
}

/* The keys of a method entry that the schema reads; every other key is a
 * parameter of its method (its declarations: base/params.h), taken out
 * with its value as written and checked against the method's declaration
 * in method_entry. */
static int take_extra(const char *method, const char *key, int is_list)
{
    (void)method;
    (void)is_list;
    return strcmp(key, "label") && strcmp(key, "display") && strcmp(key, "method") && strcmp(key, "light_frame");
}

/* A value a key may take out: 0 a scalar, 1 a list of scalars, 2 neither. */
static int extra_kind(const struct sl_ynode *v)
{
    if (v->kind == SL_YSCALAR)
        return 0;
    if (v->kind == SL_YMAP)
        return 2;
    for (unsigned i = 0; i < v->n; i++)
        if (v->kid[i]->kind != SL_YSCALAR)
            return 2;
    return 1;
}

/* Take each method entry's extras out of the tree (the first SL_CFG_MAX
 * entries: the schema refuses more). Errors (SL_E_CONFIG, naming the file
 * or the -D value, the key's line and methods[i].key): a taken key whose
 * value is a mapping, a list nested or empty or longer than
 * SL_EXTRA_VALUES, a value longer than 63 bytes, more than SL_EXTRA_KEYS
 * taken keys. */
static enum sl_err take_extras(struct sl_yaml_pos *t, struct sl_diag *d)
{
    struct sl_ynode *ms = sl_ynode_get(sl_ytree_root(t), "methods");
    if (!ms || ms->kind != SL_YSEQ)
        return SL_OK;   /* the schema names what is wrong */
    for (unsigned i = 0; i < ms->n && i < SL_CFG_MAX; i++) {
        struct sl_ynode *m = ms->kid[i];
        if (m->kind != SL_YMAP)
            continue;
        const char *method = "";
        for (unsigned p = 0; p < m->n; p++)   /* the last `method:` (the schema refuses two) */
            if (m->kid[2 * p]->text && !strcmp(m->kid[2 * p]->text, "method") && m->kid[2 * p + 1]->kind == SL_YSCALAR)
                method = m->kid[2 * p + 1]->text;
        int taken = 0;
        for (unsigned p = 0; p < m->n; p++) {
            const struct sl_ynode *k = m->kid[2 * p];
            struct sl_ynode *v = m->kid[2 * p + 1];
            if (!k->text || !strcmp(k->text, "method") || !strcmp(k->text, "label") || !strcmp(k->text, "light_frame"))
                continue;
            int kind = extra_kind(v);
            if (!take_extra(method, k->text, kind == 1))
                continue;
            char key[80];
            snprintf(key, sizeof key, "methods[%u].%.31s", i, k->text);
            const char *src = sl_ynode_source(t, v);
            int line = sl_ynode_line(v);
            int toolong = kind == 0 ? strlen(v->text) >= 64 : v->n > SL_EXTRA_VALUES;
            for (unsigned j = 0; kind == 1 && j < v->n; j++)
                toolong |= strlen(v->kid[j]->text) >= 64;
            if (kind == 2)
                return sl_fail(d, SL_E_CONFIG, src, line, key,
                               "a value or a list of values (a sweep), not a mapping or a nested list");
            if (kind == 1 && v->n == 0)
                return sl_fail(d, SL_E_CONFIG, src, line, key, "an empty list sweeps nothing");
            if (toolong)
                return sl_fail(d, SL_E_CONFIG, src, line, key, "at most %d values of at most 63 bytes each",
                               SL_EXTRA_VALUES);
            if (taken == SL_EXTRA_KEYS)
                return sl_fail(d, SL_E_CONFIG, src, line, key, "more than %d parameters or sweeps in one entry",
                               SL_EXTRA_KEYS);
            taken++;
            v->taken = 1;
        }
    }
    return SL_OK;
}

/* Entry i's taken keys, in the entry's order (take_extras checked them). */
static void entry_extras(const struct sl_yaml_pos *t, unsigned i, struct sl_method_extras *x)
{
    memset(x, 0, sizeof *x);
    const struct sl_ynode *ms = sl_ynode_get(sl_ytree_root(t), "methods");
    const struct sl_ynode *m = ms && ms->kind == SL_YSEQ && i < ms->n ? ms->kid[i] : NULL;
    for (unsigned p = 0; m && m->kind == SL_YMAP && p < m->n && x->n < SL_EXTRA_KEYS; p++) {
        const struct sl_ynode *v = m->kid[2 * p + 1];
        if (!v->taken)
            continue;
        struct sl_extra_key *e = &x->k[x->n++];
        snprintf(e->key, sizeof e->key, "%s", m->kid[2 * p]->text);
        e->line = sl_ynode_line(v);
        e->is_list = v->kind == SL_YSEQ;
        e->nvalues = e->is_list ? (int)v->n : 1;
        for (int j = 0; j < e->nvalues; j++)
            snprintf(e->value[j], sizeof e->value[j], "%s", e->is_list ? v->kid[j]->text : v->text);
    }
}

/* A sweep's value in a label: "[key=value]", the value a file word. */
static enum sl_err label_part(char *suffix, size_t n, const struct sl_extra_key *xk, const char *value, unsigned i,
                              const char *file, struct sl_diag *d)
{
    char key[96];
    snprintf(key, sizeof key, "methods[%u].%s", i, xk->key);
    for (const char *p = value; *p; p++)
        if (!is_file_word(*p) && *p != '+')
            return sl_fail(d, SL_E_CONFIG, file, xk->line, key, "swept value '%s': it names files in the "
                           "label, so letters, digits, '-', '+', '_' and '.' only", value);
    size_t l = strlen(suffix);
    snprintf(suffix + l, n - l, "[%s=%s]", xk->key, value);
    return SL_OK;
}

/* The technique folders the config names (`techniques:`), relative to it. */
static enum sl_err load_packages(const struct raw_config *r, const char *file, const struct sl_yaml_pos *ix,
                                 struct sl_config *c, struct sl_diag *d)
{
    char dir[512];
    sl_path_dir(file, dir, sizeof dir);
    const char *dirs[8];
    unsigned n = r->techniques_count < 8 ? r->techniques_count : 8;
    for (unsigned k = 0; k < n; k++) {
        dirs[k] = r->techniques[k];
        char full[1100], key[64];
        snprintf(full, sizeof full, "%s/%s", dir, dirs[k]);
        snprintf(key, sizeof key, "techniques[%u]", k);
        struct stat st;
        const char *where = dirs[k][0] == '/' ? dirs[k] : full;
        if (stat(where, &st) || !S_ISDIR(st.st_mode))
            return sl_yaml_bad(d, SL_E_CONFIG, file, ix, key, "'%s': no such folder (relative to the config)", dirs[k]);
        /* the filled-in config names it whole: it is written elsewhere */
        char *real = realpath(where, NULL);
        snprintf(c->techniques[c->ntechniques++], sizeof c->techniques[0], "%s", real ? real : where);
        free(real);
    }
    const char *c_names[64];
    int nc = 0;
    for (int k = 0; k < sl_method_count() && nc < 63; k++)
        c_names[nc++] = sl_method_at(k)->name;
    c_names[nc] = NULL;
    return sl_packages_load(&c->session->packages, dirs, (int)n, dir, c_names, d);
}

/* Entry i expanded into labels from slot c->nmethods on: one per
 * combination of its swept values (the first swept key varies slowest). */
static enum sl_err method_entry(const struct raw_method *rm, unsigned i, const struct sl_method_extras *x,
                                const char *file, const struct sl_yaml_pos *ix, struct sl_config *c,
                                struct sl_diag *d)
{
    char key[96];
    const struct sl_method *m = sl_session_method(c->session, rm->method);
    const struct sl_technique *t = m ? sl_package_of(m) : NULL;
    int nx = x ? x->n : 0;
    /* combinations: the product of the lists' lengths */
    int total = 1;
    for (int k = 0; k < nx; k++)
        if (x->k[k].is_list) {
            total *= x->k[k].nvalues;
            if (c->nmethods + total > SL_CFG_MAX) {
                snprintf(key, sizeof key, "methods[%u].%s", i, x->k[k].key);
                return sl_fail(d, SL_E_CONFIG, file, x->k[k].line, key,
                               "the sweeps make more than %d labels in all", SL_CFG_MAX);
            }
        }
    /* a sweep's values are distinct after parsing: 0.5 and 0.50 would be
     * two labels of one method, scored twice under two names */
    for (int k = 0; k < nx; k++) {
        const struct sl_extra_key *xk = &x->k[k];
        int pi = sl_param_index(m->params, m->nparams, xk->key);
        double v[SL_EXTRA_VALUES];
        for (int j = 0; xk->is_list && pi >= 0 && j < xk->nvalues; j++) {
            if (sl_param_parse(&m->params[pi], xk->value[j], &v[j]))
                break;   /* not a value: the combination below names why */
            for (int q = 0; q < j; q++)
                if (v[q] == v[j]) {
                    snprintf(key, sizeof key, "methods[%u].%s", i, xk->key);
                    return sl_fail(d, SL_E_CONFIG, file, xk->line, key, "swept values '%s' and '%s' are one "
                                   "value: each value of a sweep makes its own label", xk->value[q], xk->value[j]);
                }
        }
    }
    for (int combo = 0; combo < total; combo++) {
        int n = c->nmethods;
        struct sl_config_method *cm = &c->methods[n];
        cm->method = m;
        cm->entry = (int)i;
        sl_method_params_init(m, &cm->params);
        cm->params.tech = t;
        char suffix[64] = "";
        int rest = combo;
        /* the value each key has in this combination */
        const char *val[SL_EXTRA_KEYS];
        for (int k = nx - 1; k >= 0; k--) {
            const struct sl_extra_key *xk = &x->k[k];
            int pick = 0;
            if (xk->is_list) {
                pick = rest % xk->nvalues;
                rest /= xk->nvalues;
            }
            val[k] = xk->value[pick];
        }
        for (int k = 0; k < nx; k++) {
            const struct sl_extra_key *xk = &x->k[k];
            snprintf(key, sizeof key, "methods[%u].%s", i, xk->key);
            enum sl_err e = SL_OK;
            if (xk->is_list)
                e = label_part(suffix, sizeof suffix, xk, val[k], i, file, d);
            struct sl_diag md;
            if (!e && sl_params_put_text(&cm->params.values, xk->key, val[k], &md)) {
                if (sl_param_index(m->params, m->nparams, xk->key) < 0)   /* "no parameter 'x' (it has: ...)" */
                    e = sl_fail(d, SL_E_CONFIG, file, xk->line, key, "method '%s' has %s", m->name, md.msg);
                else
                    e = sl_fail(d, SL_E_CONFIG, file, xk->line, key, "%s", md.msg);
            }
            if (e)
                return e;
        }
        enum sl_err e = method_label(rm, i, n, suffix, file, ix, c, d);
        if (!e)
            e = method_light_frame(rm, i, file, ix, cm, d);
        if (!e)
            e = method_configure(i, x, file, ix, cm, d);
        if (e)
            return e;
        c->nmethods++;
    }
    return SL_OK;
}

/* The config's hash covers the packages its labels run: their
 * technique.yaml and both shaders, byte for byte. A package edited between
 * two runs is another study: --resume and merge key cells by the config
 * hash, so cells of the old shaders are never taken for the new ones. */
static void hash_packages(struct sl_config *c)
{
    for (int i = 0; i < c->nmethods; i++) {
        const struct sl_technique *t = c->methods[i].params.tech;
        int seen = 0;
        for (int k = 0; k < i && !seen; k++)
            seen = c->methods[k].params.tech == t;
        if (!t || seen)
            continue;
        unsigned long long h = t->file_hash;   /* technique.yaml as it was read */
        const char *parts[2] = {t->map_src, t->lookup_src};
        for (int k = 0; k < 8; k++)
            c->hash = (c->hash ^ ((h >> (8 * k)) & 0xffu)) * 1099511628211ull;
        for (int p = 0; p < 2; p++)
            for (const unsigned char *q = (const unsigned char *)(parts[p] ? parts[p] : ""); ; q++) {
                c->hash = (c->hash ^ *q) * 1099511628211ull;   /* the NUL ends each part */
                if (!*q)
                    break;
            }
    }
}

static enum sl_err check_methods(const struct raw_config *r, const char *file, const struct sl_yaml_pos *ix,
                                 struct sl_config *c, struct sl_diag *d)
{
    char key[96];
    /* packages only when an entry names no C method: a broken package on
     * the search path does not stop a config that uses none */
    /* ... but always when the config or SHADOWLAB_TECHNIQUES names folders
     * of its own: a package there named like a C method is an error, not a
     * package silently left for the C method of that name */
    const char *env = getenv("SHADOWLAB_TECHNIQUES");
    int want = r->techniques_count > 0 || (env && *env);
    for (unsigned i = 0; i < r->methods_count; i++) {
        int c_method = 0;
        for (int k = 0; k < sl_method_count() && !c_method; k++)
            c_method = !strcmp(sl_method_at(k)->name, r->methods[i].method);
        want |= !c_method;
    }
    if (want) {
        enum sl_err e = load_packages(r, file, ix, c, d);
        if (e)
            return e;
    }
    c->nmethods = 0;
    for (unsigned i = 0; i < r->methods_count; i++) {
        const struct raw_method *rm = &r->methods[i];
        snprintf(key, sizeof key, "methods[%u].method", i);
        if (!sl_session_method(c->session, rm->method)) {
            char known[1024] = "", hint[96];
            struct sl_suggest sg;
            sl_suggest_init(&sg, rm->method);
            for (int k = 0; k < sl_method_count(); k++) {
                sl_known_add(known, sizeof known, sl_method_at(k)->name);
                sl_suggest_add(&sg, sl_method_at(k)->name);
            }
            for (int k = 0; k < sl_packages_count(c->session ? &c->session->packages : NULL); k++) {
                sl_known_add(known, sizeof known, sl_packages_at(&c->session->packages, k)->name);
                sl_suggest_add(&sg, sl_packages_at(&c->session->packages, k)->name);
            }
            return sl_yaml_bad(d, SL_E_CONFIG, file, ix, key, "unknown method '%s'%s (known: %s)", rm->method,
                               sl_suggest_text(&sg, hint, sizeof hint), known);
        }
        struct sl_method_extras x;
        entry_extras(ix, i, &x);
        enum sl_err e = method_entry(rm, i, &x, file, ix, c, d);
        if (e)
            return e;
    }
    hash_packages(c);
    return SL_OK;
}

/* The lights label k handles (SL_LIGHTS_*): its method's, and a package's
 * cascades (partitions > 1: package.h) need a directional light as zpart's
 * do. */
static unsigned label_lights(const struct sl_config *c, int k)
{
    const struct sl_config_method *cm = &c->methods[k];
    unsigned lights = cm->method->lights;
    if (cm->params.tech && sl_method_param(&cm->params, "partitions") > 1)
        lights |= SL_LIGHTS_DIRECTIONAL;
    return lights;
}

/* Why label k cannot run under a light of type `type`, NULL when it can. */
static const char *label_cannot(const struct sl_config *c, int k, int type)
{
    const unsigned lights = label_lights(c, k);
    if ((lights & SL_LIGHTS_AREA) && type != SL_LIGHT_AREA)
        return "handles area lights only";
    if ((lights & SL_LIGHTS_DIRECTIONAL) && type != SL_LIGHT_DIRECTIONAL)
        return c->methods[k].params.tech ? "runs cascades (partitions > 1), which need a directional light"
                                         : "handles directional lights only";
    return NULL;
}

/* Scene entry si's labels: those its list names, each of which must handle
 * its light, or without a list every label that handles its light, so one
 * config can mix scenes of every light: the hard-shadow methods and the
 * technique packages handle all (a spot light at its position, a point
 * light per face of its cube, an area light as a point at its centre), the
 * soft ones area lights only, zpart, lispsm and a package's cascades
 * directional lights only. The labels a scene without a list leaves out
 * are kept (left_out) and named by validate and run: none is dropped
 * silently. */
static enum sl_err scene_methods(const struct raw_scene_ref *rs, unsigned si, const char *file,
                                 const struct sl_yaml_pos *ix, struct sl_config *c, struct sl_diag *d)
{
    char key[96];
    struct sl_config_scene *cs = &c->scenes[si];
    const int dirl = cs->light_type == SL_LIGHT_DIRECTIONAL;
    const char *lname = sl_config_light_name(cs->light_type);
    cs->method_mask = cs->left_out = 0u;
    for (int k = 0; k < c->nmethods && !rs->methods_count; k++) {
        if (!label_cannot(c, k, cs->light_type))
            cs->method_mask |= 1u << k;
        else
            cs->left_out |= 1u << k;
    }
    if (!rs->methods_count && !cs->method_mask) {
        snprintf(key, sizeof key, "scenes[%u]", si);
        return sl_yaml_bad(d, SL_E_CONFIG, file, ix, key,
                           "scene '%s' has %s light and no method of this config handles it (hard-shadow "
                           "methods and technique packages handle every light; hard_point, point_map, soft_mc "
                           "need an area light; zpart, lispsm and cascades a directional one)", cs->name, lname);
    }
    for (unsigned i = 0; i < rs->methods_count; i++) {
        snprintf(key, sizeof key, "scenes[%u].methods[%u]", si, i);
        /* a label, or a swept entry's label without its "[key=value]"
         * parts: every label of the sweep */
        unsigned hit = 0u;
        int exact = 0;
        size_t nl = strlen(rs->methods[i]);
        for (int k = 0; k < c->nmethods; k++)
            if (strcmp(c->methods[k].label, rs->methods[i]) == 0)
                hit = 1u << k, exact = 1;
        for (int k = 0; k < c->nmethods && !exact; k++)
            if (!strncmp(c->methods[k].label, rs->methods[i], nl) && c->methods[k].label[nl] == '[')
                hit |= 1u << k;
        if (!hit)
            return sl_yaml_bad(d, SL_E_CONFIG, file, ix, key, "no method labelled '%s' in this config",
                               rs->methods[i]);
        if (cs->method_mask & hit)
            return sl_yaml_bad(d, SL_E_CONFIG, file, ix, key, "label '%s' listed twice", rs->methods[i]);
        cs->method_mask |= hit;
    }
    /* every label a scene's list names must handle its light */
    for (int k = 0; k < c->nmethods; k++) {
        if (!(cs->method_mask & (1u << k)))
            continue;
        if (!dirl && c->methods[k].frame_fit.fit != SL_FIT_TIGHT) {
            snprintf(key, sizeof key, "methods[%d].light_frame", k);
            return sl_yaml_bad(d, SL_E_CONFIG, file, ix, key, "scene '%s' has %s light: light_frame "
                               "fits a directional light's frame only (label %s)", cs->name, lname,
                               c->methods[k].label);
        }
        const char *why = label_cannot(c, k, cs->light_type);
        if (why) {
            snprintf(key, sizeof key, "scenes[%u].methods", si);
            return sl_yaml_bad(d, SL_E_CONFIG, file, ix, key, "scene '%s' has %s light but method '%s' (label %s) %s",
                               cs->name, lname, c->methods[k].method->name, c->methods[k].label, why);
        }
    }
    return SL_OK;
}

const char *sl_config_light_name(int type)
{
    static const char *const names[] = {"a directional", "a spot", "a point", "an area"};
    return type >= 0 && type < 4 ? names[type] : "an unknown";
}

const char *sl_config_left_out_why(const struct sl_config *c, int si, int k)
{
    const char *why = si >= 0 && si < c->nscenes && k >= 0 && k < c->nmethods &&
                              (c->scenes[si].left_out & (1u << k))
                          ? label_cannot(c, k, c->scenes[si].light_type)
                          : NULL;
    return why;
}

/* A scene may run a subset of the method labels (e.g. only the cheap ones
 * at 16384²). */
static enum sl_err check_scene_methods(const struct raw_config *r, const char *file,
                                       const struct sl_yaml_pos *ix, struct sl_config *c, struct sl_diag *d)
{
    for (unsigned si = 0; si < r->scenes_count; si++) {
        enum sl_err e = scene_methods(&r->scenes[si], si, file, ix, c, d);
        if (e)
            return e;
    }
    return SL_OK;
}

/* What a config alone decides about the packages its labels run, checked
 * before any scene is rendered or any truth traced: each package's shaders
 * compile (glslang, techcheck.h: errors at the package file's line), and at
 * every map size a scene runs a package label at, its maps (the size plus
 * twice the guard band) stay within SL_TECH_MAX_MAP_SIZE. A GL whose
 * maximum texture size is smaller is checked when the run opens it
 * (sl_package_fits), still before the first truth. */
static enum sl_err check_packages(const struct raw_config *r, const char *file, const struct sl_yaml_pos *ix,
                                  struct sl_config *c, struct sl_diag *d)
{
    (void)r;
    for (int k = 0; k < c->nmethods; k++) {
        const struct sl_technique *t = c->methods[k].params.tech;
        int seen = 0;
        for (int j = 0; j < k && !seen; j++)
            seen = c->methods[j].params.tech == t;
        enum sl_err e = t && !seen ? sl_techcheck(t, d) : SL_OK;
        if (e)
            return e;
    }
    for (int si = 0; si < c->nscenes; si++)
        for (int mi = 0; mi < c->nmaps; mi++) {
            if (!(c->scenes[si].map_mask & (1u << mi)))
                continue;
            for (int k = 0; k < c->nmethods; k++) {
                const struct sl_config_method *cm = &c->methods[k];
                const struct sl_technique *t = cm->params.tech;
                if (!t || !(c->scenes[si].method_mask & (1u << k)))
                    continue;
                int g = sl_tech_guard(t, &cm->params.values);
                long long n = (long long)c->maps[mi] + 2ll * g;
                if (n <= SL_TECH_MAX_MAP_SIZE)
                    continue;
                /* the key that grows the band, at its line when the entry gives it */
                int gp = sl_tech_guard_param(t), line = 0;
                char key[96], what[96];
                struct sl_method_extras x;
                entry_extras(ix, (unsigned)cm->entry, &x);
                for (int q = 0; gp >= 0 && q < x.n && !line; q++)
                    if (!strcmp(x.k[q].key, t->param[gp].name))
                        line = x.k[q].line;
                snprintf(key, sizeof key, "methods[%d]", cm->entry);
                if (!line)
                    line = sl_yaml_line(ix, key);
                snprintf(key, sizeof key, "methods[%d].%s", cm->entry, gp >= 0 ? t->param[gp].name : "method");
                if (gp >= 0)
                    snprintf(what, sizeof what, "%s = %g", t->param[gp].name, cm->params.values.v[gp]);
                else
                    snprintf(what, sizeof what, "package %s's reach", t->name);
                return sl_fail(d, SL_E_CONFIG, file, line, key, "%s gives label %s a guard band of %d texels: at map "
                               "size %d (scene '%s') its maps would be %d + 2 x %d = %lld texels wide, over the "
                               "limit of %d", what, cm->label, g, c->maps[mi], c->scenes[si].name, c->maps[mi], g, n,
                               SL_TECH_MAX_MAP_SIZE);
            }
        }
    return SL_OK;
}

/* A run writes only under --out: a store path may not leave it (an
 * explicit --db on the command line may). */
static enum sl_err check_store(const struct raw_config *r, const char *file, const struct sl_yaml_pos *ix,
                               struct sl_config *c, struct sl_diag *d)
{
    snprintf(c->store, sizeof c->store, "%s", r->store ? r->store : "");
    c->store_line = sl_yaml_line(ix, "store");
    if (!r->store)
        return SL_OK;
    int up = 0;
    for (const char *q = r->store; *q; q += strcspn(q, "/"), q += *q == '/')
        up |= strncmp(q, "..", 2) == 0 && (q[2] == '/' || q[2] == '\0');
    if (r->store[0] == '/' || up)
        return sl_yaml_bad(d, SL_E_CONFIG, file, ix, "store", "'%s' leaves the output folder: give a path "
                           "relative to it without '..', or --db on the command line", r->store);
    return SL_OK;
}

/* gl: default is SHADOWLAB_GL, else the build's (glbackend.h) */
static enum sl_err check_gl(const struct raw_config *r, const char *file, const struct sl_yaml_pos *ix,
                            struct sl_config *c, struct sl_diag *d)
{
    (void)r, (void)file, (void)ix, (void)d;
    c->gl = sl_gl_backend_resolve(c->gl);
    return SL_OK;
}

/* What a run writes; the overlay's contour is one of the regions. */
static enum sl_err check_outputs(const struct raw_config *r, const char *file, const struct sl_yaml_pos *ix,
                                 struct sl_config *c, struct sl_diag *d)
{
    (void)r;
    /* the aliasing error m: auto (the default) where a method's study reads
     * it (method.h, SL_FIGS_ALIASING: zpart, lispsm), else as the config says */
    if (c->aliasing == 2) {
        c->aliasing = 0;
        for (int k = 0; k < c->nmethods; k++)
            c->aliasing |= (c->methods[k].method->figures & SL_FIGS_ALIASING) != 0;
    }
    if (!sl_params_given(&c->settings, "outputs.overlay_contour")) {
        c->overlay_contour = c->regions[0];   /* the thinnest */
        return SL_OK;
    }
    int found = 0;
    for (int k = 0; k < c->nregions; k++)
        found |= c->regions[k] == c->overlay_contour;
    if (!found)
        return sl_yaml_bad(d, SL_E_CONFIG, file, ix, "outputs.overlay_contour",
                           "overlay_contour %d is not one of the contours (or 0: the whole image)", c->overlay_contour);
    return SL_OK;
}

static enum sl_err check_threads(const struct raw_config *r, const char *file, const struct sl_yaml_pos *ix,
                                 struct sl_config *c, struct sl_diag *d)
{
    (void)r, (void)file, (void)ix, (void)d;
    long cores = sl_cpu_count();   /* 0: every core this process may run on */
    if (!c->threads)
        c->threads = (int)(cores > 256 ? 256 : cores > 0 ? cores : 1);
    return SL_OK;
}

/* One setting's value node: a scalar, checked against its declaration. */
static enum sl_err setting_value(const struct sl_yaml_pos *t, struct sl_params *s, const char *path,
                                 const struct sl_ynode *v, struct sl_diag *d)
{
    const char *src = sl_ynode_source(t, v);
    if (v->kind != SL_YSCALAR)
        return sl_fail(d, SL_E_CONFIG, src, sl_ynode_line(v), path, "one value, not a %s",
                       v->kind == SL_YMAP ? "mapping" : "list");
    struct sl_diag md;
    if (sl_params_put_text(s, path, v->text, &md))
        return sl_fail(d, SL_E_CONFIG, src, sl_ynode_line(v), path, "%s", md.msg);
    return SL_OK;
}

/* The settings (CONFIG_SETTINGS) from the tree, before the schema binds
 * the rest: each key given checked at its line and taken out of the
 * schema's view, a group's other keys refused; their values into
 * c->settings and each one's field (the defaults where none is given). */
static enum sl_err take_settings(struct sl_yaml_pos *t, struct sl_config *c, struct sl_diag *d)
{
    struct sl_params *s = &c->settings;
    sl_params_init(s, config_settings, CONFIG_NSETTINGS);
    struct sl_ynode *root = sl_ytree_root(t);
    for (unsigned p = 0; root && root->kind == SL_YMAP && p < root->n; p++) {
        const char *key = root->kid[2 * p]->text;
        struct sl_ynode *v = root->kid[2 * p + 1];
        if (!key)
            continue;
        size_t n = strlen(key);
        int own = sl_param_index(config_settings, CONFIG_NSETTINGS, key), group = 0;
        char known[256] = "";
        for (int k = 0; k < CONFIG_NSETTINGS; k++)
            if (!strncmp(config_settings[k].name, key, n) && config_settings[k].name[n] == '.') {
                group = 1;
                sl_known_add(known, sizeof known, config_settings[k].name + n + 1);
            }
        enum sl_err e = SL_OK;
        if (own >= 0) {
            e = setting_value(t, s, key, v, d);
        } else if (group && v->kind != SL_YMAP) {
            e = sl_fail(d, SL_E_CONFIG, sl_ynode_source(t, v), sl_ynode_line(v), key, "a mapping of %s", known);
        } else if (group) {
            for (unsigned q = 0; !e && q < v->n; q++) {
                const struct sl_ynode *kn = v->kid[2 * q];
                const char *sub = kn->text ? kn->text : "";
                char path[96];
                snprintf(path, sizeof path, "%s.%s", key, sub);
                if (sl_param_index(config_settings, CONFIG_NSETTINGS, path) < 0) {
                    struct sl_suggest sg;
                    char hint[96];
                    sl_suggest_init(&sg, sub);
                    for (int k = 0; k < CONFIG_NSETTINGS; k++)
                        if (!strncmp(config_settings[k].name, key, n) && config_settings[k].name[n] == '.')
                            sl_suggest_add(&sg, config_settings[k].name + n + 1);
                    e = sl_fail(d, SL_E_CONFIG, sl_ynode_source(t, kn), sl_ynode_line(kn), path,
                                "unknown key '%s'%s (%s has: %s)", sub, sl_suggest_text(&sg, hint, sizeof hint), key,
                                known);
                }
                else
                    e = setting_value(t, s, path, v->kid[2 * q + 1], d);
            }
        } else {
            continue;   /* the schema's */
        }
        if (e)
            return e;
        v->taken = 1;
    }
    int k = 0;
#define SETTING_STORE(field, decl) c->field = s->v[k++];
    CONFIG_SETTINGS(SETTING_STORE)
#undef SETTING_STORE
    return SL_OK;
}

/* A setting's value as its field holds it now (resolved, or set since by
 * the command line: --gl, -j), in its declarations' order. */
static double setting_field(const struct sl_config *c, int i)
{
    int k = 0;
#define SETTING_READ(field, decl) if (i == k++) return (double)c->field;
    CONFIG_SETTINGS(SETTING_READ)
#undef SETTING_READ
    return 0;
}

static enum sl_err validate(const struct raw_config *r, const char *file, const struct sl_yaml_pos *ix,
                            struct sl_config *c, struct sl_diag *d)
{
    static check_fn *const checks[] = {
        check_name,     check_scenes,  check_viewports,     check_map_sizes, check_scene_map_sizes,
        check_contours, check_methods, check_scene_methods, check_packages, check_store, check_gl,
        check_outputs,  check_threads,
    };
    for (size_t i = 0; i < sizeof checks / sizeof checks[0]; i++) {
        enum sl_err e = checks[i](r, file, ix, c, d);
        if (e) {
            sl_config_free(c);   /* a failed load holds nothing */
            return e;
        }
    }
    return SL_OK;
}

void sl_config_free(struct sl_config *c)
{
    if (c->session) {
        sl_session_free(c->session);
        free(c->session);
        c->session = NULL;
    }
}

/* ---- -D key=value: a config key replaced by its path ----
 * Each override's value (itself YAML: 0.01, [512, 1024], {width: 512,
 * height: 512}) is parsed into nodes whose origin is the override, and
 * grafted into the config's tree at its path (sl_ytree_set) before the
 * tree is bound: it goes through the same schema and checks as the file,
 * so an override is valid exactly when the same text in the file would
 * be, and an error about it names the -D value and the key. */
static enum sl_err apply_overrides(struct sl_yaml_pos *t, const char *const *ov, int n, struct sl_diag *d)
{
    const struct sl_ynode *root = sl_ytree_root(t);
    if (!root || root->kind != SL_YMAP)
        return SL_OK;   /* the binding names the file's own error */
    for (int i = 0; i < n; i++) {
        const char *eq = strchr(ov[i], '=');
        char path[96], msg[300], src[200];
        snprintf(src, sizeof src, "-D %s", ov[i]);
        if (!eq || eq == ov[i] || (size_t)(eq - ov[i]) >= sizeof path)
            return sl_fail(d, SL_E_USAGE, src, 0, NULL, "-D wants KEY=VALUE (e.g. -D map_sizes=[512,1024])");
        snprintf(path, sizeof path, "%.*s", (int)(eq - ov[i]), ov[i]);
        struct sl_ynode *val;
        enum sl_err e = sl_ytree_value(t, eq + 1, src, path, &val, d);
        if (e)
            return e;
        if (!sl_ytree_set(t, path, val, msg, sizeof msg))
            return sl_fail(d, SL_E_CONFIG, src, 0, path, "%s", msg);
    }
    return SL_OK;
}

/* An error at a key a -D value gave (or inside it) names that override,
 * as one at a key above an override's path does (the value it checks
 * includes the override); any other keeps the file's own line. */
static void ov_blame(const struct sl_yaml_pos *t, const char *const *ov, int n, struct sl_diag *d)
{
    /* only the config's own errors: a scene file's key is no key of the config */
    if (!d || !d->key[0] || strcmp(d->file, sl_ytree_file(t)) != 0)
        return;
    char path[96];
    snprintf(path, sizeof path, "%s", d->key);
    const struct sl_ynode *node = NULL;
    for (size_t k = strlen(path); !node && k > 0; k--) {   /* the deepest node the key's path reaches */
        if (path[k] && path[k] != '.' && path[k] != '[')
            continue;
        path[k] = '\0';
        node = sl_ytree_find(t, path);
    }
    if (node && node->origin) {
        snprintf(d->file, sizeof d->file, "%s", sl_ynode_source(t, node));
        d->line = 0;
        return;
    }
    size_t k = strlen(d->key);
    for (int i = 0; i < n; i++) {
        const char *eq = strchr(ov[i], '=');
        if (eq && (size_t)(eq - ov[i]) > k && strncmp(ov[i], d->key, k) == 0 && (ov[i][k] == '.' || ov[i][k] == '[')) {
            snprintf(d->file, sizeof d->file, "-D %s", ov[i]);
            d->line = 0;
            return;
        }
    }
}

enum sl_err sl_config_load_with(const char *path, const char *const *overrides, int n, struct sl_config *out,
                                struct sl_diag *d)
{
    memset(out, 0, sizeof *out);
    snprintf(out->path, sizeof out->path, "%s", path);
    /* one read: the tree, edited by the overrides, its extras taken out,
     * bound to the schema, then checked with the tree's positions */
    struct sl_yaml_pos *t = NULL;
    struct raw_config *raw = NULL;
    enum sl_err e = sl_ytree_read(path, SL_CONFIG_MAX_BYTES, SL_E_CONFIG, &t, d);
    if (e)
        return e;
    if (n > 0)
        e = apply_overrides(t, overrides, n, d);
    if (!e)
        e = take_extras(t, d);
    if (!e)
        e = take_settings(t, out, d);
    if (!e)
        e = sl_yaml_bind(t, &config_schema, (void **)&raw, SL_E_CONFIG, d);
    if (!e) {
        /* the file's bytes as read; the same file with the same overrides
         * hashes alike (so --resume finds its cells), with other overrides
         * it does not */
        out->hash = sl_ytree_hash(t);
        for (int i = 0; i < n; i++)
            for (size_t k = 0, len = strlen(overrides[i]); k <= len; k++)   /* the NUL separates them */
                out->hash = (out->hash ^ (unsigned char)overrides[i][k]) * 1099511628211ull;
        if (!(out->session = calloc(1, sizeof *out->session)))
            e = sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "the config's session");
        else
            e = validate(raw, path, t, out, d);
    }
    if (e && n > 0)
        ov_blame(t, overrides, n, d);
    sl_yaml_free(&config_schema, raw, t);
    return e;
}

enum sl_err sl_config_load(const char *path, struct sl_config *out, struct sl_diag *d)
{
    return sl_config_load_with(path, NULL, 0, out, d);
}

/* ---- the filled-in config: one write_<key> per CONFIG_KEYS line ---- */

static void write_name(const struct sl_config *c, FILE *f) { fprintf(f, "name: %s\n", c->name); }

static void write_scenes(const struct sl_config *c, FILE *f)
{
    fprintf(f, "scenes:\n");
    for (int s = 0; s < c->nscenes; s++) {
        fprintf(f, "  - {scene: %s, ", c->scenes[s].ref);
        if (c->scenes[s].nnamed) {
            fprintf(f, "viewpoints: [");
            for (int i = 0; i < c->scenes[s].nnamed; i++)
                fprintf(f, "%s%s", i ? ", " : "", c->scenes[s].viewpoints[i]);
            fprintf(f, "], ");
        }
        if (c->scenes[s].npaths) {
            fprintf(f, "paths: [");
            for (int i = 0; i < c->scenes[s].npaths; i++)
                fprintf(f, "%s%s", i ? ", " : "", c->scenes[s].paths[i]);
            fprintf(f, "], ");
        }
        fprintf(f, "map_sizes: [");
        for (int i = 0, k = 0; i < c->nmaps; i++)
            if (c->scenes[s].map_mask & (1u << i))
                fprintf(f, "%s%d", k++ ? ", " : "", c->maps[i]);
        fprintf(f, "], methods: [");
        for (int i = 0, k = 0; i < c->nmethods; i++)
            if (c->scenes[s].method_mask & (1u << i))
                fprintf(f, strpbrk(c->methods[i].label, "[]{},:#") ? "%s\"%s\"" : "%s%s", k++ ? ", " : "",
                        c->methods[i].label);
        fprintf(f, "]}\n");
    }
}

static void write_viewports(const struct sl_config *c, FILE *f)
{
    fprintf(f, "viewports:\n");
    for (int i = 0; i < c->nviewports; i++)
        fprintf(f, "  - {width: %d, height: %d}\n", c->viewport_w[i], c->viewport_h[i]);
}

static void write_map_sizes(const struct sl_config *c, FILE *f)
{
    fprintf(f, "map_sizes: [");
    for (int i = 0; i < c->nmaps; i++)
        fprintf(f, "%s%d", i ? ", " : "", c->maps[i]);
    fprintf(f, "]\n");
}

/* the regions without the last, the whole image (validate adds it) */
static void write_contours(const struct sl_config *c, FILE *f)
{
    fprintf(f, "contours: [");
    for (int i = 0; i + 1 < c->nregions; i++)
        fprintf(f, "%s%d", i ? ", " : "", c->regions[i]);
    fprintf(f, "]\n");
}

/* every parameter that applies to the label's values, in its method's order */
static void write_methods(const struct sl_config *c, FILE *f)
{
    fprintf(f, "methods:\n");
    for (int i = 0; i < c->nmethods; i++) {
        const struct sl_method_params *p = &c->methods[i].params;
        /* a sweep's label holds '[' and ']', flow indicators: quoted */
        const char *q = strpbrk(c->methods[i].label, "[]{},:#") ? "\"" : "";
        fprintf(f, "  - {label: %s%s%s, method: %s", q, c->methods[i].label, q, c->methods[i].method->name);
        if (strcmp(c->methods[i].display, c->methods[i].label) != 0) {   /* given, or the method's own */
            fputs(", display: \"", f);
            for (const char *p = c->methods[i].display; *p; p++)
                fprintf(f, *p == '"' || *p == '\\' ? "\\%c" : "%c", *p);
            fputc('"', f);
        }
        const struct sl_params *s = &p->values;
        for (int k = 0; k < s->n; k++) {
            if (s->off >> k & 1u)
                continue;   /* does not apply to these values */
            char v[64];
            sl_param_text(&s->decl[k], s->v[k], v, sizeof v);
            fprintf(f, ", %s: %s", s->decl[k].name, v);
        }
        if (c->methods[i].frame_fit.fit != SL_FIT_TIGHT)
            fprintf(f, ", light_frame: {fit: sphere, snap: %s}", c->methods[i].frame_fit.snap ? "true" : "false");
        fprintf(f, "}\n");
    }
}

static void write_techniques(const struct sl_config *c, FILE *f)
{
    if (!c->ntechniques)
        return;   /* none named: the search path alone (as before the key came) */
    fprintf(f, "techniques:\n");
    for (int i = 0; i < c->ntechniques; i++)
        fprintf(f, "  - %s\n", c->techniques[i]);
}

/* "" (the default, <output root>/shadowlab.db) is left out */
static void write_store(const struct sl_config *c, FILE *f)
{
    if (c->store[0])
        fprintf(f, "store: %s\n", c->store);
}

/* The settings under top-level key `key`: "key: value", or a group's
 * "key: {a: value, b: value}" in its declarations' order. */
static void write_settings(const struct sl_config *c, FILE *f, const char *key)
{
    size_t n = strlen(key);
    int in_group = 0;
    for (int k = 0; k < CONFIG_NSETTINGS; k++) {
        const struct sl_param *p = &config_settings[k];
        char v[64];
        sl_param_text(p, setting_field(c, k), v, sizeof v);
        if (!strcmp(p->name, key))
            fprintf(f, "%s: %s\n", key, v);
        else if (!strncmp(p->name, key, n) && p->name[n] == '.') {
            if (!in_group++)
                fprintf(f, "%s: {", key);
            else
                fputs(", ", f);
            fprintf(f, "%s: %s", p->name + n + 1, v);
        }
    }
    if (in_group)
        fputs("}\n", f);
}

void sl_config_write(const struct sl_config *c, FILE *f)
{
    fprintf(f, "# filled-in config: every default explicit\n");
#define WRITE_KEY(key, kind, ...) WRITE_##kind(key)
#define WRITE_STRING(key) write_##key(c, f);
#define WRITE_SEQ(key) write_##key(c, f);
#define WRITE_MAP(key) write_##key(c, f);
#define WRITE_UINT(key) write_##key(c, f);
#define WRITE_SETTINGS(key) write_settings(c, f, #key);
    CONFIG_KEYS(WRITE_KEY)
#undef WRITE_KEY
#undef WRITE_STRING
#undef WRITE_SEQ
#undef WRITE_MAP
#undef WRITE_UINT
#undef WRITE_SETTINGS
}

int sl_config_contour_label(const struct sl_config *c)
{
    for (int i = 0; i < c->nmethods; i++)
        if (strcmp(c->methods[i].method->name, "nsm") == 0 &&
            sl_params_get(&c->methods[i].params.values, "self_shadow") == SL_SELF_FRONT_FACES &&
            c->methods[i].frame_fit.fit == SL_FIT_TIGHT)
            return i;
    return -1;
}
