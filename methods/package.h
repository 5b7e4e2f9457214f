/*
 * package.h — technique packages (render/technique.h: a folder of
 * technique.yaml + GLSL) as methods: each package found along the search
 * path becomes a struct sl_method named like the package, found by
 * sl_method_find after the C methods, whose run renders the package's maps
 * for the cell's light frame and runs its lookup over the G-buffer on the
 * GL (render/techpass.h), the visibility read back and scored on the CPU.
 *
 * A package method is a hard-shadow method (lights 0: any light, a point
 * light per face of its cube as the C methods run there, methods/cuberun.h;
 * an area light as a point at its centre), exact in nothing; its verdict is lit iff the visibility >= the package's
 * threshold (uncertain where the lookup was not finite: NaN in vis, and the
 * maps' texels not finite counted in vd->nonfinite), and it hands the visibility itself to scoring (vd->vis,
 * has_vis) for the fractional figures. Its parameters are the package's,
 * in the package's order, then the cascades' (partitions, lambda), given
 * in the config entry like a C method's (struct sl_method_params: tech,
 * values); costs: `lookups` the package's taps per pixel looked up, ms_method
 * the map pass, the post passes, the lookup pass and the readback, the
 * map, post and readback also apart (ms_map, ms_post, ms_readback) with
 * the GPU times of its passes, so a cell's stages read as a C method's.
 *
 * A package whose technique.yaml declares `trace: {between: [lo, hi]}` is a
 * hybrid: the PFL pixels whose visibility lies in [lo, hi] are traced with
 * the truth's own rays (sl_method_trace_left: `rays`, ms_trace) and take
 * the ray's verdict and a visibility of exactly 0 or 1; its method promises
 * SL_EXACT_PROVED, so every traced pixel is checked against the truth.
 *
 * Owns: nothing of its own: a set (struct sl_packages) owns the packages
 * loaded into it and their GL passes (sl_packages_release_gl before the GL
 * context goes, sl_packages_free after); a config's set lives in its
 * session (plan/session.h), so two configs loaded in one process never
 * share or shadow each other's packages.
 */
#ifndef SL_PACKAGE_H
#define SL_PACKAGE_H
#include "method.h"
#include "technique.h"

/* A set of loaded packages, each a method: what one config resolved
 * (plan/session.h owns one per loaded config). Zero is the empty set. */
struct pkg;
struct sl_packages {
    struct pkg *pkg[SL_TECH_MAX_SET];
    int         n;
};

/* Load the packages along the search path (sl_tech_dirs: the config's
 * `techniques:` folders relative to rel_dir, SHADOWLAB_TECHNIQUES, the
 * source tree's, the installed ones) into set, a method of each one not
 * yet in it under its name (a later search path finds the name taken and
 * keeps the first). SL_E_PACKAGE for a broken package, two different
 * packages of one name along the path (sl_tech_set_scan), or one named
 * like a C method (c_names, NULL-terminated: the
 * registry's, which the caller reads, so this file never calls the
 * registry that calls it). */
enum sl_err sl_packages_load(struct sl_packages *set, const char *const *config_dirs, int n, const char *rel_dir,
                             const char *const *c_names, struct sl_diag *d);
/* Free the set's packages (their GL objects released first:
 * sl_packages_release_gl); the set is empty after. */
void sl_packages_free(struct sl_packages *set);

/* The set's package method of that name, NULL if none (or set NULL). */
const struct sl_method *sl_packages_find(const struct sl_packages *set, const char *name);
/* Packages in the set, and the i-th (listing). */
int                        sl_packages_count(const struct sl_packages *set);
const struct sl_technique *sl_packages_at(const struct sl_packages *set, int i);

/* A method's package, NULL for a C method (the method is a member of its
 * package's record: no table is searched). */
const struct sl_technique *sl_package_of(const struct sl_method *m);

/* Compile m's GL programs now (a package method; others: nothing), so a
 * GLSL error stops a run before its first cell: SL_E_PACKAGE naming the
 * package file and line. The GL context must be current. */
enum sl_err sl_package_prepare(const struct sl_method *m, struct sl_diag *d);

/* Whether m's maps at map size `size` and values p fit the GL's maximum
 * texture size (and SL_TECH_MAX_MAP_SIZE): SL_E_METHOD naming the
 * parameter that grows the guard band (techpass.h's sl_techpass_size),
 * SL_OK for a method that is no package. After sl_package_prepare, so a
 * run checks every label and map size before its first truth. */
enum sl_err sl_package_fits(const struct sl_method *m, const struct sl_method_params *p, int size, struct sl_diag *d);

/* Free every package's GL objects in set (the GL context still current). */
void sl_packages_release_gl(struct sl_packages *set);

#endif
