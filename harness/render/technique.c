/*
 * technique.c — see technique.h.
 * Invariants: a package is input and never trusted: every value read from
 * technique.yaml is checked here before anything uses it, every error names
 * technique.yaml's line and key (SL_E_PACKAGE), and no file outside the
 * package folder is read (shader paths are relative, hold no `..`, pass no
 * symbolic link and end on a regular file of bounded size). A loaded
 * sl_technique is self-contained: plain values and its two sources.
 */
#define _DEFAULT_SOURCE   /* DT_DIR, O_NOFOLLOW */
#include "technique.h"
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include "util.h"
#include "yamlfile.h"

#ifndef SL_TECHNIQUES_DIR
#define SL_TECHNIQUES_DIR "techniques"
#endif
#ifndef SL_TECHNIQUES_INSTALL_DIR
#define SL_TECHNIQUES_INSTALL_DIR "/usr/local/share/shadowlab/techniques"
#endif

#define NAME_(id, name) name,
const char *const sl_tech_format_names[4] = {SL_TECH_FORMATS(NAME_)};
const char *const sl_tech_filter_names[2] = {SL_TECH_FILTERS(NAME_)};
const char *const sl_tech_post_names[4] = {SL_TECH_POSTS(NAME_)};
const char *const sl_tech_cull_names[3] = {SL_TECH_CULLS(NAME_)};
#undef NAME_

/* ---- the schema: enums and numbers of a type given by another key are read
 * as strings and checked below, so each error names its own key ---- */

struct raw_param { char *name, *type, *def, *min, *max, *doc; };
struct raw_map { char *name, *format, *filter, *post, *blur; };
struct raw_scaled { double *texels; char *param; double *scale, *power; };
struct raw_trace { double *between; unsigned between_count; };
struct raw_tech {
    char *name, *summary, *cite, *family, *display, *cull, *map_shader, *lookup_shader;
    double *threshold;
    struct raw_map *maps;
    unsigned maps_count;
    struct raw_param *params;
    unsigned params_count;
    struct raw_scaled *reach, *taps;
    struct raw_trace *trace;
};

#define STR(key, type, member, max) CYAML_FIELD_STRING_PTR(key, CYAML_FLAG_POINTER, type, member, 1, max)
#define OPT_STR(key, type, member, max) \
    CYAML_FIELD_STRING_PTR(key, CYAML_FLAG_POINTER | CYAML_FLAG_OPTIONAL, type, member, 1, max)
#define OPT_DOUBLE(key, type, member) CYAML_FIELD_FLOAT_PTR(key, CYAML_FLAG_POINTER | CYAML_FLAG_OPTIONAL, type, member)

static const cyaml_schema_field_t param_fields[] = {
    STR("name", struct raw_param, name, 64),
    STR("type", struct raw_param, type, 16),
    STR("default", struct raw_param, def, 64),
    OPT_STR("min", struct raw_param, min, 64),
    OPT_STR("max", struct raw_param, max, 64),
    OPT_STR("doc", struct raw_param, doc, 199),
    CYAML_FIELD_END,
};
static const cyaml_schema_value_t param_schema = {
    CYAML_VALUE_MAPPING(CYAML_FLAG_DEFAULT, struct raw_param, param_fields),
};
static const cyaml_schema_field_t map_fields[] = {
    STR("name", struct raw_map, name, 64),
    STR("format", struct raw_map, format, 16),
    OPT_STR("filter", struct raw_map, filter, 16),
    OPT_STR("post", struct raw_map, post, 16),
    OPT_STR("blur", struct raw_map, blur, 64),
    CYAML_FIELD_END,
};
static const cyaml_schema_value_t map_schema = {
    CYAML_VALUE_MAPPING(CYAML_FLAG_DEFAULT, struct raw_map, map_fields),
};
static const cyaml_schema_field_t reach_fields[] = {
    OPT_DOUBLE("texels", struct raw_scaled, texels),
    OPT_STR("param", struct raw_scaled, param, 64),
    OPT_DOUBLE("scale", struct raw_scaled, scale),
    CYAML_FIELD_END,
};
static const cyaml_schema_field_t taps_fields[] = {
    OPT_DOUBLE("texels", struct raw_scaled, texels),
    OPT_STR("param", struct raw_scaled, param, 64),
    OPT_DOUBLE("scale", struct raw_scaled, scale),
    OPT_DOUBLE("power", struct raw_scaled, power),
    CYAML_FIELD_END,
};
static const cyaml_schema_value_t band_entry = {
    CYAML_VALUE_FLOAT(CYAML_FLAG_DEFAULT, double),
};
static const cyaml_schema_field_t trace_fields[] = {
    CYAML_FIELD_SEQUENCE("between", CYAML_FLAG_POINTER, struct raw_trace, between, &band_entry, 2, 2),
    CYAML_FIELD_END,
};
static const cyaml_schema_field_t tech_fields[] = {
    STR("name", struct raw_tech, name, 64),
    STR("summary", struct raw_tech, summary, 199),
    OPT_STR("cite", struct raw_tech, cite, 499),
    OPT_STR("family", struct raw_tech, family, 31),
    OPT_STR("display", struct raw_tech, display, 47),
    OPT_DOUBLE("threshold", struct raw_tech, threshold),
    OPT_STR("cull", struct raw_tech, cull, 16),
    CYAML_FIELD_SEQUENCE("maps", CYAML_FLAG_POINTER, struct raw_tech, maps, &map_schema, 1, SL_TECH_MAX_MAPS),
    STR("map_shader", struct raw_tech, map_shader, 255),
    STR("lookup_shader", struct raw_tech, lookup_shader, 255),
    CYAML_FIELD_MAPPING_PTR("reach", CYAML_FLAG_POINTER | CYAML_FLAG_OPTIONAL, struct raw_tech, reach, reach_fields),
    CYAML_FIELD_MAPPING_PTR("taps", CYAML_FLAG_POINTER | CYAML_FLAG_OPTIONAL, struct raw_tech, taps, taps_fields),
    CYAML_FIELD_MAPPING_PTR("trace", CYAML_FLAG_POINTER | CYAML_FLAG_OPTIONAL, struct raw_tech, trace, trace_fields),
    CYAML_FIELD_SEQUENCE("params", CYAML_FLAG_POINTER | CYAML_FLAG_OPTIONAL, struct raw_tech, params, &param_schema,
                         0, SL_TECH_MAX_PARAMS),
    CYAML_FIELD_END,
};
static const cyaml_schema_value_t tech_schema = {
    CYAML_VALUE_MAPPING(CYAML_FLAG_POINTER, struct raw_tech, tech_fields),
};

/* ---- checks ---- */

/* GLSL's keywords and reserved words (GLSL 4.50 §3.6), and the type names
 * made of a prefix and a shape: a name among them would not compile, or
 * would hide a type. */
static const char *const glsl_words[] = {
    "attribute", "const", "uniform", "varying", "buffer", "shared", "coherent", "volatile", "restrict",
    "readonly", "writeonly", "atomic_uint", "layout", "centroid", "flat", "smooth", "noperspective", "patch",
    "sample", "precise", "break", "continue", "do", "for", "while", "switch", "case", "default", "if", "else",
    "subroutine", "in", "out", "inout", "float", "double", "int", "void", "bool", "true", "false", "invariant",
    "discard", "return", "uint", "lowp", "mediump", "highp", "precision", "struct", "common", "partition",
    "active", "asm", "class", "union", "enum", "typedef", "template", "this", "resource", "goto", "inline",
    "noinline", "public", "static", "extern", "external", "interface", "long", "short", "half", "fixed",
    "unsigned", "superp", "input", "output", "filter", "sizeof", "cast", "namespace", "using", "main",
    NULL,
};
static const char *const glsl_type_prefixes[] = {
    "vec", "ivec", "uvec", "bvec", "dvec", "mat", "dmat", "hvec", "fvec", "sampler", "isampler", "usampler",
    "image", "iimage", "uimage", "texture", "itexture", "utexture", "subpass", NULL,
};

/* NULL when s is a GLSL identifier shadowlab lets a package use, else why not. */
static const char *ident_bad(const char *s)
{
    size_t n = strlen(s);
    if (n == 0 || n > 32)
        return "is not 1 to 32 characters";
    if (!((s[0] >= 'a' && s[0] <= 'z') || (s[0] >= 'A' && s[0] <= 'Z') || s[0] == '_'))
        return "is not a GLSL identifier (a letter or _ first)";
    for (const char *p = s; *p; p++)
        if (!((*p >= 'a' && *p <= 'z') || (*p >= 'A' && *p <= 'Z') || (*p >= '0' && *p <= '9') || *p == '_'))
            return "is not a GLSL identifier (letters, digits and _ only)";
    if (strncmp(s, "gl_", 3) == 0 || strstr(s, "__"))
        return "is reserved by GLSL (gl_ prefix or __)";
    if (strncmp(s, "sl_", 3) == 0)
        return "is reserved for the harness (sl_ prefix)";
    for (int i = 0; glsl_words[i]; i++)
        if (strcmp(s, glsl_words[i]) == 0)
            return "is a GLSL keyword";
    for (int i = 0; glsl_type_prefixes[i]; i++) {
        size_t k = strlen(glsl_type_prefixes[i]);
        if (strncmp(s, glsl_type_prefixes[i], k) == 0 && s[k] >= '1' && s[k] <= '9')
            return "is a GLSL type name";
        if (k >= 5 && strncmp(s, glsl_type_prefixes[i], k) == 0 && s[k] >= 'A' && s[k] <= 'Z')
            return "is a GLSL type name";
    }
    return NULL;
}

static int name_ok(const char *s)
{
    size_t n = strlen(s);
    if (n < 1 || n > 32 || !(s[0] >= 'a' && s[0] <= 'z'))
        return 0;
    for (const char *p = s; *p; p++)
        if (!((*p >= 'a' && *p <= 'z') || (*p >= '0' && *p <= '9') || *p == '_'))
            return 0;
    return 1;
}

static int pick(const char *s, const char *const *names, int n)
{
    for (int i = 0; i < n; i++)
        if (strcmp(s, names[i]) == 0)
            return i;
    return -1;
}

/* "a, b or c" */
static void one_of(char *buf, size_t size, const char *const *names, int n)
{
    size_t k = 0;
    buf[0] = '\0';
    for (int i = 0; i < n && k < size; i++)
        k += (size_t)snprintf(buf + k, size - k, "%s%s", i == 0 ? "" : i == n - 1 ? " or " : ", ", names[i]);
}

/* Read a shader of the package: `rel` a relative path of plain components
 * (no `..`, no `.`, no empty one), each on the way a folder and no link,
 * the last a regular file of at most SL_TECH_MAX_SHADER bytes. */
static enum sl_err read_shader(const struct sl_technique *t, const struct sl_yaml_pos *pos, const char *key,
                               const char *rel, char **out, struct sl_diag *d)
{
    *out = NULL;
    const char *file = t->file;
    if (rel[0] == '/')
        return sl_yaml_bad(d, SL_E_PACKAGE, file, pos, key, "'%s' is an absolute path: a shader is named "
                           "relative to the package folder", rel);
    char path[1400];
    int k = snprintf(path, sizeof path, "%s", t->dir);
    for (const char *p = rel; *p;) {
        size_t n = strcspn(p, "/");
        if (n == 0 || (n == 1 && p[0] == '.') || (n == 2 && p[0] == '.' && p[1] == '.'))
            return sl_yaml_bad(d, SL_E_PACKAGE, file, pos, key, "'%s' holds a '%.*s' component: a shader is a "
                               "plain path inside the package folder", rel, (int)(n ? n : 1), n ? p : "/");
        for (size_t i = 0; i < n; i++)
            if ((unsigned char)p[i] < 0x20)
                return sl_yaml_bad(d, SL_E_PACKAGE, file, pos, key, "'%s' holds a control character", rel);
        k += snprintf(path + k, sizeof path - (size_t)k, "/%.*s", (int)n, p);
        if ((size_t)k >= sizeof path)
            return sl_yaml_bad(d, SL_E_PACKAGE, file, pos, key, "'%s': path too long", rel);
        struct stat st;
        if (lstat(path, &st) != 0)
            return sl_yaml_bad(d, SL_E_PACKAGE, file, pos, key, "'%s' is not in the package folder %s: %s", rel,
                               t->dir, strerror(errno));
        if (S_ISLNK(st.st_mode))
            return sl_yaml_bad(d, SL_E_PACKAGE, file, pos, key, "'%s': %s is a symbolic link (refused: nothing "
                               "from a package's folder down may be a link)", rel, path);
        int last = p[n] == '\0';
        if (!last && !S_ISDIR(st.st_mode))
            return sl_yaml_bad(d, SL_E_PACKAGE, file, pos, key, "'%s': %s is not a folder", rel, path);
        if (last && !S_ISREG(st.st_mode))
            return sl_yaml_bad(d, SL_E_PACKAGE, file, pos, key, "'%s' is not a regular file", rel);
        char limit[32];
        if (last && (size_t)st.st_size > SL_TECH_MAX_SHADER)
            return sl_yaml_bad(d, SL_E_PACKAGE, file, pos, key, "'%s' is %lld bytes: a shader is at most %s",
                               rel, (long long)st.st_size, sl_size_text(SL_TECH_MAX_SHADER, limit, sizeof limit));
        p += n + (p[n] == '/');
        if (last)
            break;
        if (!*p)
            return sl_yaml_bad(d, SL_E_PACKAGE, file, pos, key, "'%s' ends in '/': a shader is a file", rel);
    }
    /* opened without following a link, and checked again on what was opened */
    int fd = open(path, O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0)
        return sl_yaml_bad(d, SL_E_PACKAGE, file, pos, key, "'%s': cannot read: %s", rel, strerror(errno));
    struct stat st;
    if (fstat(fd, &st) != 0 || !S_ISREG(st.st_mode) || (size_t)st.st_size > SL_TECH_MAX_SHADER) {
        close(fd);
        return sl_yaml_bad(d, SL_E_PACKAGE, file, pos, key, "'%s' changed while being read", rel);
    }
    size_t cap = (size_t)st.st_size + 1, n = 0;
    char *buf = malloc(cap + 1);
    if (!buf) {
        close(fd);
        return sl_fail(d, SL_E_NOMEM, path, 0, NULL, "reading the shader");
    }
    while (n < cap) {
        ssize_t r = read(fd, buf + n, cap - n);
        if (r < 0 && errno == EINTR)
            continue;
        if (r <= 0)
            break;
        n += (size_t)r;
    }
    close(fd);
    if (n > (size_t)st.st_size) {
        free(buf);
        return sl_yaml_bad(d, SL_E_PACKAGE, file, pos, key, "'%s' grew while being read", rel);
    }
    buf[n] = '\0';
    if (memchr(buf, '\0', n)) {
        free(buf);
        return sl_yaml_bad(d, SL_E_PACKAGE, file, pos, key, "'%s' holds a NUL byte: not GLSL text", rel);
    }
    *out = buf;
    return SL_OK;
}

/* Fill t from the loaded raw values, checking each. */
static enum sl_err fill(struct sl_technique *t, const struct raw_tech *r, const struct sl_yaml_pos *pos,
                        struct sl_diag *d)
{
    const char *file = t->file;
    char key[96], list[96];
    if (!name_ok(r->name))
        return sl_yaml_bad(d, SL_E_PACKAGE, file, pos, "name", "'%s': a technique's name is [a-z][a-z0-9_]{0,31}",
                           r->name);
    snprintf(t->name, sizeof t->name, "%s", r->name);
    snprintf(t->summary, sizeof t->summary, "%s", r->summary);
    snprintf(t->cite, sizeof t->cite, "%s", r->cite ? r->cite : "");
    if (r->family && !name_ok(r->family))
        return sl_yaml_bad(d, SL_E_PACKAGE, file, pos, "family",
                           "'%s': a family is a name like a technique's, [a-z][a-z0-9_]{0,31}", r->family);
    snprintf(t->family, sizeof t->family, "%s", r->family ? r->family : "package");
    for (const char *p = r->display ? r->display : ""; *p; p++)
        if ((unsigned char)*p < 0x20)
            return sl_yaml_bad(d, SL_E_PACKAGE, file, pos, "display", "one line of text, no control characters");
    snprintf(t->display, sizeof t->display, "%s", r->display ? r->display : "");
    t->threshold = r->threshold ? *r->threshold : 0.5;
    if (!(t->threshold >= 0.0 && t->threshold <= 1.0))
        return sl_yaml_bad(d, SL_E_PACKAGE, file, pos, "threshold", "%g: a threshold is in [0, 1]", t->threshold);
    t->cull = SL_TECH_CULL_NONE;
    if (r->cull) {
        int c = pick(r->cull, sl_tech_cull_names, 3);
        one_of(list, sizeof list, sl_tech_cull_names, 3);
        if (c < 0)
            return sl_yaml_bad(d, SL_E_PACKAGE, file, pos, "cull", "'%s': %s", r->cull, list);
        t->cull = (enum sl_tech_cull)c;
    }

    /* parameters first: maps and reach name them */
    t->nparams = (int)r->params_count;
    for (int i = 0; i < t->nparams; i++) {
        const struct raw_param *rp = &r->params[i];
        struct sl_param *p = &t->param[i];
        const char *why = ident_bad(rp->name);
        snprintf(key, sizeof key, "params[%d].name", i);
        if (why)
            return sl_yaml_bad(d, SL_E_PACKAGE, file, pos, key, "'%s' %s", rp->name, why);
        for (int j = 0; j < i; j++)
            if (!strcmp(t->param[j].name, rp->name))
                return sl_yaml_bad(d, SL_E_PACKAGE, file, pos, key, "'%s' names params[%d] already", rp->name, j);
        /* a config's method entry names these itself: the entry's own keys,
         * and the cascades every package takes (methods/package.c) */
        static const char *const entry_keys[] = {"label", "display", "method", "light_frame", "partitions", "lambda"};
        for (size_t j = 0; j < sizeof entry_keys / sizeof entry_keys[0]; j++)
            if (!strcmp(rp->name, entry_keys[j]))
                return sl_yaml_bad(d, SL_E_PACKAGE, file, pos, key, "'%s' is a key of the config's method entry "
                                   "(label, display, method, light_frame; partitions and lambda: the cascades)",
                                   rp->name);
        snprintf(p->name, sizeof p->name, "%s", rp->name);
        snprintf(key, sizeof key, "params[%d].type", i);
        int ty = pick(rp->type, sl_param_type_names, 3);
        one_of(list, sizeof list, sl_param_type_names, 3);
        if (ty < 0)
            return sl_yaml_bad(d, SL_E_PACKAGE, file, pos, key, "'%s': a parameter's type is %s", rp->type, list);
        p->type = (enum sl_param_type)ty;
        p->has_min = rp->min != NULL;
        p->has_max = rp->max != NULL;
        p->min = p->type == SL_PARAM_BOOL ? 0 : -INFINITY;
        p->max = p->type == SL_PARAM_BOOL ? 1 : INFINITY;
        if (p->type == SL_PARAM_BOOL && (rp->min || rp->max)) {
            snprintf(key, sizeof key, "params[%d].%s", i, rp->min ? "min" : "max");
            return sl_yaml_bad(d, SL_E_PACKAGE, file, pos, key, "a bool parameter has no range");
        }
        const char *const what[3] = {"default", "min", "max"};
        const char *const text[3] = {rp->def, rp->min, rp->max};
        double *const dst[3] = {&p->def, &p->min, &p->max};
        for (int k = 0; k < 3; k++) {
            if (!text[k])
                continue;
            snprintf(key, sizeof key, "params[%d].%s", i, what[k]);
            if ((why = sl_param_parse(p, text[k], dst[k])))
                return sl_yaml_bad(d, SL_E_PACKAGE, file, pos, key, "'%s' %s (the parameter is %s)", text[k], why,
                                   sl_param_type_names[p->type]);
        }
        if (p->min > p->max) {
            snprintf(key, sizeof key, "params[%d].max", i);
            return sl_yaml_bad(d, SL_E_PACKAGE, file, pos, key, "max %g is below min %g", p->max, p->min);
        }
        if (p->def < p->min || p->def > p->max) {
            snprintf(key, sizeof key, "params[%d].default", i);
            return sl_yaml_bad(d, SL_E_PACKAGE, file, pos, key, "default %g is outside [%g, %g]", p->def, p->min,
                               p->max);
        }
        snprintf(p->doc, sizeof p->doc, "%s", rp->doc ? rp->doc : "");
    }

    t->nmaps = (int)r->maps_count;
    for (int i = 0; i < t->nmaps; i++) {
        const struct raw_map *rm = &r->maps[i];
        struct sl_tech_map *m = &t->map[i];
        const char *why = ident_bad(rm->name);
        snprintf(key, sizeof key, "maps[%d].name", i);
        if (why)
            return sl_yaml_bad(d, SL_E_PACKAGE, file, pos, key, "'%s' %s", rm->name, why);
        for (int j = 0; j < i; j++)
            if (!strcmp(t->map[j].name, rm->name))
                return sl_yaml_bad(d, SL_E_PACKAGE, file, pos, key, "'%s' names maps[%d] already", rm->name, j);
        /* a map's sampler and the parameters' uniforms share the lookup's
         * names, its output out_<name> the map shader's */
        for (int j = 0; j < t->nparams; j++) {
            if (!strcmp(t->param[j].name, rm->name))
                return sl_yaml_bad(d, SL_E_PACKAGE, file, pos, key, "'%s' names a parameter already (both are "
                                   "uniforms of the lookup)", rm->name);
            if (!strncmp(t->param[j].name, "out_", 4) && !strcmp(t->param[j].name + 4, rm->name))
                return sl_yaml_bad(d, SL_E_PACKAGE, file, pos, key, "parameter '%s' is this map's output name",
                                   t->param[j].name);
        }
        snprintf(m->name, sizeof m->name, "%s", rm->name);
        snprintf(key, sizeof key, "maps[%d].format", i);
        int f = pick(rm->format, sl_tech_format_names, 4);
        one_of(list, sizeof list, sl_tech_format_names, 4);
        if (f < 0)
            return sl_yaml_bad(d, SL_E_PACKAGE, file, pos, key, "'%s': a map's format is %s", rm->format, list);
        m->format = (enum sl_tech_format)f;
        m->filter = SL_TECH_NEAREST;
        if (rm->filter) {
            snprintf(key, sizeof key, "maps[%d].filter", i);
            int k = pick(rm->filter, sl_tech_filter_names, 2);
            one_of(list, sizeof list, sl_tech_filter_names, 2);
            if (k < 0)
                return sl_yaml_bad(d, SL_E_PACKAGE, file, pos, key, "'%s': %s", rm->filter, list);
            m->filter = (enum sl_tech_filter)k;
        }
        m->post = SL_TECH_POST_NONE;
        if (rm->post) {
            snprintf(key, sizeof key, "maps[%d].post", i);
            int k = pick(rm->post, sl_tech_post_names, 4);
            one_of(list, sizeof list, sl_tech_post_names, 4);
            if (k < 0)
                return sl_yaml_bad(d, SL_E_PACKAGE, file, pos, key, "'%s': %s", rm->post, list);
            m->post = (enum sl_tech_post)k;
        }
        const int blurred = m->post == SL_TECH_POST_BLUR || m->post == SL_TECH_POST_BLUR_MIPMAPS;
        m->blur = -1;
        snprintf(key, sizeof key, "maps[%d].blur", i);
        if (rm->blur && !blurred)
            return sl_yaml_bad(d, SL_E_PACKAGE, file, pos, key, "a blur radius for post %s (blur or blur_mipmaps "
                               "blur)", sl_tech_post_names[m->post]);
        if (blurred) {
            if (!rm->blur) {
                snprintf(key, sizeof key, "maps[%d].post", i);
                return sl_yaml_bad(d, SL_E_PACKAGE, file, pos, key, "post %s needs `blur:`, the int parameter "
                                   "giving the radius", sl_tech_post_names[m->post]);
            }
            m->blur = sl_tech_param_index(t, rm->blur);
            if (m->blur < 0)
                return sl_yaml_bad(d, SL_E_PACKAGE, file, pos, key, "'%s' names no parameter", rm->blur);
            const struct sl_param *bp = &t->param[m->blur];
            if (bp->type != SL_PARAM_INT)
                return sl_yaml_bad(d, SL_E_PACKAGE, file, pos, key, "'%s' is a %s parameter: a blur radius is an "
                                   "int", rm->blur, sl_param_type_names[bp->type]);
            if (!bp->has_min || !bp->has_max || bp->min < 0 || bp->max > 64)
                return sl_yaml_bad(d, SL_E_PACKAGE, file, pos, key, "'%s' needs a range within [0, 64] (min and "
                                   "max): a blur radius is bounded", rm->blur);
        }
    }

    /* reach and taps */
    const struct raw_scaled *rs[2] = {r->reach, r->taps};
    struct sl_tech_scaled *ts[2] = {&t->reach, &t->taps};
    const char *const sname[2] = {"reach", "taps"};
    for (int k = 0; k < 2; k++) {
        struct sl_tech_scaled *s = ts[k];
        s->texels = k == 1 && !rs[k] ? 1.0 : 0.0;
        s->scale = 1.0;
        s->power = 1.0;
        s->param = -1;
        s->given = rs[k] != NULL;
        if (!rs[k])
            continue;
        if (rs[k]->texels)
            s->texels = *rs[k]->texels;
        if (rs[k]->scale)
            s->scale = *rs[k]->scale;
        if (rs[k]->power)
            s->power = *rs[k]->power;
        const double lim = k == 0 ? 1024.0 : 1e6;
        snprintf(key, sizeof key, "%s.texels", sname[k]);
        /* a negative constant offsets a scaled parameter (pcf: 0.5 kernel
         * - 0.5); the sum is taken as 0 where it falls below */
        if (!(s->texels >= -lim && s->texels <= lim))
            return sl_yaml_bad(d, SL_E_PACKAGE, file, pos, key, "%g: texels is in [-%g, %g]", s->texels, lim, lim);
        snprintf(key, sizeof key, "%s.scale", sname[k]);
        if (!(s->scale >= 0.0 && s->scale <= lim))
            return sl_yaml_bad(d, SL_E_PACKAGE, file, pos, key, "%g: scale is in [0, %g]", s->scale, lim);
        snprintf(key, sizeof key, "%s.power", sname[k]);
        if (!(s->power >= 0.0 && s->power <= 4.0))
            return sl_yaml_bad(d, SL_E_PACKAGE, file, pos, key, "%g: power is in [0, 4]", s->power);
        if (rs[k]->param) {
            snprintf(key, sizeof key, "%s.param", sname[k]);
            s->param = sl_tech_param_index(t, rs[k]->param);
            if (s->param < 0)
                return sl_yaml_bad(d, SL_E_PACKAGE, file, pos, key, "'%s' names no parameter", rs[k]->param);
            const struct sl_param *p = &t->param[s->param];
            if (p->type == SL_PARAM_BOOL)
                return sl_yaml_bad(d, SL_E_PACKAGE, file, pos, key, "'%s' is a bool: %s scales with an int or "
                                   "float parameter", rs[k]->param, sname[k]);
            if (!p->has_min || !p->has_max || p->min < 0)
                return sl_yaml_bad(d, SL_E_PACKAGE, file, pos, key, "'%s' needs a range (min >= 0 and max): %s "
                                   "is bounded", rs[k]->param, sname[k]);
            if (k == 0 && s->texels + s->scale * pow(p->max, s->power) > 1024.0)
                return sl_yaml_bad(d, SL_E_PACKAGE, file, pos, key, "reach at '%s' = %g is %g texels: at most "
                                   "1024", rs[k]->param, p->max, s->texels + s->scale * pow(p->max, s->power));
        }
    }

    /* the traced band: a visibility at or between its ends is replaced by
     * the truth's ray (methods/package.c) */
    t->trace = r->trace != NULL;
    if (t->trace) {
        t->trace_lo = r->trace->between[0];
        t->trace_hi = r->trace->between[1];
        if (!(t->trace_lo >= 0.0 && t->trace_lo < t->trace_hi && t->trace_hi <= 1.0))
            return sl_yaml_bad(d, SL_E_PACKAGE, file, pos, "trace.between", "[%g, %g]: a band is [lo, hi] with "
                               "0 <= lo < hi <= 1", t->trace_lo, t->trace_hi);
    }

    snprintf(t->map_shader, sizeof t->map_shader, "%s", r->map_shader);
    snprintf(t->lookup_shader, sizeof t->lookup_shader, "%s", r->lookup_shader);
    enum sl_err e = read_shader(t, pos, "map_shader", r->map_shader, &t->map_src, d);
    if (!e)
        e = read_shader(t, pos, "lookup_shader", r->lookup_shader, &t->lookup_src, d);
    return e;
}

enum sl_err sl_tech_load(const char *dir, struct sl_technique *t, struct sl_diag *d)
{
    memset(t, 0, sizeof *t);
    size_t n = strlen(dir);
    while (n > 1 && dir[n - 1] == '/')
        n--;
    if (n >= sizeof t->dir)
        return sl_fail(d, SL_E_PACKAGE, dir, 0, NULL, "package folder path too long");
    snprintf(t->dir, sizeof t->dir, "%.*s", (int)n, dir);
    snprintf(t->file, sizeof t->file, "%s/technique.yaml", t->dir);
    /* One rule for a package, folders and files alike: nothing from its
     * folder down is a symbolic link (the folder itself, technique.yaml,
     * every folder and file on a shader's path; read_shader). A package is
     * copied, archived and hashed as its own folder, and a link would make
     * part of it something outside that folder, which a copy carries
     * differently or not at all. The folders that hold packages (a search
     * path entry, `techniques:`) may be reached through links: they are
     * where packages are kept, not part of one. */
    struct stat st;
    if (lstat(t->dir, &st) == 0 && S_ISLNK(st.st_mode))
        return sl_fail(d, SL_E_PACKAGE, t->dir, 0, NULL, "the package folder is a symbolic link: refused (nothing "
                       "from a package's folder down may be a link; name the folder it points to)");
    if (lstat(t->file, &st) != 0)
        return sl_fail(d, SL_E_PACKAGE, t->file, 0, NULL, "no technique.yaml in %s: %s", t->dir, strerror(errno));
    if (S_ISLNK(st.st_mode))
        return sl_fail(d, SL_E_PACKAGE, t->file, 0, NULL, "a symbolic link: refused (nothing from a package's folder "
                       "down may be a link)");
    struct raw_tech *r = NULL;
    struct sl_yaml_pos *pos = NULL;
    enum sl_err e = sl_yaml_load(t->file, &tech_schema, (void **)&r, &pos, SL_TECH_MAX_YAML, SL_E_PACKAGE, d);
    if (e == SL_E_IO)   /* a package that cannot be read is a bad package (exit 2), as its diag says */
        e = SL_E_PACKAGE;
    if (!e) {
        t->name_line = sl_yaml_line(pos, "name");
        t->file_hash = sl_ytree_hash(pos);
        e = fill(t, r, pos, d);
    }
    sl_yaml_free(&tech_schema, r, pos);
    if (e) {
        sl_tech_free(t);
        memset(t, 0, sizeof *t);
    }
    return e;
}

void sl_tech_free(struct sl_technique *t)
{
    if (!t)
        return;
    free(t->map_src);
    free(t->lookup_src);
    t->map_src = t->lookup_src = NULL;
}

int sl_tech_param_index(const struct sl_technique *t, const char *name)
{
    for (int i = 0; i < t->nparams; i++)
        if (!strcmp(t->param[i].name, name))
            return i;
    return -1;
}

int sl_tech_map_index(const struct sl_technique *t, const char *name)
{
    for (int i = 0; i < t->nmaps; i++)
        if (!strcmp(t->map[i].name, name))
            return i;
    return -1;
}

/* ---- values ---- */

void sl_tech_defaults(const struct sl_technique *t, struct sl_params *v)
{
    sl_params_init(v, t->param, t->nparams);
}

static double scaled(const struct sl_tech_scaled *s, const struct sl_params *v)
{
    double x = s->texels;
    if (s->param >= 0 && s->param < v->n) {
        double p = v->v[s->param];
        x += s->scale * pow(p > 0 ? p : 0, s->power);
    }
    return x >= 0 ? x : 0;   /* NaN: 0 */
}

int sl_tech_reach(const struct sl_technique *t, const struct sl_params *v)
{
    double x = ceil(scaled(&t->reach, v));
    return x < 1e6 ? (int)x : 1000000;
}

int sl_tech_guard(const struct sl_technique *t, const struct sl_params *v)
{
    int g = sl_tech_reach(t, v), blur = 0;
    for (int i = 0; i < t->nmaps; i++)
        if (t->map[i].blur >= 0 && t->map[i].blur < v->n && v->v[t->map[i].blur] > blur)
            blur = (int)v->v[t->map[i].blur];
    return g + blur;
}

double sl_tech_taps(const struct sl_technique *t, const struct sl_params *v)
{
    return scaled(&t->taps, v);
}

int sl_tech_guard_param(const struct sl_technique *t)
{
    if (t->reach.param >= 0)
        return t->reach.param;
    for (int i = 0; i < t->nmaps; i++)
        if (t->map[i].blur >= 0)
            return t->map[i].blur;
    return -1;
}

/* ---- the search path and the set ---- */

int sl_tech_dirs(const char *const *config_dirs, int nconfig, const char *rel_dir, char (*dirs)[1024],
                 const char **origin, int max)
{
    int n = 0;
    for (int i = 0; i < nconfig && n < max; i++) {
        if (config_dirs[i][0] == '/' || !rel_dir)
            snprintf(dirs[n], 1024, "%s", config_dirs[i]);
        else
            snprintf(dirs[n], 1024, "%s/%s", rel_dir, config_dirs[i]);
        origin[n++] = "config";
    }
    const char *e = getenv("SHADOWLAB_TECHNIQUES");
    for (const char *p = e; p && *p && n < max;) {
        size_t k = strcspn(p, ":");
        if (k) {
            snprintf(dirs[n], 1024, "%.*s", (int)k, p);
            origin[n++] = "SHADOWLAB_TECHNIQUES";
        }
        p += k + (p[k] == ':');
    }
    if (n < max) {
        snprintf(dirs[n], 1024, "%s", SL_TECHNIQUES_DIR);
        origin[n++] = "source tree";
    }
    if (n < max) {
        snprintf(dirs[n], 1024, "%s", SL_TECHNIQUES_INSTALL_DIR);
        origin[n++] = "installed";
    }
    return n;
}

static int has_yaml(const char *dir)
{
    char p[1100];
    snprintf(p, sizeof p, "%s/technique.yaml", dir);
    struct stat st;
    return lstat(p, &st) == 0;
}

static int cmp_name(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

/* Load the package in dir into the set unless its name is taken. */
static enum sl_err add_one(struct sl_tech_set *s, const char *dir, const char *origin, const char *const *c_names,
                           struct sl_diag *d)
{
    struct sl_technique t;
    enum sl_err e = sl_tech_load(dir, &t, d);
    if (e)
        return e;
    for (int i = 0; c_names && c_names[i]; i++)
        if (!strcmp(c_names[i], t.name)) {
            e = sl_fail(d, SL_E_PACKAGE, t.file, t.name_line, "name", "'%s' is the name of a C method: a package may not "
                        "shadow one (rename it, e.g. %s_glsl)", t.name, t.name);
            sl_tech_free(&t);
            return e;
        }
    const struct sl_technique *had = sl_tech_find(s, t.name);
    if (had) {
        /* the same package reached twice (a folder named twice, the source
         * tree's and its installed copy) is one package; two different
         * packages of one name would leave the choice to the search order */
        int same = had->file_hash == t.file_hash && !strcmp(had->map_src, t.map_src) &&
                   !strcmp(had->lookup_src, t.lookup_src);
        if (!same)
            e = sl_fail(d, SL_E_PACKAGE, t.file, t.name_line, "name", "'%s' names two packages on the search "
                        "path: %s (%s) and this one (%s); rename one", t.name, had->file,
                        had->origin ? had->origin : "given", origin ? origin : "given");
        sl_tech_free(&t);
        return e;
    }
    if (s->n >= SL_TECH_MAX_SET) {
        sl_tech_free(&t);
        return sl_fail(d, SL_E_PACKAGE, dir, 0, NULL, "more than %d technique packages", SL_TECH_MAX_SET);
    }
    void *p = realloc(s->t, (size_t)(s->n + 1) * sizeof *s->t);
    if (!p) {
        sl_tech_free(&t);
        return sl_fail(d, SL_E_NOMEM, dir, 0, NULL, "technique set");
    }
    s->t = p;
    t.origin = origin;
    s->t[s->n++] = t;
    return SL_OK;
}

static enum sl_err scan_dir(struct sl_tech_set *s, const char *dir, const char *origin, const char *const *c_names,
                            struct sl_diag *d)
{
    struct stat st;
    if (stat(dir, &st) != 0 || !S_ISDIR(st.st_mode))
        return SL_OK;   /* a folder of the path that is not there */
    if (has_yaml(dir))
        return add_one(s, dir, origin, c_names, d);
    DIR *dp = opendir(dir);
    if (!dp)
        return sl_fail(d, SL_E_IO, dir, 0, NULL, "cannot read the techniques folder: %s", strerror(errno));
    enum { MAXSUB = 1024 };
    char **names = calloc(MAXSUB, sizeof *names);
    int n = 0;
    enum sl_err e = names ? SL_OK : sl_fail(d, SL_E_NOMEM, dir, 0, NULL, "techniques folder");
    for (struct dirent *de; !e && (de = readdir(dp));) {
        if (de->d_name[0] == '.')
            continue;
        if (n == MAXSUB) {
            e = sl_fail(d, SL_E_PACKAGE, dir, 0, NULL, "more than %d entries in a techniques folder", MAXSUB);
            break;
        }
        if (!(names[n] = strdup(de->d_name)))
            e = sl_fail(d, SL_E_NOMEM, dir, 0, NULL, "techniques folder");
        else
            n++;
    }
    closedir(dp);
    if (!e)
        qsort(names, (size_t)n, sizeof *names, cmp_name);
    for (int i = 0; !e && i < n; i++) {
        char sub[1024];
        if (snprintf(sub, sizeof sub, "%s/%s", dir, names[i]) >= (int)sizeof sub)
            continue;
        if (stat(sub, &st) == 0 && S_ISDIR(st.st_mode) && has_yaml(sub))
            e = add_one(s, sub, origin, c_names, d);
    }
    for (int i = 0; names && i < n; i++)
        free(names[i]);
    free(names);
    return e;
}

enum sl_err sl_tech_set_scan(struct sl_tech_set *s, char (*dirs)[1024], const char *const *origin, int ndirs,
                             const char *const *c_names, struct sl_diag *d)
{
    memset(s, 0, sizeof *s);
    for (int i = 0; i < ndirs; i++) {
        enum sl_err e = scan_dir(s, dirs[i], origin ? origin[i] : NULL, c_names, d);
        if (e) {
            sl_tech_set_free(s);
            return e;
        }
    }
    return SL_OK;
}

const struct sl_technique *sl_tech_find(const struct sl_tech_set *s, const char *name)
{
    for (int i = 0; i < s->n; i++)
        if (!strcmp(s->t[i].name, name))
            return &s->t[i];
    return NULL;
}

void sl_tech_set_free(struct sl_tech_set *s)
{
    for (int i = 0; i < s->n; i++)
        sl_tech_free(&s->t[i]);
    free(s->t);
    memset(s, 0, sizeof *s);
}
