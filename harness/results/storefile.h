/*
 * storefile.h — which file a results store is, and how it is opened: one
 * writer per file whatever the path it is reached by, readers read-only.
 *
 * A writer holds flock(LOCK_EX) on "<real path>.lock": the store's path
 * with every symbolic link, "." and ".." resolved (realpath of the file, or
 * of its folder when the file is still to be made), so a second writer that
 * reaches the same file through a link, a linked folder or a relative path
 * takes the same lock and is refused. A hard link is a second real name the
 * lock cannot see; the schema's one-cell-per-key constraint (store.c) still
 * keeps such a writer from adding a cell twice.
 *
 * Readers open the file through an SQLite URI: mode=ro, so a reader never
 * writes (not even a -wal it did not find); on read-only media (a read-only
 * mount, a folder no -shm can be made in), immutable=1, since no writer can
 * change the file there and SQLite's WAL locking would need a -shm file it
 * cannot make.
 *
 * Owns: the lock's file descriptor (the caller closes it). Does not: open
 * SQLite handles, or print.
 */
#ifndef SL_STOREFILE_H
#define SL_STOREFILE_H
#include <stddef.h>
#include "sl_error.h"

/* Take the writer's lock of the store at path (a flock on "<real path>.lock",
 * made if missing): *fd holds it, lockpath (lockpath_n bytes) gets the lock
 * file's name for sl_storefile_unlock. SL_E_IO naming the holder's pid when
 * another writer holds it. */
enum sl_err sl_storefile_lock(const char *path, int *fd, char *lockpath, size_t lockpath_n, struct sl_diag *d);
/* Release it: the lock file is removed first, while still held, then fd is
 * closed (no .lock is left behind a clean close; one left by a killed writer
 * is simply locked again by the next). */
void sl_storefile_unlock(int fd, const char *lockpath);
/* 1 when fd (a lock taken on lockpath) is on the file lockpath names now,
 * 0 when that file was removed or replaced since it was opened */
int sl_storefile_lock_current(int fd, const char *lockpath);

/* The URI a reader opens path with (SQLITE_OPEN_URI | SQLITE_OPEN_READONLY);
 * 0 on success, -1 when it does not fit in n. */
int sl_storefile_ro_uri(const char *path, char *uri, size_t n);

/* A reader's way into the store at path. On read-only media a store is
 * opened with immutable=1, which reads the .db alone: a -wal beside it
 * holding data (a writer whose last checkpoint never happened, a copy made
 * with its -wal) would be ignored, and the results in it lost without a
 * word. So when such a -wal lies beside a store on read-only media, the
 * store and its -wal are copied into a private folder made with mkdtemp
 * under $TMPDIR (or /tmp) and uri names the copy, where SQLite reads the
 * -wal as usual; tmpdir is that folder ("" when none), removed with
 * everything in it by sl_storefile_ro_release. SL_E_IO naming the store,
 * the folder and the reason when the copy cannot be made. */
struct sl_storefile_ro {
    char uri[4200];
    char tmpdir[512];
    char copy[600];   /* the copy's path ("" when none) */
    char upgraded[600];   /* an older schema's store upgraded for reading, in tmpdir ("" when none) */
};
enum sl_err sl_storefile_ro_open(const char *path, struct sl_storefile_ro *r, struct sl_diag *d);
void        sl_storefile_ro_release(struct sl_storefile_ro *r);   /* NULL-safe; idempotent */
/* A private folder for a reader's copy of the store at path (a store of an
 * older schema migrated for reading): r->tmpdir and r->copy set as above,
 * unless r already holds a copy (kept: it is private already). */
enum sl_err sl_storefile_private(struct sl_storefile_ro *r, const char *path, struct sl_diag *d);

/* fsync the file at path, then its folder (so its name is durable too).
 * SL_E_OUTPUT naming what could not be synced. */
enum sl_err sl_storefile_sync(const char *path, struct sl_diag *d);

/* Fault injection for the tests (built only with SL_FAULTS, which the
 * build sets with SL_TESTS; 0 otherwise): 1 when $SHADOWLAB_FAULT names
 * this fault ("checkpoint", "sync"). sl_storefile_fault_point counts the
 * calls made with name and kills the process with SIGKILL at the N-th one
 * when $SHADOWLAB_FAULT is "name:N" (a writer killed at a chosen moment). */
int  sl_storefile_fault(const char *name);
void sl_storefile_fault_point(const char *name);

#endif
