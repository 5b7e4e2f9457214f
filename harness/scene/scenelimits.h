/*
 * scenelimits.h — how many viewpoints, paths and path frames a scene file
 * may hold, apart from the scene (scene.h), so a config sizes its lists
 * without the scene's types.
 *
 * Owns: nothing.
 */
#ifndef SL_SCENELIMITS_H
#define SL_SCENELIMITS_H

#define SL_MAX_VIEWPOINTS 16
/* Paths (pathfile.h): at most SL_MAX_PATHS per scene file, their frames
 * together at most SL_MAX_FRAMES; each frame is a viewpoint held after the
 * named ones (vp[nvp .. nvp + nframes)), named "<path>.<frame>" (orbit.007). */
#define SL_MAX_PATHS 8
#define SL_MAX_FRAMES 480
#define SL_MAX_VIEWS (SL_MAX_VIEWPOINTS + SL_MAX_FRAMES)

#endif
