/*
 * rtload.h — Embree's entry points, taken from libembree3 with dlopen when
 * the first BVH is built (sl_rt_build), and called under their usual names
 * through the macros below (dlib.h). Embree and its TBB are not linked, so
 * a verb that traces nothing never loads them. Included by truth.h after
 * <embree3/rtcore.h>, whose prototypes type the pointers.
 *
 * A call to an rtc* function missing from this list fails to link (no
 * Embree on the link line): add it here. rtcInitIntersectContext is inline
 * in the header, not a library symbol.
 */
#ifndef SL_RTLOAD_H
#define SL_RTLOAD_H
#include <stddef.h>
#include <embree3/rtcore.h>

#define SL_RTC_FUNCS(X)                                                                                 \
    X(rtcAttachGeometry) X(rtcCommitGeometry) X(rtcCommitScene) X(rtcGetDeviceError)                   \
    X(rtcGetDeviceProperty) X(rtcNewDevice) X(rtcNewGeometry) X(rtcNewScene) X(rtcOccluded1)           \
    X(rtcOccluded4) X(rtcOccluded8) X(rtcOccluded16) X(rtcReleaseDevice) X(rtcReleaseGeometry)         \
    X(rtcReleaseScene)                                                                                 \
    X(rtcSetGeometryOccludedFilterFunction) X(rtcSetNewGeometryBuffer) X(rtcSetSceneBuildQuality)      \
    X(rtcSetSceneFlags)

struct sl_rtc_fns {
#define SL_RTLOAD_FIELD(f) __typeof__(f) *f;
    SL_RTC_FUNCS(SL_RTLOAD_FIELD)
#undef SL_RTLOAD_FIELD
};
extern struct sl_rtc_fns sl_rtc;

/* 0 when libembree3 is loaded (now or before); else the reason in why. */
int sl_rtc_load(char *why, size_t n);

#define rtcAttachGeometry sl_rtc.rtcAttachGeometry
#define rtcCommitGeometry sl_rtc.rtcCommitGeometry
#define rtcCommitScene sl_rtc.rtcCommitScene
#define rtcGetDeviceError sl_rtc.rtcGetDeviceError
#define rtcGetDeviceProperty sl_rtc.rtcGetDeviceProperty
#define rtcNewDevice sl_rtc.rtcNewDevice
#define rtcNewGeometry sl_rtc.rtcNewGeometry
#define rtcNewScene sl_rtc.rtcNewScene
#define rtcOccluded1 sl_rtc.rtcOccluded1
#define rtcOccluded4 sl_rtc.rtcOccluded4
#define rtcOccluded8 sl_rtc.rtcOccluded8
#define rtcOccluded16 sl_rtc.rtcOccluded16
#define rtcReleaseDevice sl_rtc.rtcReleaseDevice
#define rtcReleaseGeometry sl_rtc.rtcReleaseGeometry
#define rtcReleaseScene sl_rtc.rtcReleaseScene
#define rtcSetGeometryOccludedFilterFunction sl_rtc.rtcSetGeometryOccludedFilterFunction
#define rtcSetNewGeometryBuffer sl_rtc.rtcSetNewGeometryBuffer
#define rtcSetSceneBuildQuality sl_rtc.rtcSetSceneBuildQuality
#define rtcSetSceneFlags sl_rtc.rtcSetSceneFlags

#endif
