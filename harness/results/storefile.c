/*
 * storefile.c — see storefile.h.
 *
 * Invariants:
 * - The lock's name comes from the real path of the database file, never
 *   from the text the user typed: two spellings of one file, one lock.
 * - A refused writer leaves the lock file as it found it (the holder's pid
 *   stays readable in it).
 * Nothing here prints.
 */
#define _XOPEN_SOURCE 700
#include "storefile.h"
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
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

enum sl_err sl_storefile_lock(const char *path, int *fd_out, struct sl_diag *d)
{
    *fd_out = -1;
    char real[PATH_MAX], lp[PATH_MAX + 8];
    if (real_path(path, real, sizeof real) != 0)
        return sl_fail(d, SL_E_IO, path, 0, NULL, "unable to open its folder: %s", strerror(errno));
    snprintf(lp, sizeof lp, "%s.lock", real);
    int fd = open(lp, O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0)
        return sl_fail(d, SL_E_IO, path, 0, NULL, "unable to open its lock file %s: %s", lp, strerror(errno));
    if (flock(fd, LOCK_EX | LOCK_NB) != 0) {
        int en = errno;
        char buf[32] = "";
        ssize_t n = pread(fd, buf, sizeof buf - 1, 0);
        buf[n > 0 ? n : 0] = 0;
        buf[strcspn(buf, "\n")] = 0;
        close(fd);
        if (en == EWOULDBLOCK)
            return sl_fail(d, SL_E_IO, path, 0, NULL,
                           "results store in use by another run (pid %s, lock %s); wait for it to "
                           "finish, then `run --resume`, or write elsewhere with --out",
                           buf[0] ? buf : "unknown", lp);
        return sl_fail(d, SL_E_IO, path, 0, NULL, "cannot lock %s: %s", lp, strerror(en));
    }
    char pid[32];
    int k = snprintf(pid, sizeof pid, "%ld\n", (long)getpid());
    if (ftruncate(fd, 0) != 0 || pwrite(fd, pid, (size_t)k, 0) != k) {
        /* the pid only makes the message better; the lock holds without it */
    }
    *fd_out = fd;
    return SL_OK;
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
