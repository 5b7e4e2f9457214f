/*
 * storefile.c — see storefile.h.
 *
 * Invariants:
 * - The lock's name comes from the real path of the database file, never
 *   from the text the user typed: two spellings of one file, one lock.
 * - A refused writer leaves the lock file as it found it (the holder's pid
 *   stays readable in it).
 * - A writer that closes cleanly removes the lock file, while it still holds
 *   the lock; the lock a writer takes is always on the file at the lock's
 *   path at that moment (the check after flock, below), so the removal
 *   cannot let two writers in.
 * Nothing here prints.
 */
#define _XOPEN_SOURCE 700
#include "storefile.h"
#include <errno.h>
#include <signal.h>
#include <fcntl.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <time.h>
#include <unistd.h>

/* The real path of path into out: of the file itself when it is there, else
 * of its folder with the file's name appended (a store still to be made).
 * 0 on success. */
static int real_path(const char *path, char *out, size_t n)
{
    char buf[PATH_MAX];
    if (realpath(path, buf))
        return snprintf(out, n, "%s", buf) < (int)n ? 0 : -1;
    char dir[PATH_MAX];
    if (snprintf(dir, sizeof dir, "%s", path) >= (int)sizeof dir)
        return -1;
    char *slash = strrchr(dir, '/');
    const char *base = slash ? slash + 1 : path;
    if (slash == dir)
        snprintf(dir, sizeof dir, "/");
    else if (slash)
        *slash = '\0';
    else
        snprintf(dir, sizeof dir, ".");
    if (!realpath(dir, buf))
        return -1;
    return snprintf(out, n, "%s%s%s", buf, strcmp(buf, "/") ? "/" : "", base) < (int)n ? 0 : -1;
}

int sl_storefile_lock_current(int fd, const char *lockpath)
{
    struct stat held, named;
    return fstat(fd, &held) == 0 && stat(lockpath, &named) == 0 && held.st_dev == named.st_dev &&
           held.st_ino == named.st_ino;
}

/* Removing the lock file on close is a classic race: a second writer may
 * have opened the file (by its name) just before the holder unlinked it, and
 * take its flock just after the holder closed it; it would then hold a lock
 * on a file no longer at the path, while a third writer creates a new file
 * there and locks that one: two writers at once. So after flock succeeds,
 * the lock is checked to be on the file the path names now (fstat of the
 * descriptor against stat of the path: same device and inode); when it is
 * not, the descriptor is dropped and the lock taken again on the new file.
 * The holder unlinks only while it holds the flock, so the file at the path
 * can change only between a writer's open and its flock: a few tries are
 * plenty (each one is a writer that got in and left between two calls). */
enum sl_err sl_storefile_lock(const char *path, int *fd_out, char *lockpath, size_t lockpath_n, struct sl_diag *d)
{
    *fd_out = -1;
    if (lockpath_n)
        lockpath[0] = 0;
    char real[PATH_MAX], lp[PATH_MAX + 8];
    if (real_path(path, real, sizeof real) != 0)
        return sl_fail(d, SL_E_IO, path, 0, NULL, "unable to open its folder: %s", strerror(errno));
    snprintf(lp, sizeof lp, "%s.lock", real);
    for (int attempt = 0; attempt < 100; attempt++) {
        int fd = open(lp, O_RDWR | O_CREAT | O_CLOEXEC, 0644);
        if (fd < 0)
            return sl_fail(d, SL_E_IO, path, 0, NULL, "unable to open its lock file %s: %s", lp, strerror(errno));
        if (flock(fd, LOCK_EX | LOCK_NB) != 0) {
            int en = errno;
            /* The holder writes its pid just after its flock: a writer
             * refused in between would read nothing, so the pid is read
             * again for up to ~0.2 s before the message says "unknown". */
            char buf[32] = "";
            for (int tries = 0; tries < 100 && en == EWOULDBLOCK; tries++) {
                ssize_t n = pread(fd, buf, sizeof buf - 1, 0);
                buf[n > 0 ? n : 0] = 0;
                buf[strcspn(buf, "\n")] = 0;
                if (buf[0])
                    break;
                nanosleep(&(struct timespec){.tv_nsec = 2000000}, NULL);
            }
            close(fd);
            if (en == EWOULDBLOCK)
                return sl_fail(d, SL_E_IO, path, 0, NULL,
                               "results store in use by another run (pid %s, lock %s); wait for it to "
                               "finish, then `run --resume`, or write elsewhere with --out",
                               buf[0] ? buf : "unknown", lp);
            return sl_fail(d, SL_E_IO, path, 0, NULL, "cannot lock %s: %s", lp, strerror(en));
        }
        if (!sl_storefile_lock_current(fd, lp)) {
            close(fd);   /* a file its last holder removed: lock the one at the path now */
            continue;
        }
        char pid[32];
        int k = snprintf(pid, sizeof pid, "%ld\n", (long)getpid());
        /* written before the truncation, so the file is never seen empty
         * once it held a pid */
        if (pwrite(fd, pid, (size_t)k, 0) != k || ftruncate(fd, k) != 0) {
            /* the pid only makes the message better; the lock holds without it */
        }
        if (lockpath_n)
            snprintf(lockpath, lockpath_n, "%s", lp);
        *fd_out = fd;
        return SL_OK;
    }
    return sl_fail(d, SL_E_IO, path, 0, NULL, "cannot lock %s: its file kept being replaced", lp);
}

void sl_storefile_unlock(int fd, const char *lockpath)
{
    if (fd < 0)
        return;
    /* unlinked while still held (see sl_storefile_lock), and only when the
     * path still names the file this descriptor locks */
    if (lockpath && lockpath[0] && sl_storefile_lock_current(fd, lockpath))
        unlink(lockpath);
    close(fd);   /* releases the flock */
}

/* Read-only media: the folder is on a read-only mount, or it cannot take a
 * new file (no -shm could be made) and no -wal says a writer uses it. */
static int read_only_media(const char *path)
{
    char dir[PATH_MAX], wal[PATH_MAX + 8];
    snprintf(dir, sizeof dir, "%s", path);
    char *slash = strrchr(dir, '/');
    if (slash == dir)
        dir[1] = '\0';
    else if (slash)
        *slash = '\0';
    else
        snprintf(dir, sizeof dir, ".");
    struct statvfs vs;
    if (statvfs(dir, &vs) == 0 && (vs.f_flag & ST_RDONLY))
        return 1;
    snprintf(wal, sizeof wal, "%s-wal", path);
    return access(dir, W_OK) != 0 && access(wal, F_OK) != 0;
}

int sl_storefile_ro_uri(const char *path, char *uri, size_t n)
{
    /* file: URIs take the path percent-encoded where it would be read as
     * URI syntax */
    size_t k = 0;
    int w = snprintf(uri, n, "file:");
    if (w < 0 || (size_t)w >= n)
        return -1;
    k = (size_t)w;
    for (const unsigned char *p = (const unsigned char *)path; *p; p++) {
        int esc = *p == '%' || *p == '?' || *p == '#' || *p <= ' ' || *p >= 0x7f;
        if (k + 4 >= n)
            return -1;
        if (esc)
            k += (size_t)snprintf(uri + k, n - k, "%%%02X", *p);
        else
            uri[k++] = (char)*p;
    }
    w = snprintf(uri + k, n - k, "%s", read_only_media(path) ? "?mode=ro&immutable=1" : "?mode=ro");
    return w < 0 || (size_t)w >= n - k ? -1 : 0;
}

/* ---- a -wal beside a store on read-only media ---- */

/* A private folder for a copy of the store, under $TMPDIR (else /tmp):
 * r->tmpdir, and r->copy the copy's path in it. Returns 0, or errno with the
 * folder tried in where and r->tmpdir emptied. */
static int private_dir(struct sl_storefile_ro *r, char *where, size_t n)
{
    const char *tmp = getenv("TMPDIR");
    snprintf(r->tmpdir, sizeof r->tmpdir, "%s/shadowlab-store.XXXXXX", tmp && tmp[0] ? tmp : "/tmp");
    if (!mkdtemp(r->tmpdir)) {
        int en = errno;
        snprintf(where, n, "%s", r->tmpdir);
        r->tmpdir[0] = 0;
        return en;
    }
    snprintf(r->copy, sizeof r->copy, "%s/store.db", r->tmpdir);
    return 0;
}

/* Copy the file src to dst (created, never an existing file). 0 on success,
 * else errno. */
static int copy_file(const char *src, const char *dst)
{
    int in = open(src, O_RDONLY | O_CLOEXEC);
    if (in < 0)
        return errno;
    int out = open(dst, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
    if (out < 0) {
        int en = errno;
        close(in);
        return en;
    }
    char buf[65536];
    int en = 0;
    for (;;) {
        ssize_t r = read(in, buf, sizeof buf);
        if (r < 0 && errno == EINTR)
            continue;
        if (r < 0)
            en = errno;
        if (r <= 0)
            break;
        for (ssize_t w = 0; w < r && !en;) {
            ssize_t k = write(out, buf + w, (size_t)(r - w));
            if (k < 0 && errno != EINTR)
                en = errno;
            else if (k > 0)
                w += k;
        }
        if (en)
            break;
    }
    close(in);
    if (close(out) != 0 && !en)
        en = errno;
    return en;
}

enum sl_err sl_storefile_ro_open(const char *path, struct sl_storefile_ro *r, struct sl_diag *d)
{
    memset(r, 0, sizeof *r);
    char wal[PATH_MAX + 8];
    snprintf(wal, sizeof wal, "%s-wal", path);
    struct stat ws;
    /* immutable=1 only on read-only media (read_only_media): there, a -wal
     * holding frames is data the .db alone lacks */
    int copy = stat(wal, &ws) == 0 && ws.st_size > 0 && read_only_media(path);
    if (!copy)
        return sl_storefile_ro_uri(path, r->uri, sizeof r->uri) == 0
                   ? SL_OK : sl_fail(d, SL_E_IO, path, 0, NULL, "path too long");
    char where[sizeof r->tmpdir];
    int en = private_dir(r, where, sizeof where);
    if (en)
        return sl_fail(d, SL_E_IO, path, 0, NULL, "a -wal of %lld bytes lies beside this store on read-only media "
                       "(its last checkpoint never happened); reading it needs a private copy, but %s cannot be "
                       "made: %s (set TMPDIR to a writable folder)", (long long)ws.st_size, where, strerror(en));
    char cwal[sizeof r->copy + 8];
    snprintf(cwal, sizeof cwal, "%s-wal", r->copy);
    en = copy_file(path, r->copy);
    if (!en)
        en = copy_file(wal, cwal);
    if (en) {
        snprintf(where, sizeof where, "%s", r->tmpdir);
        sl_storefile_ro_release(r);
        return sl_fail(d, SL_E_IO, path, 0, NULL, "a -wal of %lld bytes lies beside this store on read-only media "
                       "(its last checkpoint never happened); copying store and -wal into %s to read them failed: %s "
                       "(free space there, or set TMPDIR to a folder with room)", (long long)ws.st_size, where,
                       strerror(en));
    }
    /* the copy is on writable storage: mode=ro, SQLite reads its -wal */
    if (sl_storefile_ro_uri(r->copy, r->uri, sizeof r->uri) != 0) {
        sl_storefile_ro_release(r);
        return sl_fail(d, SL_E_IO, path, 0, NULL, "path too long");
    }
    return SL_OK;
}

enum sl_err sl_storefile_private(struct sl_storefile_ro *r, const char *path, struct sl_diag *d)
{
    if (r->tmpdir[0])
        return SL_OK;   /* a -wal copy's folder: private already */
    char where[sizeof r->tmpdir];
    int en = private_dir(r, where, sizeof where);
    if (en)
        return sl_fail(d, SL_E_IO, path, 0, NULL, "reading this store needs a private copy, but %s cannot be made: "
                       "%s (set TMPDIR to a writable folder)", where, strerror(en));
    return SL_OK;
}

void sl_storefile_ro_release(struct sl_storefile_ro *r)
{
    if (!r || !r->tmpdir[0])
        return;
    /* only the files this module and SQLite make there: the copy, its -wal, -shm */
    static const char *const tails[] = {"", "-wal", "-shm", "-journal"};
    for (size_t i = 0; i < sizeof tails / sizeof tails[0]; i++) {
        char f[sizeof r->copy + 16];
        snprintf(f, sizeof f, "%s/store.db%s", r->tmpdir, tails[i]);
        unlink(f);
    }
    if (r->upgraded[0])
        unlink(r->upgraded);
    rmdir(r->tmpdir);
    r->tmpdir[0] = 0;
    r->upgraded[0] = 0;
    r->copy[0] = 0;
}

/* ---- durability ---- */

static int fsync_path(const char *path, int dir)
{
    int fd = open(path, (dir ? O_RDONLY | O_DIRECTORY : O_RDONLY) | O_CLOEXEC);
    if (fd < 0)
        return errno;
    int en = fsync(fd) == 0 ? 0 : errno;
    close(fd);
    return en;
}

enum sl_err sl_storefile_sync(const char *path, struct sl_diag *d)
{
    char dir[PATH_MAX];
    snprintf(dir, sizeof dir, "%s", path);
    char *slash = strrchr(dir, '/');
    if (slash == dir)
        dir[1] = '\0';
    else if (slash)
        *slash = '\0';
    else
        snprintf(dir, sizeof dir, ".");
    int en = sl_storefile_fault("sync") ? EIO : fsync_path(path, 0);
    if (en)
        return sl_fail(d, SL_E_OUTPUT, path, 0, NULL, "cannot sync the store to disk: %s", strerror(en));
    if ((en = fsync_path(dir, 1)) != 0)
        return sl_fail(d, SL_E_OUTPUT, path, 0, NULL, "cannot sync its folder %s to disk: %s", dir, strerror(en));
    return SL_OK;
}

/* ---- fault injection (tests) ---- */

#ifdef SL_FAULTS
int sl_storefile_fault(const char *name)
{
    const char *f = getenv("SHADOWLAB_FAULT");
    return f && strcmp(f, name) == 0;
}

void sl_storefile_fault_point(const char *name)
{
    static int calls;   /* one process, one fault: the count of the named point */
    const char *f = getenv("SHADOWLAB_FAULT");
    size_t n = strlen(name);
    if (!f || strncmp(f, name, n) != 0 || f[n] != ':')
        return;
    if (++calls == atoi(f + n + 1))
        raise(SIGKILL);
}
#else
int sl_storefile_fault(const char *name)
{
    (void)name;
    return 0;
}

void sl_storefile_fault_point(const char *name)
{
    (void)name;
}
#endif
