/*
 * util.h — small shared helpers: allocation that reports failure, wall clock,
 * atomic file output (write to a temporary, rename into place), directories.
 * Nothing here knows about scenes, GL or Embree.
 */
#ifndef SL_UTIL_H
#define SL_UTIL_H
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include "sl_error.h"

double sl_now(void);                      /* monotonic seconds */
int    sl_cpu_count(void);
/* <prefix>/share/shadowlab/SUB beside an installed binary (<prefix>/bin/shadowlab),
 * found from the binary's own place so the tree can move; "" (and 0) when that
 * folder does not exist: an installed binary never reads its source tree. */
int    sl_share_dir(const char *sub, char *dir, size_t n);                 /* cores this process may run on (its affinity mask), >= 1 */
void  *sl_calloc(size_t n, size_t size);  /* NULL on failure or overflow */

/* The folder a path names its file in ("a/b/c.db" -> "a/b"; "c.db" -> ".")
 * into out; a path longer than out is cut. */
void sl_path_dir(const char *path, char *out, size_t n);

/* A size as a message says it: in the largest unit of bytes, KiB, MiB, GiB
 * that it is at least one of, with one decimal where that unit does not
 * divide it ("512 bytes", "64 KiB", "1.5 MiB"): a limit of 64 KiB never
 * reads "0 MiB". Returns out. */
const char *sl_size_text(unsigned long long bytes, char *out, size_t n);

/* The "a, b, c" of a message's "(known: a, b, c)": appends name to the list
 * in buf (n bytes, "" to start), after ", " unless buf is empty; a list
 * longer than buf is cut. One helper, so every such list reads alike. */
void sl_known_add(char *buf, size_t n, const char *name);

/* vsnprintf into a string of its own length (free it); NULL on failure. */
char *sl_vformat(const char *fmt, va_list ap);

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

/* Input files by type: a path read as a file (a config, a scene, a model,
 * a baseline) must be a regular file. A FIFO would block the open or the
 * read, a device (/dev/zero) never ends, a folder has no text: these are
 * refused by their type, from stat(), before any open or read.
 * sl_file_type_bad: NULL when path is a regular file or does not exist (the
 * open then gives the system's reason), else what it is ("a FIFO", ...).
 * sl_open_regular: the same check, then open(O_RDONLY | O_NONBLOCK) (so a
 * path swapped for a FIFO after the stat cannot block) and fstat() again on
 * what was opened; on success *fd is open on a regular file of *size bytes.
 * Errors: SL_E_IO naming path. */
const char *sl_file_type_bad(const char *path);
enum sl_err sl_open_regular(const char *path, int *fd, long long *size, struct sl_diag *d);

/* FNV-1a 64 over a file's bytes (config hash written beside results). */
/* s as one CSV field (RFC 4180): quoted when it holds a comma, a quote or a
 * line break, its quotes doubled. Shared by the run's tables and the pivots. */
void sl_csv_field(FILE *f, const char *s);

enum sl_err sl_hash_file(const char *path, unsigned long long *out, struct sl_diag *d);

/* {median, min, max} (out[0], out[1], out[2]: SL_MED, SL_MIN, SL_MAX of
 * cellcols.h) of n >= 1 times (sorted in place), NaN ones (a GPU timer
 * that failed, glctx.h) left out; all NaN: NaN (not measured). */
void sl_med_min_max(double *t, int n, double out[3]);

#endif
