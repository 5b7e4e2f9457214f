/*
 * util.h — small shared helpers: allocation that reports failure, wall clock,
 * atomic file output (write to a temporary, rename into place), directories.
 * Nothing here knows about scenes, GL or Embree.
 */
#ifndef SL_UTIL_H
#define SL_UTIL_H
#include <stddef.h>
#include <stdio.h>
#include "sl_error.h"

double sl_now(void);                      /* monotonic seconds */
void  *sl_calloc(size_t n, size_t size);  /* NULL on failure or overflow */

/* mkdir -p; SL_E_OUTPUT with diag on failure or if not writable. */
enum sl_err sl_mkdirs(const char *path, struct sl_diag *d);

/* Atomic text/binary output: open "<path>.tmp", then commit renames it over
 * path, abort removes it. A killed run never leaves a half-written file under
 * the final name. */
struct sl_outfile { FILE *f; char path[1024]; char tmp[1040]; };
enum sl_err sl_out_open(struct sl_outfile *o, const char *path, struct sl_diag *d);
enum sl_err sl_out_commit(struct sl_outfile *o, struct sl_diag *d);
void        sl_out_abort(struct sl_outfile *o);

/* FNV-1a 64: start with SL_FNV_SEED, feed bytes. */
#define SL_FNV_SEED 1469598103934665603ull
unsigned long long sl_fnv1a(unsigned long long h, const void *p, size_t n);

/* FNV-1a 64 over a file's bytes (config hash written beside results). */
enum sl_err sl_hash_file(const char *path, unsigned long long *out, struct sl_diag *d);

#endif
