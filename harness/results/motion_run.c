/*
 * motion_run.c — see motion_run.h.
 * Invariant: only names made by the run (scene, path, label, viewpoint:
 * [A-Za-z0-9._-], scenefile.c and config.c refuse others) reach a shell
 * command, each single-quoted.
 */
#define _XOPEN_SOURCE 700
#include "motion_run.h"
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include "motion.h"
#include "outputs.h"
#include "util.h"

int sl_motion_config_has_paths(const struct sl_config *c)
{
    for (int s = 0; s < c->nscenes; s++)
        if (c->scenes[s].npaths)
            return 1;
    return 0;
}

/* `prog` in PATH */
static int have_program(const char *prog)
{
    const char *p = getenv("PATH");
    char buf[4096];
    snprintf(buf, sizeof buf, "%s", p ? p : "/usr/bin:/bin");
    for (char *save = NULL, *dir = strtok_r(buf, ":", &save); dir; dir = strtok_r(NULL, ":", &save)) {
        char path[4200];
        snprintf(path, sizeof path, "%s/%s", dir, prog);
        if (access(path, X_OK) == 0)
            return 1;
    }
    return 0;
}

/* The motion table and its note, for sl_out_write_formats. */
struct motion_tables {
    const struct sl_motion_row *rows;
    int                         n;
    const char                 *note;
};

static enum sl_err write_motion_table(FILE *f, enum sl_table_format fmt, const void *arg, struct sl_diag *d)
{
    const struct motion_tables *t = arg;
    if (fmt == SL_TABLE_MD)
        fprintf(f, "# Errors over motion\n\nPer path, map size and label: the whole image's wrong pixels per "
                   "frame (mean, worst), and flicker: pixels whose verdict changes between consecutive "
                   "frames while their truth does not, compared by surface point (reprojected through "
                   "the G-buffer onto the same triangle; pixel for pixel when the camera holds still). "
                   "Per 1,000 contour pixels: of the thinnest contour of the later frame of each "
                   "compared pair.\n\n");
    enum sl_err e = sl_motion_write(f, fmt, t->rows, t->n, d);
    if (fmt == SL_TABLE_MD && t->note[0])
        fprintf(f, "\n%s", t->note);
    return e;
}

static enum sl_err write_tables(const char *dir, const struct sl_motion_row *rows, int n, const char *note,
                                struct sl_diag *d)
{
    static const struct sl_out_format_file files[] = {
        {"motion.md", SL_TABLE_MD}, {"motion.csv", SL_TABLE_CSV}, {"motion.tex", SL_TABLE_LATEX},
    };
    const struct motion_tables t = {rows, n, note};
    return sl_out_write_formats(dir, files, (int)(sizeof files / sizeof files[0]), write_motion_table, &t, d);
}

/* The plot of one group: wrong pixels (left axis) and flicker (right axis)
 * per frame, one colour per label; a label's flicker only where it has a
 * compared pair (pairs[l]). A group none of whose labels has one (a path of
 * one frame, a --cells slice holding only its first frame: any later frame
 * is compared with the one before it, recomputed when this run did not
 * compute it, run.c) gets its .dat and no plot: its
 * flicker is not defined, and gnuplot refuses a series of NaN only (it left
 * a 0-byte PNG and failed the run after its cells were stored). *plotted: 0
 * then. */
static enum sl_err write_plot(const char *mdir, const char *name, const struct sl_cell_record *cells, int n,
                              const struct sl_motion_row *row, char (*labels)[48], const int *pairs, int nl,
                              int gnuplot, int *plotted, struct sl_diag *d)
{
    int any = 0;
    for (int l = 0; l < nl; l++)
        any |= pairs[l] > 0;
    *plotted = any;
    char path[1600];
    snprintf(path, sizeof path, "%s/%s.dat", mdir, name);
    FILE *f = fopen(path, "w");
    if (!f)
        return sl_fail(d, SL_E_OUTPUT, path, 0, NULL, "cannot write: %s", strerror(errno));
    fprintf(f, "# frame, then per label (");
    for (int l = 0; l < nl; l++)
        fprintf(f, "%s%s", l ? " " : "", labels[l]);
    fprintf(f, "): wrong pixels, flicker against the frame before (NaN: not compared)\n");
    sl_motion_series(f, cells, n, row, labels, nl);
    if (fclose(f) != 0)
        return sl_fail(d, SL_E_OUTPUT, path, 0, NULL, "write failed");
    if (!any)
        return SL_OK;
    snprintf(path, sizeof path, "%s/%s.gp", mdir, name);
    if (!(f = fopen(path, "w")))
        return sl_fail(d, SL_E_OUTPUT, path, 0, NULL, "cannot write: %s", strerror(errno));
    fprintf(f, "# shadowlab: `gnuplot %s.gp` in this folder draws %s.png from %s.dat\n"
               "set terminal pngcairo size 1100,520 noenhanced font 'sans,10'\nset output '%s.png'\n"
               "set datafile missing '-'\nset key outside right top\nset grid\n"
               "set title '%s, path %s, %dx%d, map %d: wrong pixels (solid, left) and flicker (dashed, right) "
               "per frame'\nset xlabel 'frame'\nset ylabel 'wrong pixels'\nset y2label 'flicker (pixels)'\n"
               "set ytics nomirror\nset y2tics\nset yrange [0:*]\nset y2range [0:*]\n",
            name, name, name, name, row->scene, row->path, row->vw, row->vh, row->map_size);
    static const char *const color[] = {"#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9",
                                        "#000000", "#F0E442"};
    fprintf(f, "plot ");
    for (int l = 0; l < nl; l++) {
        fprintf(f, "%s'%s.dat' using 1:%d with lines lw 2 lc rgb '%s' title '%s wrong'", l ? ", \\\n     " : "",
                name, 2 + 2 * l, color[l % 8], labels[l]);
        if (pairs[l] > 0)
            fprintf(f, ", '%s.dat' using 1:%d axes x1y2 with lines dt 2 lw 1.5 lc rgb '%s' title '%s flicker'", name,
                    3 + 2 * l, color[l % 8], labels[l]);
    }
    fprintf(f, "\n");
    if (fclose(f) != 0)
        return sl_fail(d, SL_E_OUTPUT, path, 0, NULL, "write failed");
    if (gnuplot) {
        char cmd[3400];
        snprintf(cmd, sizeof cmd, "cd '%s' && gnuplot '%s.gp' </dev/null >'%s.log' 2>&1", mdir, name, name);
        if (system(cmd) != 0)
            return sl_fail(d, SL_E_IO, path, 0, NULL, "gnuplot failed on this plot: see %s/%s.log", mdir, name);
        snprintf(path, sizeof path, "%s/%s.log", mdir, name);
        unlink(path);
    }
    return SL_OK;
}

/* The error overlays of one (group, label) as motion/NAME-LABEL/frame-NNN.png
 * (relative links into overlays/) and, with ffmpeg, NAME-LABEL.mp4. The
 * overlay sheets differ in size from frame to frame (each is cropped to its
 * frame's shadows and errors): the video pads every frame to the largest. */
static enum sl_err write_sequence(const char *dir, const char *mdir, const char *name,
                                  const struct sl_cell_record *cells, int n, const struct sl_motion_row *row,
                                  int ffmpeg, int *frames_out, struct sl_diag *d)
{
    char seq[1500];
    snprintf(seq, sizeof seq, "%s/%s-%s", mdir, name, row->label);
    if (mkdir(seq, 0777) != 0 && errno != EEXIST)
        return sl_fail(d, SL_E_OUTPUT, seq, 0, NULL, "cannot make the folder: %s", strerror(errno));
    int k = 0;
    for (int i = 0; i < n; i++) {
        const struct sl_cell_record *c = &cells[i];
        char path[64];
        int fr = sl_motion_frame_of(c->viewpoint, path, sizeof path);
        if (fr < 0 || strcmp(path, row->path) || strcmp(c->scene, row->scene) || strcmp(c->label, row->label) ||
            c->vw != row->vw || c->vh != row->vh || c->map_size != row->map_size || !c->overlay[0])
            continue;
        const char *base = strrchr(c->overlay, '/');
        base = base ? base + 1 : c->overlay;
        char src[1700], target[1700], link[1700];
        snprintf(src, sizeof src, "%s/overlays/%s", dir, base);
        if (access(src, R_OK) != 0)
            continue;   /* an overlay of a cell computed elsewhere and not gathered here */
        snprintf(target, sizeof target, "../../overlays/%s", base);
        snprintf(link, sizeof link, "%s/frame-%03d.png", seq, fr);
        unlink(link);
        if (symlink(target, link) != 0)
            return sl_fail(d, SL_E_OUTPUT, link, 0, NULL, "cannot link: %s", strerror(errno));
        k++;
    }
    *frames_out = k;
    if (ffmpeg && k > 1) {
        char cmd[5000];
        snprintf(cmd, sizeof cmd,
                 "cd '%s' && ffmpeg -y -loglevel error -framerate 10 -pattern_type glob -i '%s-%s/frame-*.png' "
                 "-vf 'scale=trunc(iw/2)*2:trunc(ih/2)*2,pad=ceil(iw/2)*2:ceil(ih/2)*2' -pix_fmt yuv420p "
                 "'%s-%s.mp4' </dev/null >/dev/null 2>&1", mdir, name, row->label, name, row->label);
        if (system(cmd) != 0)
            return sl_fail(d, SL_E_IO, mdir, 0, NULL, "ffmpeg failed on %s-%s", name, row->label);
    }
    return SL_OK;
}

enum sl_err sl_motion_outputs(struct sl_store *st, const struct sl_config *c, const struct sl_run_result *res,
                              const char *dir, struct sl_diag *d)
{
    if (!sl_motion_config_has_paths(c))
        return SL_OK;
    struct sl_cell_record *cells = NULL;
    int n = 0;
    enum sl_err e = SL_OK;
    if (st) {
        if ((e = sl_out_stored_cells(st, c, &cells, &n, d)))
            return e;
    } else {
        cells = sl_calloc((size_t)(res->ncells ? res->ncells : 1), sizeof *cells);
        if (!cells)
            return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "motion cells");
        for (int i = 0; i < res->ncells; i++) {
            sl_out_record(c, &res->cells[i], &cells[i]);
            if (c->overlays) {
                char name[400];
                sl_out_overlay_name(c, &res->cells[i], name, sizeof name);
                snprintf(cells[i].overlay, sizeof cells[i].overlay, "overlays/%s", name);
            }
        }
        n = res->ncells;
    }
    struct sl_motion_row *rows = NULL;
    int nrows = 0;
    if ((e = sl_motion_rows(cells, n, &rows, &nrows, d))) {
        free(cells);
        return e;
    }
    const int gnuplot = have_program("gnuplot"), ffmpeg = have_program("ffmpeg");
    char mdir[1200], note[1000] = "";
    snprintf(mdir, sizeof mdir, "%s/motion", dir);
    if (nrows && (e = sl_mkdirs(mdir, d)))
        goto out;
    int seq_frames = 0, unplotted = 0;
    for (int r = 0; r < nrows && !e; r++) {
        const struct sl_motion_row *row = &rows[r];
        char name[200];
        snprintf(name, sizeof name, "%s-%s-%dx%d-%d", row->scene, row->path, row->vw, row->vh, row->map_size);
        if (r == 0 || strcmp(rows[r - 1].scene, row->scene) || strcmp(rows[r - 1].path, row->path) ||
            rows[r - 1].vw != row->vw || rows[r - 1].vh != row->vh || rows[r - 1].map_size != row->map_size) {
            char labels[32][48];
            int pairs[32], nl = 0, plotted = 1;
            for (int q = r; q < nrows && nl < 32 && !strcmp(rows[q].scene, row->scene) &&
                            !strcmp(rows[q].path, row->path) && rows[q].vw == row->vw && rows[q].vh == row->vh &&
                            rows[q].map_size == row->map_size; q++) {
                pairs[nl] = rows[q].pairs;
                snprintf(labels[nl++], sizeof labels[0], "%s", rows[q].label);
            }
            e = write_plot(mdir, name, cells, n, row, labels, pairs, nl, gnuplot, &plotted, d);
            unplotted += !plotted;
        }
        int k = 0;
        if (!e && c->overlays)
            e = write_sequence(dir, mdir, name, cells, n, row, ffmpeg, &k, d);
        seq_frames += k;
    }
    if (!e) {
        size_t k = 0;
        if (unplotted)
            k += (size_t)snprintf(note + k, sizeof note - k, "%d plot(s) not drawn: a path with fewer than two "
                                  "comparable frames here (one frame, or a slice holding only its first) has no "
                                  "flicker (not defined); its wrong pixels per frame are in its .dat file.\n", unplotted);
        if (!gnuplot)
            k += (size_t)snprintf(note + k, sizeof note - k, "gnuplot is not in PATH: the plots under motion/ are "
                                  "left as .dat and .gp files (`gnuplot NAME.gp` there draws them).\n");
        if (!c->overlays)
            k += (size_t)snprintf(note + k, sizeof note - k, "Overlays are off: no frame sequences.\n");
        else if (!ffmpeg)
            k += (size_t)snprintf(note + k, sizeof note - k, "ffmpeg is not in PATH: the overlay sequences "
                                  "(motion/*/frame-NNN.png, %d frames) are not made into MP4s.\n", seq_frames);
        e = write_tables(dir, rows, nrows, note, d);
    }
out:
    free(rows);
    free(cells);
    return e;
}
