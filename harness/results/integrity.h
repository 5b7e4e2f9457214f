/*
 * integrity.h — is a results store intact: SQLite's own page check and each
 * cell's digest of what it stores.
 *
 * SQLite's quick_check finds damage to its pages (b-trees, free lists), not
 * a flipped bit inside a value: the page stays well formed and the number is
 * simply another number. So every cell row carries `digest`, a CRC-32
 * (zlib) over a canonical serialisation of every column of the cell row but
 * the digest itself, then of every column of each of its figure rows in
 * (region, figure) order. A value is its SQLite type and its bytes: an
 * integer and a REAL as their 8 bytes (little-endian, the REAL's IEEE
 * bits), a text as its length and bytes, a NULL as its type alone; each row
 * starts with a tag and its column count. Columns are taken as SQLite lists
 * them (SELECT *), so a column added to the schema is covered without a
 * change here. The digest is written in the cell's own transaction
 * (store.c, merge.c) and recomputed by `verify` and by every reader before
 * it trusts a cell (sl_store_query).
 *
 * CRC-32 finds every 1-bit error and every burst up to 32 bits; it is a
 * check against damage (disks, copies, a hand edit), not against someone
 * who means to forge a cell (they can recompute it).
 *
 * Works on any SQLite handle and schema name ("main", or an ATTACHed
 * shard), so the store and the merge share it. Owns: nothing past the
 * statements of a struct sl_integ. Does not: print, or open files.
 */
#ifndef SL_INTEGRITY_H
#define SL_INTEGRITY_H
#include <stdint.h>
#include "sl_error.h"
#include "store.h"

struct sqlite3;
struct sl_integ;

/* Statements that digest cells of db's `schema`; path names the file in errors. */
enum sl_err sl_integ_open(struct sqlite3 *db, const char *schema, const char *path, struct sl_integ **out,
                          struct sl_diag *d);
void        sl_integ_close(struct sl_integ *g);   /* NULL-safe */
/* The digest of cell cell_id as stored now; SQLITE_OK or SQLite's error code. */
int sl_integ_digest(struct sl_integ *g, int64_t cell_id, uint32_t *out);

/* PRAGMA quick_check on db's `schema`: SL_E_IO naming path with its first
 * finding when it is not "ok"; `doing` ends the message ("refusing to write
 * into it"). */
enum sl_err sl_integ_quick_check(struct sqlite3 *db, const char *schema, const char *path, const char *doing,
                                 struct sl_diag *d);

/* Every cell of db's `schema` against its digest (after quick_check): the
 * damaged ones into r (r->damaged malloc'ed: sl_store_verify_free). SL_OK
 * when the digests could be computed, damaged cells or not. */
enum sl_err sl_integ_verify(struct sqlite3 *db, const char *schema, const char *path, struct sl_store_verify *r,
                            struct sl_diag *d);

#endif
