/*
 * technique.h — shadow technique packages (issue 36): a folder holding
 * technique.yaml and the two GLSL files it names, loaded at run time.
 *
 * What it does: reads and checks technique.yaml against its schema (a libcyaml
 * schema bound by sl_yaml_load: unknown keys, missing keys, types, ranges, a default
 * outside [min, max], names that are no GLSL identifiers, a `blur:` or
 * `reach.param` naming no parameter, a `trace:` band that is not
 * 0 <= lo < hi <= 1), checks the shader paths (relative, no
 * `..`, no symbolic link on the way, a regular file inside the package
 * folder, at most SL_TECH_MAX_SHADER bytes) and reads both sources. Packages
 * are untrusted input: every error is `FILE:LINE: 'KEY': message` with the id
 * SL_E_PACKAGE (exit 2). Also: the set of packages found along a search path
 * (one package a name; a C method's name is refused), the search path itself,
 * parameter values (defaults, checked setting), the guard band a package's
 * lookup needs (reach, blur) and the texel reads it counts (taps).
 * What a package may hold and what its shaders see is issue 36's package
 * contract (techpass.h: the passes and the preludes).
 *
 * Owns: each sl_technique's shader sources (sl_tech_free), a set's
 * techniques (sl_tech_set_free).
 * Does not: touch GL (techpass.h compiles and runs a package), know the C
 * methods (their names come in as an argument), read configs.
 */
#ifndef SL_TECHNIQUE_H
#define SL_TECHNIQUE_H
#include <stddef.h>
#include "params.h"
#include "sl_error.h"

#define SL_TECH_MAX_PARAMS 16
#define SL_TECH_MAX_MAPS 4
#define SL_TECH_NAME_MAX 40                       /* names: at most 32 characters */
#define SL_TECH_MAX_YAML ((size_t)64 << 10)       /* technique.yaml: refused unread above this */
#define SL_TECH_MAX_SHADER ((size_t)256 << 10)    /* each GLSL file */
#define SL_TECH_MAX_SET 256                       /* packages in one set */
#define SL_TECH_MAX_DIRS 32                       /* folders of a search path */
#define SL_TECH_MAX_MAP_SIZE 16384                /* guarded map side, texels (GL's own limit may be lower) */

/* The closed sets of technique.yaml, each one list: the enum (SL_TECH_<ID>,
 * SL_TECH_POST_<ID>, SL_TECH_CULL_<ID>) and the YAML spelling together. */
#define SL_TECH_FORMATS(X) X(R32F, "r32f") X(RG32F, "rg32f") X(RGBA32F, "rgba32f") X(RGBA16F, "rgba16f")
#define SL_TECH_FILTERS(X) X(NEAREST, "nearest") X(LINEAR, "linear")
#define SL_TECH_POSTS(X) X(NONE, "none") X(BLUR, "blur") X(MIPMAPS, "mipmaps") X(BLUR_MIPMAPS, "blur_mipmaps")
#define SL_TECH_CULLS(X) X(NONE, "none") X(FRONT, "front") X(BACK, "back")

#define SL_TECH_ENUM_(id, name) SL_TECH_##id,
#define SL_TECH_POST_ENUM_(id, name) SL_TECH_POST_##id,
#define SL_TECH_CULL_ENUM_(id, name) SL_TECH_CULL_##id,
enum sl_tech_format { SL_TECH_FORMATS(SL_TECH_ENUM_) };
enum sl_tech_filter { SL_TECH_FILTERS(SL_TECH_ENUM_) };
enum sl_tech_post { SL_TECH_POSTS(SL_TECH_POST_ENUM_) };
enum sl_tech_cull { SL_TECH_CULLS(SL_TECH_CULL_ENUM_) };
#undef SL_TECH_ENUM_
#undef SL_TECH_POST_ENUM_
#undef SL_TECH_CULL_ENUM_

/* the YAML spellings, by enum value */
extern const char *const sl_tech_format_names[4];   /* r32f rg32f rgba32f rgba16f */
extern const char *const sl_tech_filter_names[2];   /* nearest linear */
extern const char *const sl_tech_post_names[4];     /* none blur mipmaps blur_mipmaps */
extern const char *const sl_tech_cull_names[3];     /* none front back */

/* A package's parameters are declared in the one form every method uses
 * (base/params.h): int, float or bool (no choice: technique.yaml has no
 * words), min/max -inf/+inf when not given, no unit. */

struct sl_tech_map {
    char name[SL_TECH_NAME_MAX];
    enum sl_tech_format format;
    enum sl_tech_filter filter;
    enum sl_tech_post post;
    int blur;                   /* index of the int parameter giving the blur radius; -1 without blur */
};

/* reach and taps: texels + scale * value(param)^power (param -1: texels alone) */
struct sl_tech_scaled {
    double texels, scale, power;
    int param;
    int given;                  /* technique.yaml has the key (else the default) */
};

struct sl_technique {
    char name[SL_TECH_NAME_MAX];
    char summary[200];
    char cite[500];
    char display[48];                /* `display:`, the name LaTeX tables print; "": the name */
    char family[SL_TECH_NAME_MAX];   /* `family:` (e.g. filtered), "package" when not given: the
                                      * report's grouping (sl_method.family) */
    char dir[1024];             /* the package folder, as found */
    char file[1100];            /* dir/technique.yaml: what errors name */
    int name_line;              /* the line of its `name:` */
    unsigned long long file_hash;   /* FNV-1a of technique.yaml's bytes as read (sl_hash_file's):
                                     * a config's hash covers it without reading the file again */
    const char *origin;         /* where it was found (sl_tech_dirs' origins); NULL when loaded alone */
    double threshold;           /* lit iff visibility >= threshold (default 0.5) */
    enum sl_tech_cull cull;
    int nmaps;
    struct sl_tech_map map[SL_TECH_MAX_MAPS];
    int nparams;
    struct sl_param param[SL_TECH_MAX_PARAMS];
    struct sl_tech_scaled reach;   /* default 0 texels */
    struct sl_tech_scaled taps;    /* default 1 texel */
    /* `trace: {between: [lo, hi]}`: a PFL pixel whose visibility v has
     * lo <= v <= hi is traced with the truth's rays and takes their 0 or 1
     * (a hybrid: methods/package.c); 0 <= lo < hi <= 1 */
    int trace;
    double trace_lo, trace_hi;
    char map_shader[256], lookup_shader[256];   /* as written, relative to dir */
    char *map_src, *lookup_src;    /* their text, NUL-terminated (owned) */
};

/* Load the package in folder dir (dir/technique.yaml). Every failure is
 * SL_E_PACKAGE naming technique.yaml's line and key (SL_E_IO for a folder
 * that cannot be read, SL_E_NOMEM). On failure *t holds nothing to free. */
enum sl_err sl_tech_load(const char *dir, struct sl_technique *t, struct sl_diag *d);
void        sl_tech_free(struct sl_technique *t);

/* The index of a parameter (or map) by name, -1 if none. */
int sl_tech_param_index(const struct sl_technique *t, const char *name);
int sl_tech_map_index(const struct sl_technique *t, const char *name);

/* ---- parameter values: a set over t->param (base/params.h), in its order ---- */
/* The set of t's parameters at their defaults (sl_params_init over t->param);
 * a config's values are given with sl_params_put. */
void sl_tech_defaults(const struct sl_technique *t, struct sl_params *v);

/* How far the lookup reads beyond the texel a point lands in, texels:
 * ceil(reach.texels + reach.scale * value^power), at least 0. */
int sl_tech_reach(const struct sl_technique *t, const struct sl_params *v);
/* The guard band g of the maps: reach plus the largest blur radius of a
 * blurred map (its box reads that far beyond the texels the lookup reads). */
int sl_tech_guard(const struct sl_technique *t, const struct sl_params *v);
/* Texel reads per looked-up pixel (taps), at least 0. */
double sl_tech_taps(const struct sl_technique *t, const struct sl_params *v);
/* The parameter the guard band grows with (reach's, else a blurred map's
 * radius), -1 when it is fixed: what an error about the map size names. */
int sl_tech_guard_param(const struct sl_technique *t);

/* ---- where packages come from ---- */

/* The search path, in order, each folder with its origin: config_dirs (the
 * config's `techniques:` folders, relative to rel_dir when not absolute:
 * "config"), each folder of SHADOWLAB_TECHNIQUES (colon-separated:
 * "SHADOWLAB_TECHNIQUES"), the source tree's techniques/ ("source tree",
 * compiled in), <prefix>/share/shadowlab/techniques ("installed"). Returns
 * how many (at most max). */
int sl_tech_dirs(const char *const *config_dirs, int nconfig, const char *rel_dir, char (*dirs)[1024],
                 const char **origin, int max);

struct sl_tech_set {
    int n;
    struct sl_technique *t;     /* n of them, in the order found */
};

/* Scan the folders in order: a folder holding technique.yaml is one
 * package, else each of its subfolders holding one is (in name order); a
 * folder that does not exist is skipped. A name is one package: a second
 * package of a name fails the scan naming both files, unless it is the
 * same package (technique.yaml and both shaders byte for byte: one folder
 * reached twice, the source tree's package and its installed copy), which
 * is kept once, as first found. A package that fails to load fails the
 * scan (packages are input: a broken one is an error, not skipped); so
 * does one named like a C method (c_names, NULL-terminated; may be NULL),
 * naming its file, line and 'name'. On failure *s is empty. */
enum sl_err sl_tech_set_scan(struct sl_tech_set *s, char (*dirs)[1024], const char *const *origin, int ndirs,
                             const char *const *c_names, struct sl_diag *d);
const struct sl_technique *sl_tech_find(const struct sl_tech_set *s, const char *name);
void sl_tech_set_free(struct sl_tech_set *s);

#endif
