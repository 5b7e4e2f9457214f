/*
 * bench_row.c — see bench_row.h: the rows, the timing helpers and the
 * writers every stage of the bench shares. Calls no stage.
 */
#define _GNU_SOURCE   /* wait4 */
#include "bench_row.h"
#include <errno.h>
#include <fcntl.h>
#include <spawn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>
#include "util.h"

/* ---- rows and timing ------------------------------------------------------ */

double sl_bench_cpu_s(void)
{
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    return (double)(ru.ru_utime.tv_sec + ru.ru_stime.tv_sec) +
           1e-6 * (double)(ru.ru_utime.tv_usec + ru.ru_stime.tv_usec);
}

static int cmp_d(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

double sl_bench_median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, cmp_d);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

struct sl_bench_row *sl_bench_add_row(struct sl_bench_result *res, const char *stage, const char *unit,
                                      double value, double plain, double target, enum sl_bench_cmp cmp)
{
    if (res->nrows >= (int)(sizeof res->rows / sizeof res->rows[0]))
        return NULL;
    struct sl_bench_row *r = &res->rows[res->nrows++];
    memset(r, 0, sizeof *r);
    snprintf(r->stage, sizeof r->stage, "%s", stage);
    snprintf(r->unit, sizeof r->unit, "%s", unit);
    r->value = value;
    r->plain = plain;
    r->target = target;
    r->cmp = cmp;
    if (plain > 0) {
        /* rates: ours over plain (higher is better); times: ours over plain */
        r->ratio = value / plain;
    }
    double x = plain > 0 ? r->ratio : value;
    r->pass = cmp == SL_BENCH_AT_LEAST ? x >= target : x <= target;
    return r;
}


/* Other work on a shared machine skews every time: say how busy it was. */
void sl_bench_loadavg(char *buf, size_t n)
{
    snprintf(buf, n, "unknown");
    FILE *f = fopen("/proc/loadavg", "r");
    if (!f)
        return;
    double a, b, c;
    if (fscanf(f, "%lf %lf %lf", &a, &b, &c) == 3)
        snprintf(buf, n, "%.2f %.2f %.2f", a, b, c);
    fclose(f);
}

int sl_bench_spawn_self(char *const *argv, char *const *envp, struct rusage *ru)
{
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&fa, 2, "/dev/null", O_WRONLY, 0);
    pid_t pid;
    int rc = posix_spawn(&pid, "/proc/self/exe", &fa, NULL, argv, envp);
    posix_spawn_file_actions_destroy(&fa);
    if (rc)
        return -1;
    int st;
    struct rusage own;
    while (wait4(pid, &st, 0, ru ? ru : &own) < 0)
        if (errno != EINTR)
            return -1;
    return WIFEXITED(st) ? WEXITSTATUS(st) : 128 + (WIFSIGNALED(st) ? WTERMSIG(st) : 0);
}

/* ---- output ---------------------------------------------------------------- */

static void target_text(const struct sl_bench_row *r, char *buf, size_t n)
{
    const char *op = r->cmp == SL_BENCH_AT_LEAST ? "≥" : "≤";
    if (r->plain > 0)
        snprintf(buf, n, "ratio %s %g", op, r->target);
    else
        snprintf(buf, n, "%s %g %s", op, r->target, r->unit);
}

void sl_bench_write_summary(const struct sl_bench_result *res, FILE *out)
{
    fprintf(out, "## Summary\n\n");
    fprintf(out, "| stage | measurement | unit | value | plain | ratio | target | result |\n");
    fprintf(out, "|---|---|---|---:|---:|---:|---|---|\n");
    for (int i = 0; i < res->nrows; i++) {
        const struct sl_bench_row *r = &res->rows[i];
        char tgt[48], plain[32] = "", ratio[32] = "";
        target_text(r, tgt, sizeof tgt);
        if (r->plain > 0) {
            snprintf(plain, sizeof plain, "%.2f", r->plain);
            snprintf(ratio, sizeof ratio, "%.2f", r->ratio);
        }
        fprintf(out, "| %s | %s | %s | %.2f | %s | %s | %s | %s |\n", r->stage, r->name, r->unit, r->value, plain,
                ratio, tgt, r->pass ? "PASS" : "**MISS**");
    }
    fputc('\n', out);
}

enum sl_err sl_bench_write_csv(const struct sl_bench_result *res, const char *path, struct sl_diag *d)
{
    FILE *f = fopen(path, "w");
    if (!f)
        return sl_fail(d, SL_E_IO, path, 0, NULL, "cannot write the CSV");
    fprintf(f, "git_sha,stage,name,unit,value,plain,ratio,target,cmp,result,gs_prims,fragments,plain_fragments,note\n");
    for (int i = 0; i < res->nrows; i++) {
        const struct sl_bench_row *r = &res->rows[i];
        fprintf(f, "%s,%s,\"%s\",%s,%.6g,%.6g,%.6g,%g,%s,%s,%llu,%llu,%llu,\"%s\"\n", sl_git_sha(), r->stage,
                r->name, r->unit, r->value, r->plain, r->ratio, r->target,
                r->cmp == SL_BENCH_AT_LEAST ? "at_least" : "at_most", r->pass ? "PASS" : "MISS",
                (unsigned long long)r->gs_prims, (unsigned long long)r->fragments,
                (unsigned long long)r->plain_fragments, r->note);
    }
    return fclose(f) == 0 ? SL_OK : sl_fail(d, SL_E_IO, path, 0, NULL, "cannot write the CSV");
}


/* ---- --markdown FILE: the header ----------------------------------------- */

/* The command line that made this process, as a shell would read it back. */
static void command_line(char *buf, size_t n)
{
    snprintf(buf, n, "(unknown)");
    FILE *f = fopen("/proc/self/cmdline", "rb");
    if (!f)
        return;
    char raw[2048];
    size_t len = fread(raw, 1, sizeof raw - 1, f);
    fclose(f);
    raw[len] = '\0';
    size_t o = 0;
    buf[0] = '\0';
    for (size_t i = 0; i < len && o + 4 < n;) {
        const char *arg = raw + i;
        size_t al = strlen(arg);
        int quote = al == 0 || strpbrk(arg, " \t'\"$`\\*?;&|<>()[]{}") != NULL;
        if (o)
            buf[o++] = ' ';
        if (quote && o + 1 < n)
            buf[o++] = '\'';
        for (size_t k = 0; k < al && o + 6 < n; k++) {
            if (arg[k] == '\'') {
                memcpy(buf + o, "'\\''", 4);
                o += 4;
            } else {
                buf[o++] = arg[k];
            }
        }
        if (quote && o + 1 < n)
            buf[o++] = '\'';
        buf[o] = '\0';
        i += al + 1;
    }
}

enum sl_err sl_bench_write_markdown(const char *path, const struct sl_provenance *p, const char *stages,
                                    const char *load0, const char *load1, const char *body, size_t len,
                                    struct sl_diag *d)
{
    char tmp[4096];
    if (snprintf(tmp, sizeof tmp, "%s.tmp-XXXXXX", path) >= (int)sizeof tmp)
        return sl_fail(d, SL_E_OUTPUT, path, 0, NULL, "path too long");
    int fd = mkstemp(tmp);
    if (fd < 0)
        return sl_fail(d, SL_E_OUTPUT, path, 0, NULL, "cannot write the Markdown: %s", strerror(errno));
    FILE *f = fdopen(fd, "w");
    if (!f) {
        close(fd);
        unlink(tmp);
        return sl_fail(d, SL_E_OUTPUT, path, 0, NULL, "cannot write the Markdown: %s", strerror(errno));
    }
    fchmod(fd, 0644);
    char cmd[2048];
    command_line(cmd, sizeof cmd);
    fprintf(f, "# Performance\n\n");
    fprintf(f, "Written by `shadowlab bench --markdown`; regenerate it, on a quiet machine, with the command "
               "below rather than editing it. What each stage measures and its target: `shadowlab help bench` "
               "and the man page; a missed target is a MISS, not an error. Figures measured on a lent GPU "
               "machine (not by this bench): [performance-gpu.md](performance-gpu.md). What the default "
               "timing costs a study (`--only timing`, run apart: it runs the Moderno study six times): "
               "[performance-timing.md](performance-timing.md).\n\n");
    fprintf(f, "| | |\n|---|---|\n");
    fprintf(f, "| command | `%s` |\n", cmd);
    fprintf(f, "| stages | %s |\n", stages);
    fprintf(f, "| git SHA | `%s` |\n", p->git_sha);
    fprintf(f, "| time (UTC) | %s |\n", p->time_utc);
    fprintf(f, "| machine | %s |\n", p->host);
    fprintf(f, "| CPU | %s (%s), %d threads |\n", p->cpu, p->isa, p->threads);
    fprintf(f, "| GL renderer | %s, %s |\n", p->gl_renderer, p->gl_version);
    fprintf(f, "| GL backend | %s |\n", p->gl_backend[0] ? p->gl_backend : "(unknown)");
    fprintf(f, "| Embree | %s |\n", p->embree);
    fprintf(f, "| load average (1, 5, 15 min) | %s at the start, %s at the end |\n\n", load0, load1);
    fwrite(body, 1, len, f);
    int bad = ferror(f) != 0;
    bad |= fflush(f) != 0;
    bad |= fsync(fd) != 0;
    bad |= fclose(f) != 0;
    if (bad || rename(tmp, path) != 0) {
        int err = errno;
        unlink(tmp);
        return sl_fail(d, SL_E_OUTPUT, path, 0, NULL, "cannot write the Markdown: %s", strerror(err));
    }
    return SL_OK;
}
