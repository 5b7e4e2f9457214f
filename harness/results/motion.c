/*
 * motion.c — see motion.h.
 * Invariant: a row's sums are over cells of exactly its key; a frame's
 * flicker counts only when that frame was compared (flicker_compared > 0).
 */
#include "motion.h"
#include "pivot.h"
#include <ctype.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

int sl_motion_frame_of(const char *viewpoint, char *path, size_t n)
{
    const char *dot = strrchr(viewpoint, '.');
    if (!dot || dot == viewpoint || strlen(dot + 1) != 3)
        return -1;
    for (int k = 1; k <= 3; k++)
        if (!isdigit((unsigned char)dot[k]))
            return -1;
    if (path)
        snprintf(path, n, "%.*s", (int)(dot - viewpoint), viewpoint);
    return atoi(dot + 1);
}

static int same_key(const struct sl_motion_row *r, const struct sl_cell_record *c, const char *path)
{
    return strcmp(r->scene, c->scene) == 0 && strcmp(r->path, path) == 0 && strcmp(r->label, c->label) == 0 &&
           r->vw == c->vw && r->vh == c->vh && r->map_size == c->map_size;
}

static int row_cmp(const void *pa, const void *pb)
{
    const struct sl_motion_row *a = pa, *b = pb;
    int k = strcmp(a->scene, b->scene);
    if (!k) k = strcmp(a->path, b->path);
    if (!k) k = (a->vw * 100000 + a->vh) - (b->vw * 100000 + b->vh);
    if (!k) k = a->map_size - b->map_size;
    /* labels keep their first appearance (worst_frame is borrowed below) */
    return k;
}

enum sl_err sl_motion_rows(const struct sl_cell_record *cells, int ncells, struct sl_motion_row **rows,
                           int *nrows, struct sl_diag *d)
{
    *rows = NULL;
    *nrows = 0;
    struct sl_motion_row *out = NULL;
    int n = 0, cap = 0;
    for (int i = 0; i < ncells; i++) {
        const struct sl_cell_record *c = &cells[i];
        char path[64];
        int frame = sl_motion_frame_of(c->viewpoint, path, sizeof path);
        if (frame < 0)
            continue;
        int r = 0;
        while (r < n && !same_key(&out[r], c, path))
            r++;
        if (r == n) {
            if (n == cap) {
                struct sl_motion_row *g = realloc(out, (size_t)(cap ? 2 * cap : 16) * sizeof *g);
                if (!g) {
                    free(out);
                    return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "motion rows");
                }
                out = g;
                cap = cap ? 2 * cap : 16;
            }
            memset(&out[n], 0, sizeof out[n]);
            snprintf(out[n].scene, sizeof out[n].scene, "%s", c->scene);
            snprintf(out[n].path, sizeof out[n].path, "%s", path);
            snprintf(out[n].label, sizeof out[n].label, "%s", c->label);
            out[n].vw = c->vw;
            out[n].vh = c->vh;
            out[n].map_size = c->map_size;
            out[n].worst_frame = out[n].worst_flicker_frame = -1;
            n++;
        }
        struct sl_motion_row *w = &out[r];
        uint64_t wrong = c->fig.wrong_image;
        w->frames++;
        w->mean_wrong += (double)wrong;
        if (w->worst_frame < 0 || wrong > w->worst_wrong) {
            w->worst_wrong = wrong;
            w->worst_frame = frame;
        }
        if (c->flicker_compared > 0) {
            w->pairs++;
            w->flicker += c->flicker;
            w->compared += c->flicker_compared;
            w->contour_px += c->fig.nregions > 0 ? c->fig.r[0].n[SL_FIG_pixels] : 0;
            if (w->worst_flicker_frame < 0 || c->flicker > w->worst_flicker) {
                w->worst_flicker = c->flicker;
                w->worst_flicker_frame = frame;
            }
        }
    }
    for (int r = 0; r < n; r++) {
        out[r].mean_wrong /= out[r].frames;
        out[r].mean_flicker = out[r].pairs ? (double)out[r].flicker / out[r].pairs : NAN;
        out[r].per_1000 = out[r].contour_px ? 1000.0 * (double)out[r].flicker / (double)out[r].contour_px : NAN;
    }
    /* stable: insertion sort keeps the labels' order within a key */
    for (int i = 1; i < n; i++)
        for (int k = i; k > 0 && row_cmp(&out[k - 1], &out[k]) > 0; k--) {
            struct sl_motion_row t = out[k];
            out[k] = out[k - 1];
            out[k - 1] = t;
        }
    *rows = out;
    *nrows = n;
    return SL_OK;
}

static void num(FILE *f, double v, const char *fmt)
{
    if (isnan(v))
        fputs("n/a", f);
    else
        fprintf(f, fmt, v);
}

/* a number for LaTeX, "--" when not defined */
static void tex_num(FILE *f, double v, int dec)
{
    char s[64];
    sl_tex_number(s, sizeof s, v, dec);
    fputs(s, f);
}

static void tex_caption(FILE *f, const struct sl_motion_row *r, const char *what)
{
    fputs("\\caption{", f);
    sl_tex_text(f, r->scene);
    fputs(", path ", f);
    sl_tex_text(f, r->path);
    fprintf(f, ", %d$\\times$%d, map %d\\textsuperscript{2}: %s}\\\\\n", r->vw, r->vh, r->map_size, what);
}

static void tex_head(FILE *f, const char *cols)
{
    for (int pass = 0; pass < 2; pass++)
        fprintf(f, "\\toprule\n%s \\\\\n\\midrule\n%s\n", cols, pass ? "\\endhead" : "\\endfirsthead");
    fputs("\\bottomrule\n\\endfoot\n", f);
}

/* Per group (scene, path, viewport, map size) two longtables that each fit
 * a plain article's \\columnwidth at \\small (the eight columns side by side
 * ran 222 pt too wide): the wrong pixels per frame, then the flicker. */
static void motion_tex(FILE *f, const struct sl_motion_row *rows, int n)
{
    fputs("% shadowlab motion tables; needs \\usepackage{booktabs,longtable}\n\n", f);
    for (int i = 0; i < n;) {
        int e = i + 1;
        while (e < n && row_cmp(&rows[i], &rows[e]) == 0)
            e++;
        fputs("{\\small\\setlength{\\tabcolsep}{4pt}\n\\begin{longtable}{lrrrr}\n", f);
        tex_caption(f, &rows[i], "the whole image's wrong pixels per frame (mean, worst and the frame of the worst)");
        tex_head(f, "label & frames & mean & worst & frame");
        for (int k = i; k < e; k++) {
            const struct sl_motion_row *r = &rows[k];
            sl_tex_text(f, r->label);
            fprintf(f, " & %d & ", r->frames);
            tex_num(f, r->mean_wrong, 1);
            fputs(" & ", f);
            tex_num(f, (double)r->worst_wrong, 0);
            fprintf(f, " & %d \\\\\n", r->worst_frame);
        }
        fputs("\\end{longtable}\n\\begin{longtable}{lrrrrrr}\n", f);
        tex_caption(f, &rows[i], "flicker, pixels whose verdict changes between consecutive frames while their truth "
                                 "does not: in all, per compared pair, at worst (and its frame), and per 1,000 "
                                 "pixels of the thinnest contour; -- where no pair was compared");
        tex_head(f, "label & pairs & flicker & per pair & worst & frame & per 1,000");
        for (int k = i; k < e; k++) {
            const struct sl_motion_row *r = &rows[k];
            sl_tex_text(f, r->label);
            fprintf(f, " & %d & ", r->pairs);
            tex_num(f, r->pairs ? (double)r->flicker : NAN, 0);
            fputs(" & ", f);
            tex_num(f, r->mean_flicker, 1);
            fputs(" & ", f);
            tex_num(f, r->pairs ? (double)r->worst_flicker : NAN, 0);
            if (r->pairs)
                fprintf(f, " & %d & ", r->worst_flicker_frame);
            else
                fputs(" & -- & ", f);
            tex_num(f, r->per_1000, 2);
            fputs(" \\\\\n", f);
        }
        fputs("\\end{longtable}}\n\n", f);
        i = e;
    }
}

void sl_motion_write(FILE *f, enum sl_table_format fmt, const struct sl_motion_row *rows, int n)
{
    if (fmt == SL_TABLE_CSV) {
        fprintf(f, "scene,path,viewport,map_size,label,frames,pairs,mean_wrong,worst_wrong,worst_frame,flicker,"
                   "mean_flicker,worst_flicker,worst_flicker_frame,compared,contour_px,flicker_per_1000_contour\n");
        for (int i = 0; i < n; i++) {
            const struct sl_motion_row *r = &rows[i];
            fprintf(f, "%s,%s,%dx%d,%d,%s,%d,%d,%.2f,%llu,%d,%llu,", r->scene, r->path, r->vw, r->vh, r->map_size,
                    r->label, r->frames, r->pairs, r->mean_wrong, (unsigned long long)r->worst_wrong, r->worst_frame,
                    (unsigned long long)r->flicker);
            if (!isnan(r->mean_flicker))
                fprintf(f, "%.2f", r->mean_flicker);
            fprintf(f, ",%llu,%d,%llu,%llu,", (unsigned long long)r->worst_flicker, r->worst_flicker_frame,
                    (unsigned long long)r->compared, (unsigned long long)r->contour_px);
            if (!isnan(r->per_1000))
                fprintf(f, "%.3f", r->per_1000);
            fputc('\n', f);
        }
        return;
    }
    if (fmt == SL_TABLE_LATEX) {
        motion_tex(f, rows, n);
        return;
    }
    /* Markdown */
    for (int i = 0; i < n; i++) {
        const struct sl_motion_row *r = &rows[i];
        if (i == 0 || row_cmp(&rows[i - 1], r) != 0)
            fprintf(f, "%s### %s, path %s, %dx%d, map %d²\n\n| label | frames | mean wrong | worst wrong "
                       "(frame) | flicker | mean per pair | worst (frame) | per 1,000 contour px |\n"
                       "|---|---:|---:|---:|---:|---:|---:|---:|\n", i ? "\n" : "", r->scene, r->path, r->vw,
                    r->vh, r->map_size);
        const char *sep = " | ";
        fprintf(f, "| %s%s%d%s", r->label, sep, r->frames, sep);
        fprintf(f, "%.1f%s%llu (%d)%s", r->mean_wrong, sep, (unsigned long long)r->worst_wrong, r->worst_frame, sep);
        if (r->pairs)
            fprintf(f, "%llu%s", (unsigned long long)r->flicker, sep);
        else   /* no compared pair: fewer than two comparable frames */
            fprintf(f, "not defined%s", sep);
        num(f, r->mean_flicker, "%.1f");
        fputs(sep, f);
        if (r->pairs)
            fprintf(f, "%llu (%d)", (unsigned long long)r->worst_flicker, r->worst_flicker_frame);
        else
            fputs("n/a", f);
        fputs(sep, f);
        num(f, r->per_1000, "%.2f");
        fputs(" |\n", f);
    }
}

int sl_motion_series(FILE *f, const struct sl_cell_record *cells, int ncells, const struct sl_motion_row *row,
                     char (*labels)[48], int nlabels)
{
    int maxf = -1;
    for (int i = 0; i < ncells; i++) {
        char path[64];
        int fr = sl_motion_frame_of(cells[i].viewpoint, path, sizeof path);
        if (fr > maxf && strcmp(path, row->path) == 0 && strcmp(cells[i].scene, row->scene) == 0)
            maxf = fr;
    }
    int written = 0;
    for (int fr = 0; fr <= maxf; fr++) {
        fprintf(f, "%d", fr);
        for (int l = 0; l < nlabels; l++) {
            const struct sl_cell_record *hit = NULL;
            for (int i = 0; i < ncells && !hit; i++) {
                char path[64];
                if (sl_motion_frame_of(cells[i].viewpoint, path, sizeof path) == fr &&
                    strcmp(path, row->path) == 0 && strcmp(cells[i].scene, row->scene) == 0 &&
                    strcmp(cells[i].label, labels[l]) == 0 && cells[i].vw == row->vw && cells[i].vh == row->vh &&
                    cells[i].map_size == row->map_size)
                    hit = &cells[i];
            }
            if (!hit)
                fputs(" - -", f);
            else if (hit->flicker_compared)
                fprintf(f, " %llu %llu", (unsigned long long)hit->fig.wrong_image, (unsigned long long)hit->flicker);
            else
                fprintf(f, " %llu NaN", (unsigned long long)hit->fig.wrong_image);
        }
        fputc('\n', f);
        written++;
    }
    return written;
}
