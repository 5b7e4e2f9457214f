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

#endif
