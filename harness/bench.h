/*
 * bench.h — `shadowlab bench`: the truth pass against a plain Embree
 * rtcOccluded16 loop over the very same rays, and the stage times of one run
 * of a config. A benchmark, not a test: it prints figures, it asserts nothing.
 */
#ifndef SL_BENCH_H
#define SL_BENCH_H
#include <stdio.h>
#include "config.h"

struct sl_bench_opts {
    const char *config;    /* NULL = configs/default.yaml */
    int reps;              /* timed repetitions (after one warm-up); 0 = 7 */
    FILE *out;
};

enum sl_err sl_bench(const struct sl_bench_opts *o, struct sl_diag *d);

#endif
