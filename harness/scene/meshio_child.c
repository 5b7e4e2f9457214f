/*
 * meshio_child.c — a model reader run in a forked child with limits, its
 * mesh handed back through a pipe (issue 15: model files are untrusted and
 * assimp is not hardened; malformed files crash it or loop forever).
 *
 * Invariants:
 * - The child does only the reader's work (assimp, our checks, the weld)
 *   and writes one result into the pipe, then _exit()s: it flushes and
 *   cleans nothing of the parent's, prints nothing (stdout and stderr go to
 *   /dev/null), writes no core file, and runs no signal handler of the
 *   parent's: a crash ends it by the signal.
 * - The child is bounded in CPU time (RLIMIT_CPU), address space (RLIMIT_AS)
 *   and wall time (the parent kills it at the deadline), all scaled by the
 *   file's size, so no file can hang or exhaust the parent. The wall
 *   deadline stops a child that is blocked; one still using CPU when it
 *   comes is only starved by a loaded machine, and gets more time (up to 8×
 *   the deadline; struct deadline).
 * - The pipe protocol is one header (magic, error id, diagnostic, stats,
 *   counts) and, on success, exactly nv*3 floats then nt*3 indices. The
 *   parent trusts none of it: the magic, the error id's range, the counts'
 *   limits, every coordinate's finiteness and every index's range are
 *   checked before `out` is filled, so a child that went wrong (or a reader
 *   with a bug) cannot hand over a broken mesh.
 * - Every way the child can end without a whole result (a signal, the CPU
 *   limit, the wall deadline, a short write) becomes one SL_E_SCENE message
 *   naming the file and the cause; the child is always reaped.
 */
#define _DEFAULT_SOURCE   /* fork, poll, setrlimit, kill */
#include "gen.h"   /* sl_mesh_free */
#include "meshio_child.h"
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#define JAIL_CPU_BASE_S   3     /* CPU seconds for any file ... */
#define JAIL_CPU_PER_MB_S 1     /* ... plus this per MiB of file */
#define JAIL_AS_BASE      (4ull << 30)  /* address space beyond the parent's ... */
#define JAIL_AS_PER_BYTE  64ull         /* ... plus this per byte of file */

struct jail_head {
    uint32_t                  magic;
    int32_t                   err;
    struct sl_diag            d;
    struct sl_mesh_load_stats st;
    uint32_t                  nv, nt;
};
#define JAIL_MAGIC 0x534c4d31u   /* "SLM1" */

static int write_all(int fd, const void *p, size_t n)
{
    const char *c = p;
    while (n) {
        ssize_t w = write(fd, c, n > (1u << 20) ? (1u << 20) : n);
        if (w < 0 && errno == EINTR)
            continue;
        if (w <= 0)
            return 0;
        c += w;
        n -= (size_t)w;
    }
    return 1;
}

static unsigned long long vm_size(void)
{
    unsigned long long pages = 0;
    FILE *f = fopen("/proc/self/statm", "r");
    if (f) {
        if (fscanf(f, "%llu", &pages) != 1)
            pages = 0;
        fclose(f);
    }
    long ps = sysconf(_SC_PAGESIZE);
    return pages * (unsigned long long)(ps > 0 ? ps : 4096);
}

static void jail_child(int fd, sl_mesh_reader_fn read, const char *path, const float xform[16],
                       unsigned cpu_s, unsigned long long as_bytes)
{
    /* A crash ends the child by its signal (what jail_verdict reports), not
     * in a handler inherited from the parent: a host's, or libFuzzer's,
     * which would write the input as its own crash (fuzz/, issue 15). */
    static const int fatal[] = {SIGSEGV, SIGBUS, SIGABRT, SIGFPE, SIGILL, SIGXCPU};
    for (size_t i = 0; i < sizeof fatal / sizeof fatal[0]; i++)
        signal(fatal[i], SIG_DFL);
    struct rlimit r = {.rlim_cur = cpu_s, .rlim_max = cpu_s + 1};
    setrlimit(RLIMIT_CPU, &r);
    r.rlim_cur = r.rlim_max = as_bytes;
    setrlimit(RLIMIT_AS, &r);
    r.rlim_cur = r.rlim_max = 0;
    setrlimit(RLIMIT_CORE, &r);
    int null = open("/dev/null", O_RDWR);
    if (null >= 0) {   /* assimp may print; only main() speaks */
        dup2(null, 1);
        dup2(null, 2);
    }
    struct sl_mesh m = {0};
    struct jail_head h;
    memset(&h, 0, sizeof h);
    h.magic = JAIL_MAGIC;
    h.err = (int32_t)read(&m, path, xform, &h.st, &h.d);
    if (!h.err) {
        h.nv = m.nv;
        h.nt = m.nt;
    }
    int ok = write_all(fd, &h, sizeof h);
    if (ok && !h.err)
        ok = write_all(fd, m.pos, (size_t)m.nv * 3 * sizeof(float)) &&
             write_all(fd, m.idx, (size_t)m.nt * 3 * sizeof(uint32_t));
    _exit(ok ? 0 : 3);
}

static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* The child's CPU time so far in clock ticks (utime + stime of
 * /proc/PID/stat), or -1 when it cannot be read. */
static long long child_ticks(pid_t pid)
{
    char path[64], buf[1024];
    snprintf(path, sizeof path, "/proc/%d/stat", (int)pid);
    FILE *f = fopen(path, "r");
    if (!f)
        return -1;
    size_t n = fread(buf, 1, sizeof buf - 1, f);
    fclose(f);
    buf[n] = 0;
    const char *p = strrchr(buf, ')');   /* the command name may hold spaces */
    unsigned long long ut, stt;
    if (!p || sscanf(p + 1, " %*c %*d %*d %*d %*d %*d %*u %*u %*u %*u %*u %llu %llu", &ut, &stt) != 2)
        return -1;
    return (long long)(ut + stt);
}

/* The wall-clock deadline of a reader. At `at`, a child that has used CPU
 * since the last look is making progress on a loaded machine (two cores
 * shared by a dozen processes give it a fifth of one), so the deadline moves
 * on by `step`, up to `cap`; RLIMIT_CPU still bounds its work. A child that
 * used none is blocked — the hang this deadline is for — and is stopped. */
struct deadline {
    double at, step, cap;
    pid_t pid;
    long long ticks;
};

static int deadline_passed(struct deadline *dl)
{
    double t = now_s();
    if (t < dl->at)
        return 0;
    long long k = child_ticks(dl->pid);
    if (k > dl->ticks && t + dl->step <= dl->cap) {
        dl->ticks = k;
        dl->at = t + dl->step;
        return 0;
    }
    return 1;
}

/* Read n bytes before the deadline: 1 done, 0 end of data, -1 timeout, -2 error. */
static int read_until(int fd, void *p, size_t n, struct deadline *dl)
{
    char *c = p;
    while (n) {
        if (deadline_passed(dl))
            return -1;
        double left = dl->at - now_s();
        struct pollfd pf = {.fd = fd, .events = POLLIN};
        int k = poll(&pf, 1, left > 0 ? (int)(left * 1000.0) + 1 : 0);
        if (k < 0 && errno == EINTR)
            continue;
        if (k < 0)
            return -2;
        if (k == 0)
            continue;
        ssize_t r = read(fd, c, n);
        if (r < 0 && errno == EINTR)
            continue;
        if (r < 0)
            return -2;
        if (r == 0)
            return 0;
        c += r;
        n -= (size_t)r;
    }
    return 1;
}

static const char *sig_name(int s)
{
    switch (s) {
    case SIGSEGV: return "SIGSEGV";
    case SIGBUS:  return "SIGBUS";
    case SIGABRT: return "SIGABRT";
    case SIGFPE:  return "SIGFPE";
    case SIGILL:  return "SIGILL";
    case SIGKILL: return "SIGKILL";
    case SIGXCPU: return "SIGXCPU";
    default:      return "signal";
    }
}

/* What the child's end says, once its data did not come back whole. */
static enum sl_err jail_verdict(int status, int timed_out, unsigned cpu_s, unsigned wall_s,
                                unsigned long long as_mb, const char *path, struct sl_diag *d)
{
    const char *pre = "cannot read the model";
    if (timed_out)
        return sl_fail(d, SL_E_SCENE, path, 0, NULL,
                       "%s: the reader was stopped after %u s (wall clock): a hang or a file "
                       "too large", pre, wall_s);
    if (WIFSIGNALED(status)) {
        int s = WTERMSIG(status);
        if (s == SIGXCPU || s == SIGKILL)
            return sl_fail(d, SL_E_SCENE, path, 0, NULL,
                           "%s: the reader was stopped after %u s of CPU (%s): a hang or a "
                           "file too large", pre, cpu_s, sig_name(s));
        return sl_fail(d, SL_E_SCENE, path, 0, NULL,
                       "%s: the reader crashed (signal %d, %s; memory limit %llu MiB)", pre, s,
                       sig_name(s), as_mb);
    }
    return sl_fail(d, SL_E_SCENE, path, 0, NULL, "%s: the reader ended without a result "
                   "(exit %d)", pre, WIFEXITED(status) ? WEXITSTATUS(status) : -1);
}

enum sl_err sl_mesh_read_in_child(sl_mesh_reader_fn read, const char *path,
                                  const float xform[16], struct sl_mesh *out,
                                  struct sl_mesh_load_stats *st, struct sl_diag *d)
{
    if (!read || !out || !path)
        return sl_fail(d, SL_E_INTERNAL, path, 0, NULL, "sl_mesh_read_in_child: NULL argument");
    struct stat sb;
    unsigned long long size = stat(path, &sb) == 0 ? (unsigned long long)sb.st_size : 0;
    unsigned cpu_s = JAIL_CPU_BASE_S + JAIL_CPU_PER_MB_S * (unsigned)(size >> 20);
    unsigned wall_s = 2 * cpu_s + 5;   /* blocked this long: stopped (struct deadline) */
    unsigned long long as = vm_size() + JAIL_AS_BASE + JAIL_AS_PER_BYTE * size;
    int fds[2];
    if (pipe(fds) != 0)
        return sl_fail(d, SL_E_INTERNAL, path, 0, NULL, "cannot read the model: pipe: %s",
                       strerror(errno));
    fflush(NULL);   /* the child must not write the parent's buffers again */
    pid_t pid = fork();
    if (pid < 0) {
        int en = errno;
        close(fds[0]);
        close(fds[1]);
        return sl_fail(d, SL_E_INTERNAL, path, 0, NULL, "cannot read the model: fork: %s",
                       strerror(en));
    }
    if (pid == 0) {
        close(fds[0]);
        jail_child(fds[1], read, path, xform, cpu_s, as);
    }
    close(fds[1]);
    double t0 = now_s();
    struct deadline deadline = {.at = t0 + wall_s, .step = wall_s, .cap = t0 + 8.0 * wall_s, .pid = pid,
                                .ticks = 0};
    struct jail_head h;
    struct sl_mesh got = {0};
    int r = read_until(fds[0], &h, sizeof h, &deadline), bad = 0;
    enum sl_err e = SL_OK;
    if (r == 1 && h.magic != JAIL_MAGIC)
        bad = 1;
    else if (r == 1 && h.err) {
        if (h.err < 0 || h.err >= SL_ERR_COUNT)
            bad = 1;
        else {
            h.d.file[sizeof h.d.file - 1] = h.d.key[sizeof h.d.key - 1] = 0;
            h.d.msg[sizeof h.d.msg - 1] = 0;
            if (d)
                *d = h.d;
            e = (enum sl_err)h.err;
        }
    } else if (r == 1) {
        if (h.nv == 0 || h.nt == 0 || h.nv > MESHIO_MAX_ELEMS || h.nt > MESHIO_MAX_ELEMS)
            bad = 1;
        else {
            got.pos = malloc((size_t)h.nv * 3 * sizeof(float));
            got.idx = malloc((size_t)h.nt * 3 * sizeof(uint32_t));
            if (!got.pos || !got.idx)
                e = sl_fail(d, SL_E_NOMEM, path, 0, NULL, "mesh of %u triangles", h.nt);
            else {
                got.nv = got.cap_v = h.nv;
                got.nt = got.cap_t = h.nt;
                r = read_until(fds[0], got.pos, (size_t)h.nv * 3 * sizeof(float), &deadline);
                if (r == 1)
                    r = read_until(fds[0], got.idx, (size_t)h.nt * 3 * sizeof(uint32_t), &deadline);
            }
        }
    }
    if (r == -1)
        kill(pid, SIGKILL);
    close(fds[0]);
    int status = 0;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR)
        ;
    if (!e && r != 1)
        e = jail_verdict(status, r == -1, cpu_s, (unsigned)(now_s() - t0 + 0.5), as >> 20, path, d);
    else if (!e && bad)
        e = sl_fail(d, SL_E_INTERNAL, path, 0, NULL, "cannot read the model: the reader "
                    "handed back a malformed result");
    /* the child's result is checked like assimp's was */
    for (size_t i = 0; !e && got.pos && i < 3 * (size_t)got.nv; i++)
        if (!isfinite(got.pos[i]))
            e = sl_fail(d, SL_E_INTERNAL, path, 0, NULL, "cannot read the model: the reader "
                        "handed back a non-finite vertex");
    for (size_t i = 0; !e && got.idx && i < 3 * (size_t)got.nt; i++)
        if (got.idx[i] >= got.nv)
            e = sl_fail(d, SL_E_INTERNAL, path, 0, NULL, "cannot read the model: the reader "
                        "handed back an index out of range");
    if (!e) {
        *out = got;   /* checked whole: handed over */
        if (st)
            *st = h.st;
    } else
        sl_mesh_free(&got);
    return e;
}
