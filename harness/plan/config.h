/*
 * config.h — experiment files (YAML bound to a libcyaml schema, yamlfile.h):
 * parse, then validate with defaults filled in, then hand the run a plain
 * struct. Touches no GL and no Embree, so `shadowlab validate` is cheap.
 *
 * The file is read once into a positioned node tree (ytree.h); -D
 * overrides are grafted into that tree, a method entry's sweeps and package
 * parameters are taken out of it, and the rest is bound to the schema and
 * checked. Every error names the file, the line and the key (dotted path,
 * e.g. methods[1].self_shadow), each line the node's own; an error at a
 * value a -D override gave names the override ("-D KEY=VALUE") instead.
 *
 * Schema (all keys but scene, map_sizes and methods optional):
 *   name: default              # experiment name, output folder under results/
 *   scenes:                    # scene files by name (scenes/) or path (relative to this file)
 *     - {scene: primitives, viewpoints: [side, with]}   # default: all of the scene's viewpoints
 *     - {scene: primitives_motion, paths: [orbit]}      # a path's frames as views (pathfile.h);
 *                                                       # with paths, no viewpoint unless named
 *   viewports: [{width: 1024, height: 1024}]      # default 1024 x 1024
 *   map_sizes: [1024, 2048]    # powers of two, 64 .. 16384
 *   contours: [2, 4, 6]        # even thicknesses in pixels; the whole image is always added
 *   contour_from: nsm          # whose image the contours are drawn from: nsm (default, Moderno
 *                              # 2011's: NSM's, front faces culled, one contour per view and map
 *                              # shared by every method) or own (each method's own result image)
 *   methods:                   # the same method may appear under several labels
 *     - {label: nsm, method: nsm, self_shadow: front_faces}
 *     - {label: nsm_snap, method: nsm, light_frame: {fit: sphere, snap: true}}   # a stabilised
 *                              # frame of its own (lightfit.h); default fit tight, snap false
 *   outputs: {tables: true, overlays: true, overlay_contour: 2, exr: false, visibility: none}
 *   repetitions: {mode: adaptive}   # how often timed stages run (reps.h); fixed: {warmup: 1, runs: 5}
 *   seed: 1                    # for anything random
 *   store: results/shadowlab.db   # default: <output root>/shadowlab.db
 *   threads: 0                 # 0 = every core
 *   limits: {pass_seconds: 300}   # a technique package's GL pass ends the run past it
 */
#ifndef SL_CONFIG_H
#define SL_CONFIG_H
#include <stdio.h>
#include "fitopts.h"
#include "glbackend.h"
#include "methodparams.h"
#include "scenelimits.h"
#include "sl_error.h"

struct sl_method;    /* method.h */
struct sl_session;   /* session.h: what the load resolved besides values (scenes, packages) */

#define SL_CFG_MAX 32
/* A config is refused unread above 4 MiB: with at most SL_CFG_MAX entries
 * per list a real one is a few KiB, and a huge one would cost memory and
 * time (the YAML parse and its line index) before the entry limits apply. */
#define SL_CONFIG_MAX_BYTES ((size_t)4 << 20)

/* Whose result image a (view, map size)'s contours are drawn from. */
enum sl_contour_from {
    SL_CONTOUR_NSM = 0,   /* NSM's (front faces culled), shared by every method: the thesis's */
    SL_CONTOUR_OWN = 1,   /* each method's own verdicts */
};
const char *sl_contour_from_name(int policy);   /* "nsm", "own" */

struct sl_config_method {
    char                     label[48];
    char                     display[64];   /* the label's name in LaTeX tables ('display:', else the method's) */
    const struct sl_method  *method;
    struct sl_method_params  params;
    struct sl_fit_opts       frame_fit;   /* 'light_frame: {fit: tight|sphere, snap: bool}' (fitopts.h, lightfit.h);
                                           * zero: the tight fit every other label shares */
    int                      entry;       /* the `methods:` entry it comes from (a sweep's labels share one) */
};

struct sl_config_scene {
    char ref[256];                    /* as written */
    char path[1024];                  /* resolved scene file */
    char name[64];                    /* the scene's own name */
    int  nviewpoints;                 /* resolved: never 0; the named ones, then each path's frames */
    char viewpoints[SL_MAX_VIEWS][32];
    int  nnamed;                      /* of those, named viewpoints (the rest are frames) */
    int  npaths;                      /* paths named (pathfile.h), in order */
    char paths[SL_MAX_PATHS][24];
    unsigned map_mask;                /* bit i: swept at map size maps[i] */
    unsigned method_mask;             /* bit i: runs methods[i] */
    unsigned left_out;                /* bit i: methods[i] left out, the scene naming no list and the
                                       * label handling no light of its kind (sl_config_left_out_why) */
    int      light_type;              /* enum sl_light_type of the scene's light */
};

struct sl_config {
    char path[512];
    unsigned long long hash;          /* FNV-1a of the file's bytes */
    char name[64];
    int  nscenes;
    struct sl_config_scene scenes[SL_CFG_MAX];
    int  nviewports;
    int  viewport_w[SL_CFG_MAX], viewport_h[SL_CFG_MAX];
    int  nmaps;
    int  maps[SL_CFG_MAX];
    int  nregions;                    /* contours then 0 (whole image) */
    int  regions[SL_CFG_MAX];
    int  nmethods;
    struct sl_config_method methods[SL_CFG_MAX];   /* a sweep's entry expanded: one per label */
    int  ntechniques;                 /* 'techniques:' folders of packages, resolved (absolute) */
    char techniques[8][512];
    int  tables, overlays, exr;
    int  visibility;                  /* outputs.visibility: 0 none, 1 exr (visibility/<cell>.exr) */
    int  aliasing;                    /* resolved: the aliasing error m's figures (outputs.aliasing) */
    int  overlay_contour;
    int  contour_from;                /* enum sl_contour_from */
    int  rep_mode;                    /* repetitions.mode: enum sl_rep_mode (reps.h) */
    int  warmup, runs;                /* repetitions for timing (reps.h) */
    double rep_spread, rep_budget_ms, rep_share;   /* mode adaptive's stops (reps.h) */
    unsigned seed;
    int  area_samples;                /* area-light truth: samples per side of the light (0 = 32) */
    char store[512];                  /* "" = <output root>/shadowlab.db; relative, no '..' (validate) */
    int  store_line;                  /* its line in the config file (0: none or -D) */
    int  threads;                     /* resolved: >= 1 */
    enum sl_gl_backend gl;            /* 'gl: osmesa|egl'; resolved (never SL_GL_DEFAULT); the
                                       * command line's --gl replaces it */
    double pass_seconds;              /* limits.pass_seconds: a package's GL pass ends past it */
    struct sl_params settings;        /* the settings as the config gave them (config.c: CONFIG_SETTINGS;
                                       * given: which); the fields above hold them resolved */
    struct sl_session *session;       /* the scenes read and the technique packages the labels run
                                       * (owned); a copy of the struct shares it: free one copy */
};

/* Parse and validate; on failure d names file, line and key and *out holds
 * nothing to free. On success free with sl_config_free (its session). */
enum sl_err sl_config_load(const char *path, struct sl_config *out, struct sl_diag *d);
void        sl_config_free(struct sl_config *c);

/* The same with command-line overrides, each "key.path[i]=YAML value"
 * (-D): applied to the file's YAML before the schema and every check, so an
 * override is refused exactly as the same text in the file would be, the
 * diag then naming "-D key=value" as the source. The hash covers the file
 * and the overrides. */
enum sl_err sl_config_load_with(const char *path, const char *const *overrides, int n, struct sl_config *out,
                                struct sl_diag *d);

/* Write the filled-in config (every default explicit) as YAML. */
void sl_config_write(const struct sl_config *c, FILE *f);

/* The reference of every key a config file may give, from the parser's own
 * schema: a Markdown table (roff 0: doc/config.md) or man-page paragraphs
 * (roff 1). Fails (SL_E_USAGE, naming the key) when a key of the schema has
 * no text or a text names no key: the reference cannot drift. */
enum sl_err sl_config_reference(FILE *f, int roff, struct sl_diag *d);

/* The config's first label whose run is the contour's NSM (method nsm,
 * front faces culled: the configured parameters are then exactly those),
 * -1 none (run.c: contour_from nsm). */
int sl_config_contour_label(const struct sl_config *c);

/* "a point" for SL_LIGHT_POINT (a light type as a scene's messages name it). */
const char *sl_config_light_name(int type);
/* Why scene si left out label k (its bit in left_out: "handles area lights
 * only"), NULL when it did not. */
const char *sl_config_left_out_why(const struct sl_config *c, int si, int k);


#endif
