/*
 * util.c — clock, allocation, hashing, folders, atomic files.
 * Invariant: nothing here prints; callers get an id and an sl_diag.
 */
#define _GNU_SOURCE   /* sched_getaffinity, CPU_COUNT */
#include "util.h"
#include <sched.h>
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

int sl_cpu_count(void)
{
    /* the cores this process may run on (taskset, a Slurm or container
     * allocation), not the machine's: 64 threads on the 4 cores a job was
     * given would only take turns */
    cpu_set_t set;
    CPU_ZERO(&set);
    if (sched_getaffinity(0, sizeof set, &set) == 0 && CPU_COUNT(&set) > 0)
        return CPU_COUNT(&set);
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    return n > 0 ? (int)(n > 1 << 20 ? 1 << 20 : n) : 1;
}

int sl_share_dir(const char *sub, char *dir, size_t n)
{
    dir[0] = '\0';
    char exe[900];
    ssize_t len = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (len <= 0)
        return 0;
    exe[len] = '\0';
    for (int up = 0; up < 2; up++) {   /* <prefix>/bin/shadowlab -> <prefix> */
        char *slash = strrchr(exe, '/');
        if (!slash)
            return 0;
        *slash = '\0';
    }
    snprintf(dir, n, "%s/share/shadowlab/%s", exe, sub);
    struct stat st;
    if (stat(dir, &st) != 0 || !S_ISDIR(st.st_mode))
        dir[0] = '\0';
    return dir[0] != '\0';
}

double sl_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

void *sl_calloc(size_t n, size_t size)
{
    if (size && n > SIZE_MAX / size)
        return NULL;
    return calloc(n ? n : 1, size ? size : 1);
}

enum sl_err sl_mkdirs(const char *path, struct sl_diag *d)
{
    char buf[1024];
    if (snprintf(buf, sizeof buf, "%s", path) >= (int)sizeof buf)
        return sl_fail(d, SL_E_OUTPUT, path, 0, NULL, "path too long");
    for (char *p = buf + 1; ; p++) {
        if (*p == '/' || *p == '\0') {
            char c = *p;
            *p = '\0';
            if (mkdir(buf, 0777) != 0 && errno != EEXIST)
                return sl_fail(d, SL_E_OUTPUT, path, 0, NULL, "cannot create directory %s: %s",
                               buf, strerror(errno));
            *p = c;
            if (c == '\0')
                break;
        }
    }
    struct stat st;
    if (stat(buf, &st) != 0 || !S_ISDIR(st.st_mode))
        return sl_fail(d, SL_E_OUTPUT, path, 0, NULL, "not a directory");
    if (access(buf, W_OK | X_OK) != 0)
        return sl_fail(d, SL_E_OUTPUT, path, 0, NULL, "directory not writable: %s", strerror(errno));
    return SL_OK;
}

enum sl_err sl_out_open(struct sl_outfile *o, const char *path, struct sl_diag *d)
{
    memset(o, 0, sizeof *o);
    snprintf(o->path, sizeof o->path, "%s", path);
    snprintf(o->tmp, sizeof o->tmp, "%s.tmp", path);
    o->f = fopen(o->tmp, "wb");
    if (!o->f)
        return sl_fail(d, SL_E_OUTPUT, path, 0, NULL, "cannot write: %s", strerror(errno));
    return SL_OK;
}

enum sl_err sl_out_commit(struct sl_outfile *o, struct sl_diag *d)
{
    int bad = ferror(o->f);
    if (fclose(o->f) != 0)
        bad = 1;
    o->f = NULL;
    if (bad || rename(o->tmp, o->path) != 0) {
        remove(o->tmp);
        return sl_fail(d, SL_E_OUTPUT, o->path, 0, NULL, "write failed: %s", strerror(errno));
    }
    return SL_OK;
}

void sl_out_abort(struct sl_outfile *o)
{
    if (o->f) {
        fclose(o->f);
        o->f = NULL;
        remove(o->tmp);
    }
}

unsigned long long sl_fnv1a(unsigned long long h, const void *p, size_t n)
{
    const unsigned char *b = p;
    for (size_t i = 0; i < n; i++) {
        h ^= b[i];
        h *= 1099511628211ull;
    }
    return h;
}

static const char *type_name(mode_t m)
{
    return S_ISREG(m) ? NULL : S_ISDIR(m) ? "a folder" : S_ISFIFO(m) ? "a FIFO" : S_ISCHR(m) ? "a character device"
         : S_ISBLK(m) ? "a block device" : S_ISSOCK(m) ? "a socket" : "not a regular file";
}

const char *sl_file_type_bad(const char *path)
{
    struct stat st;
    return stat(path, &st) != 0 ? NULL : type_name(st.st_mode);
}

enum sl_err sl_open_regular(const char *path, int *fd, long long *size, struct sl_diag *d)
{
    *fd = -1;
    const char *bad = sl_file_type_bad(path);
    if (bad)
        return sl_fail(d, SL_E_IO, path, 0, NULL, "cannot read: %s, not a regular file", bad);
    int f = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (f < 0)
        return sl_fail(d, SL_E_IO, path, 0, NULL, "cannot read: %s", strerror(errno));
    struct stat st;
    if (fstat(f, &st) != 0 || (bad = type_name(st.st_mode)) != NULL) {
        int err = errno;
        close(f);
        return sl_fail(d, SL_E_IO, path, 0, NULL, "cannot read: %s%s", bad ? bad : strerror(err),
                       bad ? ", not a regular file" : "");
    }
    *fd = f;
    if (size)
        *size = (long long)st.st_size;
    return SL_OK;
}

enum sl_err sl_hash_file(const char *path, unsigned long long *out, struct sl_diag *d)
{
    int fd;
    enum sl_err e = sl_open_regular(path, &fd, NULL, d);
    if (e)
        return e;
    uint64_t h = 1469598103934665603ull;
    unsigned char buf[65536];
    ssize_t n;
    while ((n = read(fd, buf, sizeof buf)) > 0)
        for (ssize_t i = 0; i < n; i++) {
            h ^= (uint64_t)buf[i];
            h *= 1099511628211ull;
        }
    int err = n < 0 ? errno : 0;
    close(fd);
    if (err)
        return sl_fail(d, SL_E_IO, path, 0, NULL, "cannot read: %s", strerror(err));
    *out = h;
    return SL_OK;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

void sl_med_min_max(double *t, int n, double out[3])
{
    int k = 0;
    for (int i = 0; i < n; i++)
        if (!isnan(t[i]))
            t[k++] = t[i];
    if ((n = k) == 0) {
        out[0] = out[1] = out[2] = NAN;
        return;
    }
    qsort(t, (size_t)n, sizeof t[0], cmp_double);
    out[0] = n % 2 ? t[n / 2] : 0.5 * (t[n / 2 - 1] + t[n / 2]);
    out[1] = t[0];
    out[2] = t[n - 1];
}

void sl_path_dir(const char *path, char *out, size_t n)
{
    snprintf(out, n, "%s", path);
    char *slash = strrchr(out, '/');
    if (slash)
        *slash = '\0';
    else
        snprintf(out, n, ".");
}

const char *sl_size_text(unsigned long long bytes, char *out, size_t n)
{
    static const char *const unit[] = {"bytes", "KiB", "MiB", "GiB"};
    int u = 0;
    while (u < 3 && bytes >= 1ull << (10 * (u + 1)))
        u++;
    unsigned long long whole = bytes >> (10 * u), rest = bytes & ((1ull << (10 * u)) - 1);
    if (u == 0 || rest == 0)
        snprintf(out, n, "%llu %s", whole, unit[u]);
    else
        snprintf(out, n, "%.1f %s", (double)bytes / (double)(1ull << (10 * u)), unit[u]);
    return out;
}

void sl_known_add(char *buf, size_t n, const char *name)
{
    size_t len = strlen(buf);
    snprintf(buf + len, n - len, "%s%s", len ? ", " : "", name);
}

char *sl_vformat(const char *fmt, va_list ap)
{
    va_list aq;
    va_copy(aq, ap);
    int len = vsnprintf(NULL, 0, fmt, aq);
    va_end(aq);
    if (len < 0)
        return NULL;
    char *s = malloc((size_t)len + 1);
    if (s)
        vsnprintf(s, (size_t)len + 1, fmt, ap);
    return s;
}

void sl_csv_field(FILE *f, const char *s)
{
    if (!strpbrk(s, ",\"\r\n")) {
        fputs(s, f);
        return;
    }
    fputc('"', f);
    for (; *s; s++) {
        if (*s == '"')
            fputc('"', f);
        fputc(*s, f);
    }
    fputc('"', f);
}
