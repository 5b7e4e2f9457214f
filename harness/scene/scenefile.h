/*
 * scenefile.h — scene files (YAML in scenes/): meshes from procedural
 * generators or model files (through meshio.c), each with a transform and
 * two-sidedness; one light (directional; spot and point with a position;
 * rectangular area lights with a size); named viewpoints.
 *
 * Parse, validate (every error names file, line and key), then build. No GL,
 * no Embree: `shadowlab validate` loads scenes fully.
 *
 *   name: primitives                     # defaults to the file's base name
 *   description: "..."
 *   base: bench                          # optional: take light and meshes of another scene file
 *   light: {type: directional, direction: [0.53, -0.38, 0.76]}
 *   # or {type: spot, position: [0, 7, 0], direction: [0, -1, 0], fov: 70, penumbra: 5}:
 *   # fov the full cone angle; penumbra (optional, [0, fov/2]) ignored by the hard methods
 *   meshes:
 *     - {name: ground, generator: plane, center: [0, 0, 0], size: 600, grid: 16}
 *     - {name: spider, file: /usr/share/assimp/models/OBJ/spider.obj,
 *        transform: {translate: [0, 0, 0], rotate: [0, 90, 0], scale: [0.1, 0.1, 0.1]},
 *        two_sided: false}
 *     - {name: ground, generator: plane, size: 60, receiver: true}   # a pure receiver: soft_mc's
 *                                          # layers leave it out (Curtis 3.3); default false
 *   viewpoints:
 *     - {name: side, position: [35, 50, -43], direction: [-1, -1.2, 1],
 *        up: [0, 1, 0], fov: 60, near: 20, far: 250}
 *
 * Transforms: scale, then rotate about x, y, z (degrees, in that order), then
 * translate. Model paths are relative to the scene file unless absolute.
 * A scene is named by a path (ending in .yaml or starting with / or ., relative
 * to the referring file) or by a name looked up in the scenes folder, which
 * may name a sub-folder (hard/grazing_89 is scenes/hard/grazing_89.yaml):
 * the search path of sl_scene_dirs, first hit wins.
 */
#ifndef SL_SCENEFILE_H
#define SL_SCENEFILE_H
#include <stddef.h>
#include "scene.h"
#include "sl_error.h"

/* A scene file is refused unread above 16 MiB: big geometry lives in model
 * files, and 4096 mesh entries (the schema's limit) fit in under 1 MiB; a
 * huge file would cost memory and time (the YAML parse and its line index)
 * before the entry limits apply. */
#define SL_SCENE_MAX_BYTES ((size_t)16 << 20)

/* The folders a scene name is looked up in, in order, each with where it
 * comes from: the referring file's folder (rel_dir, when given: "config
 * folder"), then each folder of $SHADOWLAB_SCENES (colon-separated, in
 * order: "SHADOWLAB_SCENES"), then the installed share folder found from the
 * binary's own place (<prefix>/share/shadowlab/scenes: "installed") or, for
 * a binary that is not installed, the source tree's scenes/ ("source
 * tree"). Returns how many (at most max). */
int sl_scene_dirs(const char *rel_dir, char (*dirs)[1024], const char **origin, int max);

/* Is path a scene file (a top-level meshes, light or base key; a config has
 * none)? Reads only a regular file (a FIFO or a device is no scene: its
 * loader then refuses it by type) and at most SL_SCENE_MAX_BYTES of it;
 * descr (if not NULL) gets its description line. */
int sl_scene_sniff(const char *path, char *descr, size_t n);

/* The last folder of that path: installed, else the source tree's. */
const char *sl_scenes_dir(void);

/* The scene files (top-level meshes, light or base) of the search path
 * without a referring file, first of a name only, sorted: name, description,
 * path, origin (as sl_scene_dirs). */
int sl_scene_list_where(char (*names)[64], char (*descr)[160], char (*paths)[1024], const char **origins,
                        int max);

/* Resolve `ref` to a readable file path. rel_dir: folder of the referring
 * file (NULL = current folder). */
enum sl_err sl_scene_resolve(const char *ref, const char *rel_dir, char *path, size_t n,
                             struct sl_diag *d);

/* A scene by name (a file in the scenes folder) or by path (scenefile.h). */
enum sl_err sl_scene_build(const char *ref, struct sl_scene *out, struct sl_diag *d);
enum sl_err sl_scene_load(const char *path, struct sl_scene *out, struct sl_diag *d);

/* Scene files in the scenes folder: names (file base names) and
 * descriptions; returns how many (at most max). */
int sl_scene_list(char (*names)[64], char (*descr)[160], int max);

#endif
