/*
 * plots.c — the report's figures, drawn by gnuplot from data computed here:
 * the chain's steps per scene (Moderno 2011 Figures 31/32) and wrong and
 * undecided pixels against cost with the Pareto front (see report.h).
 *
 * Invariants:
 * - Each plot is a kept pair, NAME.dat and NAME.gp, in the staging folder's
 *   plots/; gnuplot runs on NAME.gp there (system(), stdin /dev/null) and
 *   draws NAME.svg, and NAME.pdf where it has pdfcairo; its output goes to a
 *   scratch log, so nothing of it reaches our stdout/stderr; a failed plot
 *   names the log's first error line. The pair redraws the plot without
 *   shadowlab.
 * - Every number in a plot is also printed in a table beside it, so the
 *   Markdown page and a reader without SVG see the same data.
 * - Strings reach gnuplot only through gp_quote/gp_datum: no label or path
 *   can end a string or inject a command.
 * - Shell words (the gnuplot path, the folder) are single-quoted (sh_quote).
 */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>
#include "report_int.h"
#include "util.h"

/* ---- Pareto and points (public, unit-tested) ---- */

int sl_report_pareto(const double *x, const double *y, int n, unsigned char *front)
{
    int count = 0;
    for (int i = 0; i < n; i++) {
        int on = !isnan(x[i]) && !isnan(y[i]);
        for (int j = 0; j < n && on; j++) {
            if (j == i || isnan(x[j]) || isnan(y[j]))
                continue;
            if (x[j] <= x[i] && y[j] <= y[i] && (x[j] < x[i] || y[j] < y[i]))
                on = 0;
        }
        front[i] = (unsigned char)on;
        count += on;
    }
    return count;
}

enum sl_err sl_report_points(const struct sl_cell_record *cells, int ncells, struct sl_report_point **out, int *n,
                             struct sl_diag *d)
{
    *out = NULL;
    *n = 0;
    if (ncells <= 0)
        return SL_OK;
    struct sl_report_point *p = sl_calloc((size_t)ncells, sizeof *p);
    double *sum_w = sl_calloc((size_t)ncells, 2 * sizeof *sum_w);   /* wrong %, then uncertain % */
    int *nw = sl_calloc((size_t)ncells, sizeof *nw);
    if (!p || !sum_w || !nw) {
        free(p);
        free(sum_w);
        free(nw);
        return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "plot points");
    }
    int np = 0;
    /* labels in order of first appearance, then map sizes ascending */
    for (int i = 0; i < ncells; i++) {
        const struct sl_cell_record *c = &cells[i];
        int k = 0;
        while (k < np && !(p[k].map_size == c->map_size && strcmp(p[k].label, c->label) == 0))
            k++;
        if (k == np) {
            int at = np;
            int first = -1, last = -1;
            for (int j = 0; j < np; j++)
                if (strcmp(p[j].label, c->label) == 0) {
                    if (first < 0)
                        first = j;
                    last = j;
                }
            if (first >= 0) {
                at = last + 1;
                while (at > first && p[at - 1].map_size > c->map_size)
                    at--;
            }
            memmove(&p[at + 1], &p[at], (size_t)(np - at) * sizeof *p);
            memmove(&sum_w[at + 1], &sum_w[at], (size_t)(np - at) * sizeof *sum_w);
            memmove(&sum_w[ncells + at + 1], &sum_w[ncells + at], (size_t)(np - at) * sizeof *sum_w);
            memmove(&nw[at + 1], &nw[at], (size_t)(np - at) * sizeof *nw);
            memset(&p[at], 0, sizeof *p);
            sum_w[at] = sum_w[ncells + at] = 0.0;
            nw[at] = 0;
            snprintf(p[at].label, sizeof p[at].label, "%s", c->label);
            snprintf(p[at].method, sizeof p[at].method, "%s", c->method);
            snprintf(p[at].display, sizeof p[at].display, "%s", c->display[0] ? c->display : c->label);
            p[at].map_size = c->map_size;
            np++;
            k = at;
        }
        struct sl_report_point *q = &p[k];
        q->ncells++;
        /* the step, and every other stage (map pass, post, readback: cellcols.h) as
         * "layers", so a package's own map pass counts as NSM's layer does */
        q->ms_step += c->ms_method;
        q->ms_layers += sl_report_cell_ms(c, 0) - c->ms_method;
        /* with one run min = max = median */
        q->ms_min += sl_report_cell_ms(c, 1);
        q->ms_max += sl_report_cell_ms(c, 2);
        q->reps = q->ncells == 1 || c->runs < q->reps ? c->runs : q->reps;
        int r = sl_report_region(c, 0);
        double px = r >= 0 ? (double)c->fig.r[r].n[SL_FIG_pixels] : 0.0;
        if (px > 0.0) {
            sum_w[k] += 100.0 * (double)c->fig.r[r].n[SL_FIG_wrong] / px;
            sum_w[ncells + k] += 100.0 * (double)c->fig.r[r].n[SL_FIG_uncertain] / px;
            nw[k]++;
            q->rays_per_px += (double)c->rays / px;
        }
    }
    double *x = sl_calloc((size_t)np, sizeof *x), *y = sl_calloc((size_t)np, sizeof *y);
    unsigned char *f = sl_calloc((size_t)np, 1);
    if (!x || !y || !f) {
        free(p);
        free(sum_w);
        free(nw);
        free(x);
        free(y);
        free(f);
        return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "plot points");
    }
    for (int k = 0; k < np; k++) {
        p[k].ms_layers /= p[k].ncells;
        p[k].ms_step /= p[k].ncells;
        /* a method's cost is its own layers and its step: NSM's map counts, as does raytrace's rays */
        p[k].ms = p[k].ms_layers + p[k].ms_step;
        p[k].ms_min /= p[k].ncells;
        p[k].ms_max /= p[k].ncells;
        p[k].wrong_pct = nw[k] ? sum_w[k] / nw[k] : NAN;
        p[k].uncertain_pct = nw[k] ? sum_w[ncells + k] / nw[k] : NAN;
        p[k].rays_per_px = nw[k] ? p[k].rays_per_px / nw[k] : NAN;
    }
    for (int k = 0; k < np; k++) {
        x[k] = p[k].ms > 0.0 ? p[k].ms : NAN;   /* no time stored: not a point of the time front */
        y[k] = p[k].wrong_pct + p[k].uncertain_pct;
    }
    sl_report_pareto(x, y, np, f);
    for (int k = 0; k < np; k++) {
        p[k].front_ms = f[k];
        x[k] = p[k].rays_per_px;
    }
    sl_report_pareto(x, y, np, f);
    for (int k = 0; k < np; k++)
        p[k].front_rays = f[k];
    free(sum_w);
    free(nw);
    free(x);
    free(y);
    free(f);
    *out = p;
    *n = np;
    return SL_OK;
}

/* ---- gnuplot ---- */

enum sl_err sl_report_gnuplot_find(const char *want, char *path, size_t n, struct sl_diag *d)
{
    if (!want || !want[0])
        want = "gnuplot";
    if (strchr(want, '/')) {
        if (access(want, X_OK) == 0) {
            snprintf(path, n, "%s", want);
            return SL_OK;
        }
    } else {
        const char *env = getenv("PATH");
        char dirs[4096];
        snprintf(dirs, sizeof dirs, "%s", env ? env : "/usr/bin:/bin");
        char *save = NULL;
        for (char *dir = strtok_r(dirs, ":", &save); dir; dir = strtok_r(NULL, ":", &save)) {
            char cand[4200];
            struct stat st;
            snprintf(cand, sizeof cand, "%s/%s", dir[0] ? dir : ".", want);
            if (stat(cand, &st) == 0 && S_ISREG(st.st_mode) && access(cand, X_OK) == 0) {
                snprintf(path, n, "%s", cand);
                return SL_OK;
            }
        }
    }
    return sl_fail(d, SL_E_USAGE, NULL, 0, "gnuplot",
                   "gnuplot is not installed (no '%s' in PATH); the report draws its plots with it: install "
                   "it (Debian: apt-get install gnuplot-nox)", want);
}

/* A gnuplot single-quoted string: '' stands for ' */
static void gp_quote(FILE *f, const char *s)
{
    fputc('\'', f);
    for (; s && *s; s++) {
        if (*s == '\'')
            fputc('\'', f);
        if (*s != '\n' && *s != '\r')
            fputc(*s, f);
    }
    fputc('\'', f);
}

/* a datablock string field: double quotes, no quote, backslash or line break inside */
static void gp_datum(FILE *f, const char *s)
{
    fputc('"', f);
    for (; s && *s; s++)
        fputc((*s == '"' || *s == '\\' || *s == '\n' || *s == '\r') ? '_' : *s, f);
    fputc('"', f);
}

/* A POSIX shell single-quoted word */
static void sh_quote(char *buf, size_t n, const char *s)
{
    size_t k = 0;
    if (k + 1 < n)
        buf[k++] = '\'';
    for (; *s && k + 5 < n; s++) {
        if (*s == '\'') {
            memcpy(buf + k, "'\\''", 4);
            k += 4;
        } else {
            buf[k++] = *s;
        }
    }
    if (k + 1 < n)
        buf[k++] = '\'';
    buf[k] = '\0';
}

static int run_sh(const char *cmd)
{
    fflush(NULL);
    int status = system(cmd);
    return status != -1 && WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

enum sl_err sl_report_open_script(FILE **m, char **body, size_t *blen, FILE **dm, char **data, size_t *dlen,
                                  const char *what, struct sl_diag *d)
{
    *m = open_memstream(body, blen);
    *dm = open_memstream(data, dlen);
    if (*m && *dm)
        return SL_OK;
    if (*m)
        fclose(*m);
    if (*dm)
        fclose(*dm);
    free(*body);
    free(*data);
    return sl_fail(d, SL_E_NOMEM, NULL, 0, what, "plot script");
}

enum sl_err sl_report_close_script(FILE *m, FILE *dm, char **body, char **data, int bad, const char *what,
                                   struct sl_diag *d)
{
    bad |= ferror(m) | ferror(dm);
    bad |= fclose(m) != 0;
    bad |= fclose(dm) != 0;
    if (!bad && *body && *data)
        return SL_OK;
    free(*body);
    free(*data);
    *body = *data = NULL;
    return sl_fail(d, SL_E_NOMEM, NULL, 0, what, "plot script");
}

static enum sl_err write_text(struct sl_report_doc *doc, const char *rel, const char *text, struct sl_diag *d)
{
    char path[1400];
    enum sl_err e = sl_report_out_path(doc->out, rel, 1, path, sizeof path, d);
    if (e)
        return e;
    FILE *f = fopen(path, "w");
    if (!f)
        return sl_fail(d, SL_E_OUTPUT, path, 0, NULL, "cannot write: %s", strerror(errno));
    fputs(text, f);
    int bad = ferror(f);
    if (fclose(f) != 0 || bad)
        return sl_fail(d, SL_E_OUTPUT, path, 0, NULL, "write failed");
    return SL_OK;
}

/* A plot is kept as plots/NAME.dat (its numbers) and plots/NAME.gp (the
 * script, which reads NAME.dat from its own folder), drawn from them as
 * NAME.svg for the page and, where gnuplot has pdfcairo, NAME.pdf for
 * LaTeX: `cd plots && gnuplot NAME.gp` (SVG) or `gnuplot -e "out='pdf'"
 * NAME.gp` redraws it, so a plot can be restyled without shadowlab. `body`
 * refers to the data as DATA. */
/* an SVG plot's font (px) for a canvas w px wide: 8.5 pt when printed
 * (gp_run) */
int sl_report_svg_font_px(int w)
{
    double px = 8.5 / 0.75 * (w > 703 ? w / 703.0 : 1.0);
    int f = (int)ceil(px);
    return f < 11 ? 11 : f;
}
static int svg_font_px(int w) { return sl_report_svg_font_px(w); }

static enum sl_err gp_run(struct sl_report_doc *doc, const char *gnuplot, const char *name, int w, int h,
                          const char *data, const char *body, struct sl_diag *d)
{
    char rel[4][300], path[4][1400], logrel[300], log[1400];
    static const char *const ext[4] = {"dat", "gp", "svg", "pdf"};
    for (int k = 0; k < 4; k++)
        snprintf(rel[k], sizeof rel[k], "plots/%s.%s", name, ext[k]);
    char qexe[4400], cmd[9000];
    sh_quote(qexe, sizeof qexe, gnuplot);
    if (doc->gp_pdf == 0) {
        snprintf(cmd, sizeof cmd, "%s -e 'set terminal pdfcairo' </dev/null >/dev/null 2>&1", qexe);
        doc->gp_pdf = run_sh(cmd) == 0 ? 1 : -1;
    }
    char *script = NULL;
    size_t slen = 0;
    FILE *m = open_memstream(&script, &slen);
    if (!m)
        return sl_fail(d, SL_E_NOMEM, NULL, 0, name, "plot script");
    fprintf(m, "# shadowlab plot: cd to this folder, then `gnuplot %s.gp` (SVG) or\n"
               "# `gnuplot -e \"out='pdf'\" %s.gp` (PDF, needs the pdfcairo terminal); numbers in %s.dat\n"
               "if (!exists(\"out\")) out = 'svg'\n"
               "if (out eq 'pdf') {\n"
               "  set terminal pdfcairo size %.2fcm,%.2fcm noenhanced font 'sans,9'\n"
               "  set output '%s.pdf'\n"
               "} else {\n"
               "  set terminal svg size %d,%d dynamic noenhanced font 'sans,%d' background '#ffffff'\n"
               "  set output '%s.svg'\n"
               "}\n"
               "set encoding utf8\nDATA = '%s.dat'\n",
            /* text at least 8 pt printed (issue 47). PDF: 12 cm, about the
             * line width of report.tex's article (12.2 cm), so 9 pt stays
             * about 9 pt. SVG: the page prints on A4 within 12 mm margins,
             * 186 mm = 703 px at 96 px an inch, so a plot wider than that is
             * shrunk by 703 / w; its font (px, 0.75 pt each) is as large as
             * keeps 8.5 pt after that, and never under 11 px on screen */
            name, name, name, 12.0, 12.0 * h / w, name, w, h, svg_font_px(w), name, name);
    fputs(body, m);
    fputs("\nunset output\n", m);
    int bad = ferror(m);
    fclose(m);
    if (bad || !script) {
        free(script);
        return sl_fail(d, SL_E_NOMEM, NULL, 0, name, "plot script");
    }
    enum sl_err e = write_text(doc, rel[0], data, d);
    if (!e)
        e = write_text(doc, rel[1], script, d);
    free(script);
    snprintf(logrel, sizeof logrel, "plots/%s.log", name);
    for (int k = 2; k < 4 && !e; k++)
        if (k == 2 || doc->gp_pdf > 0)
            e = sl_report_out_path(doc->out, rel[k], 1, path[k], sizeof path[k], d);
    if (!e)
        e = sl_report_out_path(doc->out, logrel, 0, log, sizeof log, d);
    if (e)
        return e;
    /* the folder of the staged files: log is <stage>/plots/NAME.log */
    char dir[1400], qdir[2900], qlog[2900], qgp[700];
    snprintf(dir, sizeof dir, "%s", log);
    *strrchr(dir, '/') = '\0';
    sh_quote(qdir, sizeof qdir, dir);
    sh_quote(qlog, sizeof qlog, log);
    char gpname[320];
    snprintf(gpname, sizeof gpname, "%s.gp", name);
    sh_quote(qgp, sizeof qgp, gpname);
    for (int k = 2; k < 4; k++) {
        if (k == 3 && doc->gp_pdf <= 0)
            break;
        snprintf(cmd, sizeof cmd, "(cd %s && %s -e \"out='%s'\" %s </dev/null) >>%s 2>&1", qdir, qexe, ext[k],
                 qgp, qlog);
        int status = run_sh(cmd);
        struct stat st;
        if (status != 0 || stat(path[k], &st) != 0 || st.st_size == 0) {
            char first[300] = "";
            FILE *lf = fopen(log, "r");
            if (lf) {
                char line[300];
                while (fgets(line, sizeof line, lf))
                    if (strstr(line, "rror") || !first[0]) {
                        snprintf(first, sizeof first, "%s", line);
                        if (strstr(line, "rror"))
                            break;
                    }
                fclose(lf);
            }
            first[strcspn(first, "\r\n")] = '\0';
            return sl_fail(d, SL_E_IO, gnuplot, 0, rel[2], "gnuplot failed on this plot (status %d): %s", status,
                           first[0] ? first : "no message");
        }
    }
    return SL_OK;
}

/* The plot on the page (SVG) and in the LaTeX document (PDF, where drawn). */
static void plot_show(struct sl_report_doc *doc, const char *name, const char *caption)
{
    char rel[300];
    snprintf(rel, sizeof rel, "plots/%s.svg", name);
    sl_report_doc_image(doc, rel, caption);
    snprintf(rel, sizeof rel, "plots/%s.pdf", name);
    if (sl_report_out_has(doc->out, rel))
        sl_report_doc_tex_figure(doc, rel, caption);
    char gp[300], dat[300];
    snprintf(gp, sizeof gp, "plots/%s.gp", name);
    snprintf(dat, sizeof dat, "plots/%s.dat", name);
    const char *r[2] = {gp, dat}, *t[2] = {"gnuplot script", "its data"};
    sl_report_doc_links(doc, "Redraw or restyle:", r, t, 2);
}

/* ---- Moderno Figures 31/32: the chain's steps per scene ---- */

enum { ST_HINT_OK, ST_HINT_BAD, ST_CONFIRM, ST_CONFIRM_ADJ, ST_CORRECT, ST_TRACED, ST_LEFT, ST_N };
static const struct { const char *name, *color; } steps[ST_N] = {
    [ST_HINT_OK] = {"hinted (right)", "#4a90d9"},
    [ST_HINT_BAD] = {"hinted (wrong)", "#d62728"},
    [ST_CONFIRM] = {"confirmed (neighbours)", "#1b7f3b"},
    [ST_CONFIRM_ADJ] = {"confirmed (adjacency)", "#ff8c00"},
    [ST_CORRECT] = {"corrected", "#8fd18f"},
    [ST_TRACED] = {"traced", "#8e44ad"},
    [ST_LEFT] = {"left (map or fallback)", "#f2d13c"},
};

/* shares (% of PFL) of the chain's steps, summed over the scene's views */
static int chain_shares(const struct sl_report_study *s, const char *scene, const char *label, int map, int region,
                        double share[ST_N], uint64_t *pfl_out)
{
    uint64_t n[SL_FIG_COUNT];
    memset(n, 0, sizeof n);
    int found = 0;
    for (int i = 0; i < s->n; i++) {
        const struct sl_cell_record *c = &s->cells[i];
        if (c->map_size != map || strcmp(c->scene, scene) || strcmp(c->label, label))
            continue;
        int r = sl_report_region(c, region);
        if (r < 0)
            continue;
        for (int k = 0; k < SL_FIG_COUNT; k++)
            n[k] += c->fig.r[r].n[k];
        found = 1;
    }
    if (!found || n[SL_FIG_pfl] == 0)
        return 0;
    double pfl = (double)n[SL_FIG_pfl];
    double v[ST_N];
    v[ST_HINT_BAD] = (double)n[SL_FIG_hinted_wrong];
    v[ST_HINT_OK] = (double)n[SL_FIG_hinted] - v[ST_HINT_BAD];
    v[ST_CONFIRM_ADJ] = (double)n[SL_FIG_confirmed_adj];
    v[ST_CONFIRM] = (double)n[SL_FIG_confirmed] - v[ST_CONFIRM_ADJ];
    v[ST_CORRECT] = (double)n[SL_FIG_corrected];
    v[ST_TRACED] = (double)n[SL_FIG_traced];
    double used = 0.0;
    for (int k = 0; k < ST_LEFT; k++)
        used += v[k];
    v[ST_LEFT] = pfl > used ? pfl - used : 0.0;
    for (int k = 0; k < ST_N; k++)
        share[k] = 100.0 * v[k] / pfl;
    *pfl_out = n[SL_FIG_pfl];
    return 1;
}

enum sl_err sl_report_plot_chain(struct sl_report_doc *doc, const struct sl_report_study *s, const char *gnuplot,
                                 struct sl_diag *d)
{
    int chains[SL_REPORT_MAXKEYS], nchains = 0;
    for (int l = 0; l < s->nlabels; l++)
        if (strcmp(s->methods[l], "chain") == 0)
            chains[nchains++] = l;
    if (nchains == 0)
        return SL_OK;   /* report.c asks only when a chain label ran */
    sl_report_doc_para(doc,
                       "Share of the region's PFL pixels each step of the chain decides (Moderno 2011 Figures "
                       "31/32), per chain variant, map size and region, pooled over the scene's viewpoints and "
                       "viewports: hinted by texel coherence (right or wrong), shadow confirmed by a neighbour "
                       "texel's or an adjacent triangle's hit, lit corrected to shadow, traced, and left to the "
                       "map's verdict or the fallback.");
    enum sl_err e = SL_OK;
    for (int sc = 0; sc < s->nscenes && !e; sc++) {
        const char *scene = s->scenes[sc];
        char *body = NULL, *data = NULL;
        size_t blen = 0, dlen = 0;
        FILE *m, *dm;
        if ((e = sl_report_open_script(&m, &body, &blen, &dm, &data, &dlen, scene, d)))
            return e;
        char id[160], slug[64];
        sl_tab_slug(scene, slug, sizeof slug);
        snprintf(id, sizeof id, "%s-chain-%s", s->slug, slug);
        struct sl_tab t;
        sl_tab_init(&t, id, 3 + ST_N, 3, "%s / %s: pixels decided by each step of the chain, %% of PFL",
                           s->name, scene);
        sl_tab_head(&t, 0, "method");
        sl_tab_head(&t, 1, "map");
        sl_tab_head(&t, 2, "region (PFL)");
        for (int k = 0; k < ST_N; k++)
            sl_tab_head(&t, 3 + k, "%s", steps[k].name);
        fprintf(dm, "# %s / %s: %% of PFL per step:", s->name, scene);
        for (int k = 0; k < ST_N; k++)
            fprintf(dm, " %s;", steps[k].name);
        fputc('\n', dm);
        int bars = 0;
        for (int q = 0; q < nchains; q++)
            for (int k = 0; k < s->nmaps; k++)
                for (int r = 0; r < s->nregions; r++) {
                    double share[ST_N];
                    uint64_t pfl = 0;
                    if (!chain_shares(s, scene, s->labels[chains[q]], s->maps[k], s->regions[r], share, &pfl))
                        continue;
                    char rn[16], name[128];
                    sl_report_region_name(s->regions[r], rn, sizeof rn);
                    snprintf(name, sizeof name, "%s %d² %s", s->labels[chains[q]], s->maps[k], rn);
                    gp_datum(dm, name);
                    for (int j = 0; j < ST_N; j++)
                        fprintf(dm, " %.4f", share[j]);
                    fputc('\n', dm);
                    sl_tab_row(&t, r == 0);
                    sl_tab_cell(&t, 0, "%s", s->labels[chains[q]]);
                    sl_tab_cell(&t, 1, "%d²", s->maps[k]);
                    sl_tab_cell(&t, 2, "%s (%llu)", rn, (unsigned long long)pfl);
                    for (int j = 0; j < ST_N; j++)
                        sl_tab_cell(&t, 3 + j, "%.2f", share[j]);
                    bars++;
                }
        fputs("set style data histograms\nset style histogram rowstacked\n"
              "set style fill solid 1.0 border rgb '#444444'\nset boxwidth 0.8 relative\n"
              "set yrange [0:100]\nset ylabel 'share of the region''s PFL pixels (%)'\n"
              "set key outside right top\nset xtics rotate by -40 scale 0\nset grid ytics\n"
              "set border 3\nset tics nomirror\nset title ", m);
        char title[200];
        snprintf(title, sizeof title, "%s / %s: the chain's steps (Moderno 2011 Figures 31/32)", s->name, scene);
        gp_quote(m, title);
        fputs("\nplot ", m);
        for (int j = 0; j < ST_N; j++) {
            fprintf(m, "%s using %d%s title ", j ? ", ''" : "DATA", j + 2, j ? "" : ":xtic(1)");
            gp_quote(m, steps[j].name);
            fprintf(m, " lc rgb '%s'", steps[j].color);
        }
        fputc('\n', m);
        if ((e = sl_report_close_script(m, dm, &body, &data, 0, scene, d))) {
            sl_tab_free(&t);
            return e;
        }
        if (bars > 0) {
            int w = 420 + 34 * bars;
            e = gp_run(doc, gnuplot, id, w > 1400 ? 1400 : w, 520, data, body, d);
            if (!e) {
                plot_show(doc, id, title);
                e = sl_report_doc_table(doc, &t, d);
            }
        }
        free(body);
        free(data);
        sl_tab_free(&t);
    }
    return e;
}

/* ---- accuracy against cost ---- */

/* Okabe-Ito's colour-blind-safe palette (its yellow swapped for grey: too
 * faint on white) and twelve markers, filled first: label k gets colour
 * k % 8 and marker (k + k / 24) % 12, so 96 labels (more than a study may
 * hold) differ in colour, marker or both, and the first eight in both. pt 6 (the open circle) is left out: it is
 * the Pareto front's ring. Every plot of the report takes its styles here. */
static const char *const okabe[8] = {"#E69F00", "#56B4E9", "#009E73", "#999999",
                                     "#0072B2", "#D55E00", "#CC79A7", "#000000"};
static const int markers[12] = {7, 5, 9, 11, 13, 15, 4, 8, 10, 12, 1, 2};

void sl_report_style(int k, const char **colour, int *pt)
{
    if (k < 0)
        k = 0;
    *colour = okabe[k % 8];
    *pt = markers[(k + k / 24) % 12];
}

int sl_report_axis(FILE *m, const char *axis, const double *v, int n, int from_zero)
{
    if (strcmp(axis, "x") != 0 && strcmp(axis, "y") != 0)
        return -1;
    double lo = INFINITY, hi = -INFINITY, pos = INFINITY;
    int zeros = 0;
    for (int i = 0; i < n; i++) {
        if (!isfinite(v[i]))
            continue;
        zeros |= v[i] == 0.0;
        lo = fmin(lo, v[i]);
        hi = fmax(hi, v[i]);
        if (v[i] > 0.0)
            pos = fmin(pos, v[i]);
    }
    if (!(hi > 0.0))
        return -1;   /* nothing but zeros (or nothing): the caller drops the panel */
    char up[8];
    snprintf(up, sizeof up, "%c", axis[0] == 'x' ? 'X' : 'Y');
    /* tics start afresh: another panel's may be set */
    fprintf(m, "unset %stics\nset %stics nomirror\nset format %s '%%g'\n", axis, axis, axis);
    if (lo >= 0.0 && hi / pos > 100.0) {
        /* more than two decades: log, a factor 2 of room above; a zero (an
         * exact method's wrong pixels) cannot sit on a log axis, so it is
         * drawn at a tick labelled 0 half a decade under the lowest decade */
        double zero = pow(10.0, floor(log10(pos)) - 0.5);
        fprintf(m, "set logscale %s\nset %srange [%.6g:%.6g]\n", axis, axis, zeros ? zero / 1.8 : pos / 2.0,
                hi * 2.0);
        if (zeros)
            fprintf(m, "set %stics add ('0' %.6g)\n", axis, zero);
        fprintf(m, "%sZERO = %.6g\n%sZERO_OF(c) = column(c) == 0 ? %sZERO : column(c)\n", up, zero, up, up);
        return 1;
    }
    fprintf(m, "unset logscale %s\n%sZERO = 0\n%sZERO_OF(c) = column(c) == 0 ? %sZERO : column(c)\n", axis, up, up,
            up);
    double a, b;
    if (lo >= 0.0 && (from_zero || zeros)) {
        a = 0.0;
        b = hi * 1.06;
        if (lo < 0.03 * hi) {
            /* points at (or next to) 0: the axis a little below, so they do not
             * sit on its line, and tics from 0 up, so no negative value is labelled */
            a = -0.03 * b;
            /* about six tics up a y axis, four along an x axis: the plots'
             * panels are narrow (the key beside them), and labels such as
             * 0.012 at 8.5 pt printed run into each other at six */
            double raw = b / (axis[0] == 'x' ? 4.0 : 6.0), mag = pow(10.0, floor(log10(raw))), r = raw / mag;
            double step = (r < 1.5 ? 1.0 : r < 3.5 ? 2.0 : r < 7.5 ? 5.0 : 10.0) * mag;
            fprintf(m, "set %stics 0, %.6g\n", axis, step);
        }
    } else {
        double pad = hi > lo ? 0.06 * (hi - lo) : 0.1 * fabs(hi);
        a = lo - pad;
        b = hi + pad;
        if (lo >= 0.0 && a < 0.0)
            a = 0.0;   /* never below zero for a count or a time */
    }
    fprintf(m, "set %srange [%.6g:%.6g]\n", axis, a, b);
    return 0;
}

/* Whether point k of an accuracy plot opens its method's block: its cost
 * (rays, or a time above 0) and wrong % known, and a label other than the
 * block before it's (*prev, updated). The data, the panels and the key walk
 * the points alike, so a method's block, style and key entry agree. */
static int accuracy_opens(const struct sl_report_point *p, int k, int which, const char **prev)
{
    double x = which ? p[k].rays_per_px : p[k].ms;
    if (isnan(x) || isnan(p[k].wrong_pct) || (which == 0 && !(x > 0.0)))
        return 0;
    if (*prev && strcmp(*prev, p[k].label) == 0)
        return 0;
    *prev = p[k].label;
    return 1;
}

/* Two panels over one cost axis (which: 0 method time, 1 rays per pixel):
 * wrong pixels above, undecided pixels below, one colour and marker per
 * method label with its map sizes joined smallest to largest, min-max bars
 * of the repetitions on time, and the Pareto front of (cost, wrong +
 * uncertain) ringed in both. Returns SL_OK without a plot when no point has
 * that cost (say so on the page). */
static enum sl_err accuracy_plot(struct sl_report_doc *doc, const struct sl_report_study *s, const char *gnuplot,
                                 const struct sl_report_point *p, int np, int which, struct sl_diag *d)
{
    char *body = NULL, *data = NULL;
    size_t blen = 0, dlen = 0;
    FILE *m, *dm;
    enum sl_err oe = sl_report_open_script(&m, &body, &blen, &dm, &data, &dlen, s->name, d);
    if (oe)
        return oe;
    int npts = 0, nblocks = 0, bars = 0, any_rays = 0;
    double *xs = sl_calloc((size_t)(2 * np + 1), sizeof *xs), *ys[2];
    ys[0] = sl_calloc((size_t)np + 1, sizeof *ys[0]);
    ys[1] = sl_calloc((size_t)np + 1, sizeof *ys[1]);
    if (!xs || !ys[0] || !ys[1]) {
        free(xs);
        free(ys[0]);
        free(ys[1]);
        fclose(m);
        fclose(dm);
        free(body);
        free(data);
        return sl_fail(d, SL_E_NOMEM, NULL, 0, s->name, "plot points");
    }
    int nx = 0;
    const char *plabel = NULL;
    /* one block per label: x, wrong %, uncertain %, x min, x max, map size */
    for (int k = 0; k < np; k++) {
        double x = which ? p[k].rays_per_px : p[k].ms;
        if (which && x > 0.0)
            any_rays = 1;
        if (isnan(x) || isnan(p[k].wrong_pct) || (which == 0 && !(x > 0.0)))
            continue;
        if (!plabel || strcmp(plabel, p[k].label) != 0) {
            if (plabel)
                fputs("\n\n", dm);
            fputs("# ", dm);
            gp_datum(dm, p[k].label);
            fputs(": x wrong% uncertain% x_min x_max map\n", dm);
            plabel = p[k].label;
            nblocks++;
        }
        double xl = which ? x : p[k].ms_min, xh = which ? x : p[k].ms_max;
        if (!which && p[k].reps > 1 && xh > xl)
            bars = 1;
        fprintf(dm, "%.6g %.6g %.6g %.6g %.6g %d\n", x, p[k].wrong_pct, p[k].uncertain_pct, xl, xh, p[k].map_size);
        xs[nx++] = xl;
        xs[nx++] = xh;
        ys[0][npts] = p[k].wrong_pct;
        ys[1][npts] = p[k].uncertain_pct;
        npts++;
    }
    fputs("\n\n# Pareto front of (cost, wrong% + uncertain%): x wrong% uncertain%\n", dm);
    int nfront = 0;
    for (int k = 0; k < np; k++) {
        double x = which ? p[k].rays_per_px : p[k].ms;
        if ((which ? p[k].front_rays : p[k].front_ms) && !isnan(x)) {
            fprintf(dm, "%.6g %.6g %.6g\n", x, p[k].wrong_pct, p[k].uncertain_pct);
            nfront++;
        }
    }
    if (nfront == 0)
        fputs("NaN NaN NaN\n", dm);
    /* a panel whose values are all zero says nothing: dropped (the table keeps its zeros) */
    int show[2], nshow = 0, logy = 0;
    for (int panel = 0; panel < 2; panel++) {
        double hi = 0.0;
        for (int i = 0; i < npts; i++)
            hi = fmax(hi, ys[panel][i]);
        show[panel] = hi > 0.0;
        nshow += show[panel];
    }
    char title[200];
    snprintf(title, sizeof title, "%s: wrong and undecided pixels against %s", s->name,
             which ? "shadow rays per pixel" : "method time");
    fputs("set multiplot title ", m);
    gp_quote(m, title);
    /* no key on the panels: it is a plot of its own beside them (below) */
    fputs("\nset lmargin at screen 0.13\nset rmargin at screen 0.56\n"
          "set grid\nset border 3\nset tics nomirror\nunset key\n", m);
    int logx = sl_report_axis(m, "x", xs, nx, 0) == 1;
    static const char *const ylab[2] = {"wrong, % of pixels", "undecided, % of pixels"};
    int drawn = 0;
    for (int panel = 0; panel < 2; panel++) {
        if (!show[panel])
            continue;
        int last = drawn == nshow - 1;
        if (nshow == 2)
            fprintf(m, "set tmargin at screen %s\nset bmargin at screen %s\n", drawn ? "0.46" : "0.90",
                    drawn ? "0.10" : "0.54");
        else
            fputs("set tmargin at screen 0.90\nset bmargin at screen 0.10\n", m);
        if (drawn)
            fputs("unset key\n", m);
        if (last)
            fprintf(m, "set xlabel '%s'\n",
                    which ? "shadow rays per pixel (mean over views)"
                          : "ms per cell: map layers + per-pixel step");
        else
            fputs("set xlabel ''\n", m);
        fprintf(m, "set ylabel '%s'\n", ylab[panel]);
        logy |= sl_report_axis(m, "y", ys[panel], npts, 1) == 1;
        /* the front's rings first, light and wide, so the markers sit on top of them */
        /* XZERO_OF/YZERO_OF(c): column c, a zero moved to the log axis's 0 tick (sl_report_axis) */
        fprintf(m, "plot DATA index %d using (XZERO_OF(1)):(YZERO_OF(%d)) with points pt 6 ps 2.3 lw 2 lc rgb '#b0b0b0' "
                   "title 'Pareto front (wrong + undecided)'",
                nblocks, 2 + panel);
        int b = 0;
        plabel = NULL;
        for (int k = 0; k < np; k++) {
            if (!accuracy_opens(p, k, which, &plabel))
                continue;
            const char *col;
            int pt;
            sl_report_style(b, &col, &pt);
            fprintf(m, ", \\\n  DATA index %d using (XZERO_OF(1)):(YZERO_OF(%d)) with lines lw 1 lc rgb '%s' notitle, ",
                    b, 2 + panel, col);
            if (bars)
                fprintf(m, "DATA index %d using (XZERO_OF(1)):(YZERO_OF(%d)):4:5 with xerrorbars pt %d ps 1.1 "
                           "lc rgb '%s' title ", b, 2 + panel, pt, col);
            else
                fprintf(m, "DATA index %d using (XZERO_OF(1)):(YZERO_OF(%d)) with points pt %d ps 1.1 lc rgb '%s' "
                           "title ", b, 2 + panel, pt, col);
            gp_quote(m, p[k].display);
            b++;
        }
        fputc('\n', m);
        drawn++;
    }
    if (drawn) {
        /* The key alone, a plot of its own beside both panels from the top
         * to the bottom: a key drawn by a panel holds only as many rows as
         * that panel is tall, and gnuplot drops the methods past them (5 of
         * Moderno's 10 in the upper of two panels). */
        fputs("set lmargin at screen 0.57\nset rmargin at screen 0.99\nset tmargin at screen 0.90\n"
              "set bmargin at screen 0.10\nunset border\nunset tics\nunset grid\nunset logscale\n"
              "set xlabel ''\nset ylabel ''\nset xrange [0:1]\nset yrange [0:1]\n"
              "set key at screen 0.58, screen 0.90 left top Left reverse samplen 1.5 spacing 1.1 box\n"
              "plot NaN with points pt 6 ps 2.3 lw 2 lc rgb '#b0b0b0' title 'Pareto front (wrong + undecided)'",
              m);
        int b = 0;
        plabel = NULL;
        for (int k = 0; k < np; k++) {
            if (!accuracy_opens(p, k, which, &plabel))
                continue;
            const char *col;
            int pt;
            sl_report_style(b, &col, &pt);
            fprintf(m, ", \\\n  NaN with points pt %d ps 1.1 lc rgb '%s' title ", pt, col);
            gp_quote(m, p[k].display);
            b++;
        }
        fputc('\n', m);
    }
    free(xs);
    free(ys[0]);
    free(ys[1]);
    fputs("unset multiplot\n", m);
    enum sl_err e = sl_report_close_script(m, dm, &body, &data, 0, s->name, d);
    if (e)
        return e;
    if (which && !any_rays) {
        /* a study without rays gets no rays plot: every point would sit at 0 */
        sl_report_doc_para(doc, "No method of this study casts shadow rays: the rays-per-pixel plot is not drawn.");
    } else if (npts == 0) {
        sl_report_doc_para(doc, "No cell of this study has a %s stored: that plot is not drawn.",
                           which ? "ray count" : "method time");
    } else if (nshow == 0) {
        sl_report_doc_para(doc, "Every method of this study gets every pixel right and leaves none undecided: "
                                "the plot against %s would show only zeros and is not drawn (the table has the "
                                "costs).", which ? "rays" : "time");
    } else {
        char name[160];
        snprintf(name, sizeof name, "%s-accuracy-%s", s->slug, which ? "rays" : "time");
        e = gp_run(doc, gnuplot, name, 900, 640, data, body, d);
        if (!e) {
            char cap[700];
            snprintf(cap, sizeof cap, "%s. %s; each method's map sizes joined from the smallest map to the "
                     "largest%s; ringed in grey: the Pareto front of cost against wrong + undecided.%s%s", title,
                     nshow == 2 ? "Above the pixels the method gets wrong, below those it leaves undecided"
                     : show[0]  ? "The pixels the method gets wrong (no method leaves a pixel undecided: that "
                                  "panel is dropped)"
                                : "The pixels the method leaves undecided (no method gets one wrong: that panel "
                                  "is dropped)",
                     bars ? ", bars from the fastest to the slowest timed repetition" : "",
                     logx || logy ? " Log scale where the values span more than two decades; a zero is drawn "
                                    "at the tick labelled 0 below the smallest value." : "", "");
            plot_show(doc, name, cap);
        }
    }
    free(body);
    free(data);
    return e;
}

/* ---- error against map size, and its spread across views (issue 47) ---- */

/* The wrong pixels (% of the image's non-background pixels, a view's own
 * percentage, the same figure as the accuracy plots and table.tex) against
 * the shadow-map size on a log2 axis, one line per method label (its
 * display name in the legend, the legend beside the data). Drawn when the
 * study has two map sizes or more. */
static enum sl_err maps_plot(struct sl_report_doc *doc, const struct sl_report_study *s, const char *gnuplot,
                             const struct sl_report_point *p, int np, struct sl_diag *d)
{
    int maps[64], nmaps = 0, npts = 0;
    for (int k = 0; k < np; k++) {
        if (isnan(p[k].wrong_pct))
            continue;
        npts++;
        int seen = 0;
        for (int j = 0; j < nmaps && !seen; j++)
            seen = maps[j] == p[k].map_size;
        if (!seen && nmaps < 64)
            maps[nmaps++] = p[k].map_size;
    }
    if (nmaps < 2)
        return SL_OK;   /* one map size: nothing to plot against */
    char *body = NULL, *data = NULL;
    size_t blen = 0, dlen = 0;
    FILE *m, *dm;
    enum sl_err e = sl_report_open_script(&m, &body, &blen, &dm, &data, &dlen, s->name, d);
    if (e)
        return e;
    double *ys = sl_calloc((size_t)npts + 1, sizeof *ys);
    if (!ys) {
        fclose(m), fclose(dm), free(body), free(data);
        return sl_fail(d, SL_E_NOMEM, NULL, 0, s->name, "plot points");
    }
    int ny = 0, nblocks = 0;
    const char *plabel = NULL;
    for (int k = 0; k < np; k++) {
        if (isnan(p[k].wrong_pct))
            continue;
        if (!plabel || strcmp(plabel, p[k].label) != 0) {
            fputs(plabel ? "\n\n# " : "# ", dm);
            gp_datum(dm, p[k].display);
            fputs(": map_size wrong%\n", dm);
            plabel = p[k].label;
            nblocks++;
        }
        fprintf(dm, "%d %.6g\n", p[k].map_size, p[k].wrong_pct);
        ys[ny++] = p[k].wrong_pct;
    }
    char title[200];
    snprintf(title, sizeof title, "%s: wrong pixels against the shadow-map size", s->name);
    fputs("set title ", m);
    gp_quote(m, title);
    fputs("\nset lmargin at screen 0.13\nset rmargin at screen 0.56\nset tmargin at screen 0.90\n"
          "set bmargin at screen 0.14\nset grid\nset border 3\nset tics nomirror\n"
          "set key at screen 0.58, screen 0.90 left top Left reverse samplen 2 spacing 1.1 box\n"
          "set logscale x 2\nset xtics (", m);
    for (int j = 0; j < nmaps; j++)
        fprintf(m, "%s'%d\xC2\xB2' %d", j ? ", " : "", maps[j], maps[j]);
    int lo = maps[0], hi = maps[0];
    for (int j = 0; j < nmaps; j++) {
        lo = maps[j] < lo ? maps[j] : lo;
        hi = maps[j] > hi ? maps[j] : hi;
    }
    fprintf(m, ")\nset xrange [%.6g:%.6g]\nset xlabel 'shadow-map size (texels, log\xE2\x82\x82 scale)'\n"
               "set ylabel 'wrong pixels, %% of non-background (mean of the views)'\n", lo / 1.25, hi * 1.25);
    int logy = sl_report_axis(m, "y", ys, ny, 1) == 1;
    fputs("plot ", m);
    plabel = NULL;
    for (int k = 0, b = 0; k < np; k++) {
        if (isnan(p[k].wrong_pct) || (plabel && !strcmp(plabel, p[k].label)))
            continue;
        plabel = p[k].label;
        const char *col;
        int pt;
        sl_report_style(b, &col, &pt);
        fprintf(m, "%sDATA index %d using 1:(YZERO_OF(2)) with linespoints pt %d ps 1.1 lw 1.5 lc rgb '%s' title ",
                b ? ", \\\n  " : "", b, pt, col);
        gp_quote(m, p[k].display);
        b++;
    }
    fputc('\n', m);
    free(ys);
    if ((e = sl_report_close_script(m, dm, &body, &data, 0, s->name, d)))
        return e;
    if (ny == 0 || !(logy >= 0)) {
        free(body), free(data);
        return SL_OK;
    }
    char name[160], cap[600];
    snprintf(name, sizeof name, "%s-maps", s->slug);
    e = gp_run(doc, gnuplot, name, 900, 600, data, body, d);
    if (!e) {
        snprintf(cap, sizeof cap, "%s. Each point the mean over the study's views of a view's wrong pixels in %% of "
                 "its non-background pixels (the accuracy plots' and table.tex's figure), one line per method over "
                 "its map sizes; the map size on a log\xE2\x82\x82 axis.%s", title,
                 logy == 1 ? " Log scale on the wrong pixels: they span more than two decades; a zero is drawn at "
                             "the tick labelled 0." : "");
        plot_show(doc, name, cap);
    }
    free(body), free(data);
    return e;
}

/* The spread of the wrong pixels across the views: per method label, at its
 * largest map size, a box plot of its views' percentages (median, quartiles,
 * whiskers to the furthest value within 1.5 IQR, points beyond), n under
 * each box. Drawn when a label has two views or more. */
static enum sl_err spread_plot(struct sl_report_doc *doc, const struct sl_report_study *s, const char *gnuplot,
                               const struct sl_report_point *p, int np, struct sl_diag *d)
{
    char *body = NULL, *data = NULL;
    size_t blen = 0, dlen = 0;
    FILE *m, *dm;
    enum sl_err e = sl_report_open_script(&m, &body, &blen, &dm, &data, &dlen, s->name, d);
    if (e)
        return e;
    double *ys = sl_calloc((size_t)s->n + 1, sizeof *ys);
    if (!ys) {
        fclose(m), fclose(dm), free(body), free(data);
        return sl_fail(d, SL_E_NOMEM, NULL, 0, s->name, "plot points");
    }
    int ny = 0, nb = 0, maxn = 0, one_map = 1, map = 0;
    /* every label's largest map the same: named in the title, not under each box */
    for (int k = 0; k < np; k++)
        if (!isnan(p[k].wrong_pct) && (k + 1 == np || strcmp(p[k + 1].label, p[k].label))) {
            one_map &= map == 0 || map == p[k].map_size;
            map = p[k].map_size;
        }
    char tics[8192] = "";
    size_t tl = 0;
    for (int k = 0; k < np; k++) {
        /* a label once, at its largest map size (the last of its points) */
        if (isnan(p[k].wrong_pct) || (k + 1 < np && !strcmp(p[k + 1].label, p[k].label)))
            continue;
        int n = 0;
        for (int i = 0; i < s->n; i++) {
            const struct sl_cell_record *c = &s->cells[i];
            int r = sl_report_region(c, 0);
            if (strcmp(c->label, p[k].label) || c->map_size != p[k].map_size || r < 0 ||
                !c->fig.r[r].n[SL_FIG_pixels])
                continue;
            double v = 100.0 * (double)c->fig.r[r].n[SL_FIG_wrong] / (double)c->fig.r[r].n[SL_FIG_pixels];
            if (n == 0) {
                fputs(nb ? "\n\n# " : "# ", dm);
                gp_datum(dm, p[k].display);
                fprintf(dm, " at %d\xC2\xB2: wrong%% of each view\n", p[k].map_size);
            }
            fprintf(dm, "%.6g\n", v);
            ys[ny++] = v;
            n++;
        }
        if (n == 0)
            continue;
        maxn = n > maxn ? n : maxn;
        char lab[160];
        if (one_map)
            snprintf(lab, sizeof lab, "%s (n = %d)", p[k].display, n);
        else
            snprintf(lab, sizeof lab, "%s, %d\xC2\xB2 (n = %d)", p[k].display, p[k].map_size, n);
        if (tl + strlen(lab) + 40 < sizeof tics) {
            tl += (size_t)snprintf(tics + tl, sizeof tics - tl, "%s", nb ? ", " : "");
            FILE *tf = fmemopen(tics + tl, sizeof tics - tl, "w");
            if (tf) {
                gp_quote(tf, lab);
                fprintf(tf, " %d", nb + 1);
                fclose(tf);
                tl = strlen(tics);
            }
        }
        nb++;
    }
    char title[200];
    if (one_map)
        snprintf(title, sizeof title, "%s: wrong pixels across the views, %d\xC2\xB2 maps", s->name, map);
    else
        snprintf(title, sizeof title, "%s: wrong pixels across the views", s->name);
    fputs("set title ", m);
    gp_quote(m, title);
    fprintf(m, "\nset lmargin at screen 0.16\nset rmargin at screen 0.97\nset tmargin at screen 0.90\n"
               "set bmargin at screen 0.36\nset grid ytics\nset border 3\nset tics nomirror\nunset key\n"
               "set style fill solid 0.3 border -1\nset style boxplot outliers pointtype 7\n"
               "set boxwidth 0.5\nset xrange [0.3:%.1f]\nset xtics rotate by 30 right (%s)\n"
               "set ylabel 'wrong pixels, %% (one value a view)'\n", nb + 0.7, tics);
    int logy = sl_report_axis(m, "y", ys, ny, 1);
    fputs("plot ", m);
    for (int b = 0; b < nb; b++) {
        const char *col;
        int pt;
        sl_report_style(b, &col, &pt);
        fprintf(m, "%sDATA index %d using (%d):(YZERO_OF(1)) with boxplot lc rgb '%s'", b ? ", \\\n  " : "", b,
                b + 1, col);
    }
    fputc('\n', m);
    free(ys);
    if ((e = sl_report_close_script(m, dm, &body, &data, 0, s->name, d)))
        return e;
    if (nb == 0 || maxn < 2 || logy < 0) {   /* one view, or nothing but zeros: no spread to show */
        free(body), free(data);
        return SL_OK;
    }
    char name[160], cap[700];
    snprintf(name, sizeof name, "%s-spread", s->slug);

    e = gp_run(doc, gnuplot, name, 900, 620, data, body, d);
    if (!e) {
        snprintf(cap, sizeof cap, "%s. Per method at its largest shadow map, a box over its views' wrong pixels (%% "
                 "of each view's non-background pixels): the median, the quartiles, whiskers to the furthest value "
                 "within 1.5 times the interquartile range, a dot for each value beyond; n views under each box.%s",
                 title, logy == 1 ? " Log scale: the values span more than two decades; a zero is drawn at the tick "
                                    "labelled 0." : "");
        plot_show(doc, name, cap);
    }
    free(body), free(data);
    return e;
}

enum sl_err sl_report_plot_accuracy(struct sl_report_doc *doc, const struct sl_report_study *s,
                                    const char *gnuplot, struct sl_diag *d)
{
    struct sl_report_point *p = NULL;
    int np = 0;
    enum sl_err e = sl_report_points(s->cells, s->n, &p, &np, d);
    if (e)
        return e;
    sl_report_doc_para(doc,
                       "One point per method label and shadow-map size: the mean over the study's scenes, "
                       "viewpoints and viewports of the wrong and of the undecided pixels (whole image) and of "
                       "the cost. A method's time is the rendering of the shadow-map layers it reads plus its "
                       "per-pixel step (ray step included), each the median of the timed repetitions (min-max "
                       "beside it), so a map-only method and a ray tracer are charged alike. The Pareto front "
                       "holds the points no other point beats in both cost and wrong + undecided pixels: a pixel "
                       "left undecided counts as an error there, since the method has not answered for it.");
    e = accuracy_plot(doc, s, gnuplot, p, np, 0, d);
    if (!e)
        e = accuracy_plot(doc, s, gnuplot, p, np, 1, d);
    if (!e) {
        char id[160];
        snprintf(id, sizeof id, "%s-accuracy", s->slug);
        struct sl_tab t;
        sl_tab_init(&t, id, 12, 2, "%s: wrong and undecided pixels against cost, with the Pareto fronts",
                           s->name);
        static const char *const heads[] = {"method", "map", "cells", "wrong %", "undecided %", "layers ms",
                                            "step ms", "layers + step ms", "min–max ms", "rays / pixel", "front (time)",
                                            "front (rays)"};
        for (int k = 0; k < 12; k++)
            sl_tab_head(&t, k, "%s", heads[k]);
        int once = 0;
        for (int k = 0; k < np; k++) {
            sl_tab_row(&t, k == 0 || strcmp(p[k].label, p[k - 1].label) != 0);
            sl_tab_cell(&t, 0, "%s", p[k].display);
            sl_tab_cell(&t, 1, "%d²", p[k].map_size);
            sl_tab_cell(&t, 2, "%d", p[k].ncells);
            if (isnan(p[k].wrong_pct)) {   /* a soft method: no hard verdicts (the soft table has its errors) */
                sl_tab_cell(&t, 3, "–");
                sl_tab_cell(&t, 4, "–");
            } else {
                sl_tab_cell(&t, 3, "%.4f", p[k].wrong_pct);
                sl_tab_cell(&t, 4, "%.4f", p[k].uncertain_pct);
            }
            const char *one = p[k].reps == 1 ? SL_REPORT_ONCE : "";
            once |= p[k].reps == 1;
            sl_tab_cell(&t, 5, "%.3f%s", p[k].ms_layers, one);
            sl_tab_cell(&t, 6, "%.3f%s", p[k].ms_step, one);
            sl_tab_cell(&t, 7, "%.3f%s", p[k].ms, one);
            if (p[k].reps > 1)
                sl_tab_cell(&t, 8, "%.3f–%.3f (%d runs)", p[k].ms_min, p[k].ms_max, p[k].reps);
            else
                sl_tab_cell(&t, 8, "1 run");
            if (isnan(p[k].rays_per_px))
                sl_tab_cell(&t, 9, "–");
            else
                sl_tab_cell(&t, 9, "%.4f", p[k].rays_per_px);
            sl_tab_cell(&t, 10, "%s", p[k].front_ms ? "yes" : "");
            sl_tab_cell(&t, 11, "%s", p[k].front_rays ? "yes" : "");
        }
        sl_tab_notef(&t, "Means over the cells: layers ms (the shadow-map render of the layers "
                 "the method reads), step ms (its per-pixel step, ray step included) and their sum, each cell's "
                 "the median over its timed repetitions.");
        if (once)
            sl_report_tab_once(&t);
        e = sl_report_doc_table(doc, &t, d);
        sl_tab_free(&t);
    }
    if (!e)
        e = maps_plot(doc, s, gnuplot, p, np, d);
    if (!e)
        e = spread_plot(doc, s, gnuplot, p, np, d);
    free(p);
    return e;
}

void sl_report_gp_quote(FILE *f, const char *s) { gp_quote(f, s); }

/* ---- for the other sections: one plot drawn and shown ---- */

enum sl_err sl_report_plot_draw(struct sl_report_doc *doc, const char *gnuplot, const char *name, int w, int h,
                                const char *data, const char *body, const char *caption, struct sl_diag *d)
{
    enum sl_err e = gp_run(doc, gnuplot, name, w, h, data, body, d);
    if (!e)
        plot_show(doc, name, caption);
    return e;
}
