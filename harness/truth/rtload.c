/*
 * rtload.c — dlopen of libembree3 on the first BVH (rtload.h). rtload.h is
 * included first without its macros' effect on the names below: the
 * symbols are looked up by the strings the list makes.
 */
#include "rtload.h"
#include "dlib.h"

struct sl_rtc_fns sl_rtc;

#define SL_RTLOAD_NAME(f) #f,

int sl_rtc_load(char *why, size_t n)
{
    static const char *const names[] = {"libembree3.so.3", "libembree3.so", NULL};
    static const char *const syms[] = {SL_RTC_FUNCS(SL_RTLOAD_NAME)};
    static int loaded;
    _Static_assert(sizeof sl_rtc == sizeof syms / sizeof syms[0] * sizeof(void *), "one field per name");
    return sl_dl_table(&loaded, names, syms, (int)(sizeof syms / sizeof syms[0]), &sl_rtc, why, n);
}
