/*
 * store_int.h — the results store's SQLite connection, for the files of
 * harness/results that read through the same handle as store.c: the runs
 * listing (runs.c) and `verify` (integrity.c). Nothing outside
 * harness/results includes it; everyone else goes through store.h.
 */
#ifndef SL_STORE_INT_H
#define SL_STORE_INT_H
#include "store.h"

struct sqlite3;
/* s's connection, and its database path into *path (for messages). */
struct sqlite3 *sl_store_handle(struct sl_store *s, const char **path);

#endif
