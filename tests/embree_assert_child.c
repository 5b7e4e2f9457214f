/*
 * embree_assert_child.c — portability::assertion_guard's program: a child
 * process breaks Embree's packet contract the way the truth pass did before
 * harness/truth/packet.h (an inactive lane left with tnear < 0, traced by
 * Embree's ray-stream emulation of rtcOccluded16 under its SSE4.2 kernels,
 * which ignores the valid mask), and Debian's assertion-enabled libembree3
 * aborts in it. The parent then exits 0, as a tool that logs a worker's
 * death and carries on would.
 *
 * ctest must fail such a test all the same: every test carries
 * FAIL_REGULAR_EXPRESSION on the assertion's message (tests/CMakeLists.txt).
 * portability::assertion_guard is WILL_FAIL, so it passes only when that
 * guard caught the child's assertion. Exit 77 (skipped) where the child did
 * not abort: an Embree built without assertions has nothing to catch.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>
#include "truth.h"

static int child(void)
{
    char why[300];
    if (sl_rtc_load(why, sizeof why)) {
        fprintf(stderr, "%s\n", why);
        return 3;
    }
    RTCDevice dev = rtcNewDevice("threads=1,isa=sse4.2");
    if (!dev)
        return 3;
    RTCScene scene = rtcNewScene(dev);
    RTCGeometry g = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_TRIANGLE);
    float *vb = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3);
    unsigned *ib = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), 1);
    if (!vb || !ib)
        return 3;
    const float v[9] = {-1, -1, 1, 1, -1, 1, 0, 1, 1};
    memcpy(vb, v, sizeof v);
    ib[0] = 0, ib[1] = 1, ib[2] = 2;
    rtcCommitGeometry(g);
    rtcAttachGeometry(scene, g);
    rtcReleaseGeometry(g);
    rtcCommitScene(scene);
    _Alignas(64) struct RTCRay16 r;
    _Alignas(64) int valid[16];
    for (int k = 0; k < 16; k++) {
        r.org_x[k] = r.org_y[k] = r.org_z[k] = 0.0f;
        r.dir_x[k] = r.dir_y[k] = 0.0f, r.dir_z[k] = 1.0f;
        r.tnear[k] = 0.0f, r.tfar[k] = 10.0f, r.time[k] = 0.0f;
        r.mask[k] = 0xffffffffu, r.id[k] = 0, r.flags[k] = 0;
        valid[k] = k == 0 ? -1 : 0;
    }
    r.tnear[1] = -1.0f;   /* inactive, but tnear <= tfar: the stream path traces it */
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    rtcOccluded16(valid, scene, &ctx, &r);
    rtcReleaseScene(scene);
    rtcReleaseDevice(dev);
    return 0;
}

int main(void)
{
    fflush(stdout);
    pid_t p = fork();
    if (p < 0)
        return 3;
    if (p == 0)
        _exit(child());
    int st = 0;
    if (waitpid(p, &st, 0) != p)
        return 3;
    if (WIFSIGNALED(st)) {
        printf("child killed by signal %d; the parent carries on and exits 0\n", WTERMSIG(st));
        return 0;
    }
    printf("child exited %d: this Embree does not assert on an inactive lane's ray\n", WEXITSTATUS(st));
    return WEXITSTATUS(st) == 0 ? 77 : 3;
}
