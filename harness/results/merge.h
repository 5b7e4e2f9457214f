/*
 * merge.h — shards into one results store (`shadowlab merge`).
 *
 * A sweep split across tasks (`run --cells A:B`, one store per task, so no
 * SQLite file is ever written by two hosts) comes back together here: each
 * shard is attached in turn (SQLite allows 10 attached databases, one at a
 * time is enough), its runs and cells are copied in one transaction, and
 * the overlay of every copied cell is gathered under the merged store's
 * folder as <study>/overlays/<file> (the layout `run` writes: the store
 * beside results/<name>/), with the exr/ files of <study> beside them.
 *
 * A cell is the same cell when its config hash and key (scene, viewpoint,
 * viewport, map size, label) are, and the store's schema holds each such
 * key once (UNIQUE): a cell already in the merged store is not copied again
 * (counted as a duplicate), so merging twice adds nothing and the first
 * copy of a key wins (two shards of one sweep holding one key computed it
 * twice, from the same config). A run row is copied with the first of its
 * cells copied, and keeps its provenance (git SHA, host, ISA, GL renderer).
 *
 * Trust: a shard is checked whole before anything is written: a regular
 * file (not a folder or a device), a results store of this version, SQLite's
 * quick_check, every cell's digest (integrity.h). Each copied cell gets its
 * own digest in the merged store, in the shard's transaction. Shards are
 * attached read-only (storefile.h), so a shard on read-only media merges.
 *
 * Owns: its own SQLite connection to the merged store, opened after
 * sl_store_open made (or checked) the schema and while that handle holds the
 * store's lock. Does not: know the sweep (the driver checks for missing
 * cells against the config the runs carry), or print.
 */
#ifndef SL_MERGE_H
#define SL_MERGE_H
#include "store.h"

struct sl_merge;

struct sl_merge_shard {
    char config_hash[24];      /* the one config hash the shard holds */
    char study[64];
    int  runs;                 /* run rows copied (0 when all were there) */
    int  cells;                /* cell rows copied */
    int  duplicates;           /* cells whose key the merged store already held */
    int  overlays;             /* overlay files gathered */
    int  overlays_missing;     /* overlays a copied cell names but the shard's folder lacks */
    int  exr;                  /* EXR files gathered */
    /* where its cells were computed: "git SHA, GL 'renderer', ISA isa" of
     * its runs that hold cells, and a second such when they differ ("" if not) */
    char provenance[256], other[256];
};

/* sl_shards_merge's flags (submit.h). */
enum {
    SL_MERGE_APPEND = 1,       /* sl_merge_open's append: run --jobs' fresh cells replace stored ones */
    SL_MERGE_ALLOW_MIXED = 2,  /* shards of other git SHAs, GL renderers or ISAs merge (merge --allow-mixed) */
};

/* Open (or create) the merged store at out_path; its folder must exist.
 * append: a shard's cell replaces the stored one of its key (fresh results
 * of `run --jobs`, which supersede older ones as a second `run`'s would). */
enum sl_err sl_merge_open(const char *out_path, int append, struct sl_merge **out, struct sl_diag *d);
/* The same into a store the caller holds open for writing (its lock held,
 * its schema made: `run --jobs` holds its store for the whole run); held
 * stays the caller's. */
enum sl_err sl_merge_open_held(struct sl_store *held, const char *out_path, int append, struct sl_merge **out,
                               struct sl_diag *d);
/* Cells of the merged store (by cell_id) that a shard's cell of their key
 * replaces though append is off: `run --jobs --resume` recomputes a stored
 * cell whose overlay or EXR file is lost, and its fresh copy supersedes the
 * stored one. ids is copied; call before sl_merge_add. */
enum sl_err sl_merge_replace(struct sl_merge *m, const int64_t *ids, int n, struct sl_diag *d);
/* Check a shard before anything is written: a file, a results store of
 * this version, intact (quick_check, every digest), whose runs are of one
 * config; its hash, study and provenance into info (config_hash "" when it
 * holds no run). SL_E_USAGE for a folder or device, SL_E_IO naming the
 * shard (and its first damaged cell) otherwise. */
enum sl_err sl_merge_probe(const char *shard, struct sl_merge_shard *info, struct sl_diag *d);
/* Copy one shard. Refused (SL_E_USAGE naming both) when it holds another
 * config hash than the first shard added, or more than one; SL_E_IO when it
 * is not a results store of this version. */
enum sl_err sl_merge_add(struct sl_merge *m, const char *shard, struct sl_merge_shard *info, struct sl_diag *d);
/* The config hash every shard holds and the filled-in config text of the
 * first run copied (NULL before any shard); valid until sl_merge_close. */
const char *sl_merge_config_hash(const struct sl_merge *m);
const char *sl_merge_config_text(const struct sl_merge *m);
const char *sl_merge_config_path(const struct sl_merge *m);   /* as that run was given it */
/* The merge's last step when it opened the store itself (sl_merge_open):
 * its connection closed, the store sealed (sl_store_seal); with a held
 * store only the connection is closed (the holder seals). Nothing may be
 * added after it; sl_merge_close still frees m. */
enum sl_err sl_merge_seal(struct sl_merge *m, struct sl_diag *d);
void        sl_merge_close(struct sl_merge *m);   /* NULL-safe */

#endif
