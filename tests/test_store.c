/* store::* — the SQLite results store: round trip of every count and
 * percentage, resume lookups, latest-run-wins, atomic cells, refusal of files
 * that are not a store of this version. Each test uses its own temp folder. */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <math.h>
#include <sqlite3.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <signal.h>
#include <fcntl.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>
#include <cmocka.h>
#include "sl_test.h"
#include "outputs.h"
#include "store.h"
#include "storefile.h"
#include "table.h"

#define HASH_A 0x0123456789abcdefull
#define HASH_B 0xfedcba9876543210ull

struct tmp {
    char dir[64];
    char db[128];
};

static void tmp_make(struct tmp *t)
{
    snprintf(t->dir, sizeof t->dir, "/tmp/sl_store_XXXXXX");
    assert_non_null(mkdtemp(t->dir));
    snprintf(t->db, sizeof t->db, "%s/shadowlab.db", t->dir);
}

static void tmp_remove(struct tmp *t)
{
    static const char *const suffix[] = {"", "-wal", "-shm", "-journal", ".lock"};
    char p[160];
    for (size_t i = 0; i < sizeof suffix / sizeof suffix[0]; i++) {
        snprintf(p, sizeof p, "%s%s", t->db, suffix[i]);
        unlink(p);
    }
    rmdir(t->dir);
}

/* Figures where every count differs (base + 100 r + k) and every percentage
 * differs; pixels (no base) and uncertain of region 1 are NaN. */
static void make_fig(struct sl_figures *f, uint64_t base, const int *thick, int nreg)
{
    memset(f, 0, sizeof *f);
    f->nregions = nreg;
    f->background = base + 7777;
    f->wrong_image = base + 999;
    for (int r = 0; r < nreg; r++) {
        f->r[r].thickness = thick[r];
        for (int k = 0; k < SL_FIG_COUNT; k++) {
            f->r[r].n[k] = base + 100u * (uint64_t)r + (uint64_t)k;
            f->r[r].pct[k] = (double)(r * SL_FIG_COUNT + k) + 0.125 + (double)base / 1024.0;
        }
        f->r[r].pct[SL_FIG_pixels] = NAN;
    }
    if (nreg > 1)
        f->r[1].pct[SL_FIG_uncertain] = NAN;
}

/* A cell of prim_s; cost holds its counters and times (NULL: none measured). */
static struct sl_cell_record make_cell(const char *vp, int map, const char *label, const struct sl_figures *f,
                                       const struct sl_cell_record *cost, uint64_t base)
{
    struct sl_cell_record c;
    if (cost)
        c = *cost;
    else
        sl_cell_record_init(&c);
    snprintf(c.scene, sizeof c.scene, "prim_s");
    snprintf(c.viewpoint, sizeof c.viewpoint, "%s", vp);
    snprintf(c.method, sizeof c.method, "nsm");
    snprintf(c.label, sizeof c.label, "%s", label);
    c.vw = 640;
    c.vh = 480;
    c.map_size = map;
    c.cell_index = map / 1024;
    c.n_pfl = base + 1;
    c.n_pnfl = base + 2;
    c.n_background = base + 3;
    c.n_truth_lit = base + 4;
    c.n_truth_shadow = base + 5;
    c.fig = *f;
    snprintf(c.overlay, sizeof c.overlay, "%s", cost ? "study_s/overlays/a.png" : "");
    return c;
}

static void fill_prov(struct sl_provenance *p, const char *sha)
{
    memset(p, 0, sizeof *p);
    snprintf(p->git_sha, sizeof p->git_sha, "%s", sha);
    snprintf(p->time_utc, sizeof p->time_utc, "2024-01-02T03:04:05Z");
    snprintf(p->host, sizeof p->host, "hostA");
    snprintf(p->cpu, sizeof p->cpu, "CPU, Model \"X\"");
    snprintf(p->isa, sizeof p->isa, "x86_64-avx2+fma");
    snprintf(p->gl_renderer, sizeof p->gl_renderer, "llvmpipe");
    snprintf(p->gl_version, sizeof p->gl_version, "4.5");
    snprintf(p->embree, sizeof p->embree, "3.13.5");
    p->threads = 2;
}

/* The fixture of most cases: a temp folder (fx_temp), the store opened in
 * it (fx_store), and one run begun (fx_run: study_s, config hash HASH_A,
 * the provenance p of "abc1234"). The teardown closes the store the fixture
 * opened (a case that closes it itself says so with fx_close) and removes
 * the folder. */
struct fx {
    struct tmp t;
    struct sl_store *s;
    struct sl_provenance p;
    int64_t run;
};

static int fx_temp(void **st)
{
    struct fx *x = calloc(1, sizeof *x);
    assert_non_null(x);
    *st = x;
    tmp_make(&x->t);
    return 0;
}

static int fx_store(void **st)
{
    fx_temp(st);
    struct fx *x = *st;
    struct sl_diag d;
    assert_int_equal(sl_store_open(x->t.db, &x->s, &d), SL_OK);
    return 0;
}

static int fx_run(void **st)
{
    fx_store(st);
    struct fx *x = *st;
    struct sl_diag d;
    fill_prov(&x->p, "abc1234");
    assert_int_equal(sl_store_begin_run(x->s, &x->p, "study_s", "c.yaml", HASH_A, "name: study_s\n", &x->run, &d),
                     SL_OK);
    return 0;
}

static void fx_close(struct fx *x)
{
    sl_store_close(x->s);
    x->s = NULL;
}

static int fx_teardown(void **st)
{
    struct fx *x = *st;
    if (x) {
        fx_close(x);
        tmp_remove(&x->t);
        free(x);
    }
    return 0;
}

static const struct sl_cell_record *find(const struct sl_cell_record *cells, int n, const char *vp, int map)
{
    for (int i = 0; i < n; i++)
        if (strcmp(cells[i].viewpoint, vp) == 0 && cells[i].map_size == map)
            return &cells[i];
    return NULL;
}

static void assert_same_fig(const struct sl_figures *got, const struct sl_figures *want)
{
    assert_int_equal(got->nregions, want->nregions);
    assert_int_equal(got->background, want->background);
    assert_int_equal(got->wrong_image, want->wrong_image);
    for (int r = 0; r < want->nregions; r++) {
        assert_int_equal(got->r[r].thickness, want->r[r].thickness);
        for (int k = 0; k < SL_FIG_COUNT; k++) {
            assert_int_equal(got->r[r].n[k], want->r[r].n[k]);
            if (isnan(want->r[r].pct[k]))
                assert_true(isnan(got->r[r].pct[k]));
            else
                assert_true(got->r[r].pct[k] == want->r[r].pct[k]);   /* REAL is a double: exact */
        }
    }
}

static void assert_cell(const struct sl_cell_record *c, uint64_t base, const struct sl_figures *f,
                        const char *sha)
{
    assert_non_null(c);
    assert_string_equal(c->scene, "prim_s");
    assert_string_equal(c->method, "nsm");
    assert_string_equal(c->label, "nsm_a");
    assert_int_equal(c->vw, 640);
    assert_int_equal(c->vh, 480);
    assert_int_equal(c->n_pfl, base + 1);
    assert_int_equal(c->n_pnfl, base + 2);
    assert_int_equal(c->n_background, base + 3);
    assert_int_equal(c->n_truth_lit, base + 4);
    assert_int_equal(c->n_truth_shadow, base + 5);
    assert_string_equal(c->git_sha, sha);
    assert_string_equal(c->config_hash, "0123456789abcdef");
    assert_string_equal(c->machine, "hostA/CPU, Model \"X\"/x86_64-avx2+fma");
    assert_same_fig(&c->fig, f);
}

/* 10 px sorts before 2 px as text: the store must order by thickness */
static const int thick4[] = {2, 4, 10, 0};
static const int thick3[] = {2, 6, 0};

static void store_round_trip(void **st)
{
    struct fx *x = *st;
    struct tmp t = x->t;
    struct sl_diag d;
    struct sl_store *s = x->s;
    struct sl_provenance p;
    fill_prov(&p, "abc1234");
    int64_t run1 = 0;
    assert_int_equal(sl_store_begin_run(s, &p, "study_s", "configs/x.yaml", HASH_A, "name: study_s\n", &run1, &d), SL_OK);
    assert_true(run1 > 0);

    struct sl_figures f1, f2;
    make_fig(&f1, 1000, thick4, 4);
    make_fig(&f2, 3000, thick3, 3);
    struct sl_cell_record cost;
    sl_cell_record_init(&cost);
    cost.runs = 5;
    cost.truth_rays = 10;
    cost.lookups = 11;
    cost.rays = 12;
    cost.tri_tests = 13;
    cost.gs_prims = 14;
    cost.fragments = 15;
    cost.violations = 0;
    cost.ms_gbuffer_render = 1.5, cost.ms_gbuffer_render_min = 1.25, cost.ms_gbuffer_render_max = 2.0;
    cost.ms_truth = 2.25, cost.ms_truth_min = 2.0, cost.ms_truth_max = 3.0;
    cost.ms_map_render = 4.5, cost.ms_map_render_min = 4.0, cost.ms_map_render_max = 5.0;
    cost.ms_method = 3.125, cost.ms_method_min = 3.0, cost.ms_method_max = 3.5;
    cost.ms_gbuffer_readback = 0.5, cost.ms_fit = 0.75, cost.ms_map_readback = 0.875, cost.ms_ray_step = 1.0;
    cost.ms_step1 = 0.1, cost.ms_step2 = 0.2, cost.ms_step3 = 0.3, cost.ms_step4 = 0.4;
    cost.ms_contours = 6.0, cost.ms_figures = 7.0, cost.ms_overlay = NAN;
    cost.ms_gpu_gbuffer = 0.3125, cost.ms_gpu_map = 0.0;   /* 0: no layer read */
    struct sl_cell_record c1 = make_cell("side", 1024, "nsm_a", &f1, &cost, 1000);
    struct sl_cell_record c2 = make_cell("side", 2048, "nsm_a", &f2, NULL, 3000);
    assert_int_equal(sl_store_put_cell(s, run1, HASH_A, &c1, &d), SL_OK);
    assert_int_equal(sl_store_put_cell(s, run1, HASH_A, &c2, &d), SL_OK);

    assert_int_equal(sl_store_count(s, "runs"), 1);
    assert_int_equal(sl_store_count(s, "cells"), 2);
    assert_int_equal(sl_store_count(s, "figures"), (4 * SL_FIG_COUNT + 1) + (3 * SL_FIG_COUNT + 1));
    assert_int_equal(sl_store_count(s, "sqlite_master"), -1);

    struct sl_cell_record *cells = NULL;
    int n = -1;
    assert_int_equal(sl_store_query(s, NULL, &cells, &n, &d), SL_OK);
    assert_int_equal(n, 2);
    assert_cell(find(cells, n, "side", 1024), 1000, &f1, "abc1234");
    assert_cell(find(cells, n, "side", 2048), 3000, &f2, "abc1234");
    /* sweep order (cell_index 1, then 2) */
    assert_int_equal(cells[0].map_size, 1024);
    /* costs, study, overlay and run come back as stored; unknown costs as zero counts and NaN times */
    const struct sl_cell_record *k = &cells[0];
    assert_int_equal(k->runs, 5);
    assert_int_equal(k->truth_rays, 10);
    assert_int_equal(k->lookups, 11);
    assert_int_equal(k->rays, 12);
    assert_int_equal(k->tri_tests, 13);
    assert_int_equal(k->gs_prims, 14);
    assert_int_equal(k->fragments, 15);
    assert_true(k->ms_gbuffer_render_min == 1.25 && k->ms_truth_max == 3.0 && k->ms_map_render == 4.5);
    assert_true(k->ms_method == 3.125 && k->ms_method_min == 3.0 && k->ms_method_max == 3.5);
    assert_true(k->ms_gbuffer_readback == 0.5 && k->ms_fit == 0.75 && k->ms_map_readback == 0.875 &&
                k->ms_ray_step == 1.0);
    assert_true(k->ms_step1 == 0.1 && k->ms_step4 == 0.4 && k->ms_contours == 6.0 && k->ms_figures == 7.0);
    assert_true(isnan(k->ms_overlay));
    assert_true(k->ms_gpu_gbuffer == 0.3125 && k->ms_gpu_map == 0.0);
    assert_true(isnan(cells[1].ms_gpu_gbuffer));   /* not measured: NULL, back as NaN */
    assert_string_equal(cells[0].study, "study_s");
    assert_string_equal(cells[0].overlay, "study_s/overlays/a.png");
    assert_int_equal(cells[0].run_id, run1);
    assert_string_equal(cells[1].overlay, "");
    assert_int_equal(cells[1].rays, 0);
    assert_true(isnan(cells[1].ms_method));
    free(cells);

    /* the study filter */
    struct sl_store_filter other = {.study = "other"}, same = {.study = "study_s"};
    assert_int_equal(sl_store_query(s, &other, &cells, &n, &d), SL_OK);
    assert_int_equal(n, 0);
    assert_int_equal(sl_store_query(s, &same, &cells, &n, &d), SL_OK);
    assert_int_equal(n, 2);
    free(cells);

    /* the runs, with their provenance and config text */
    struct sl_store_run *runs = NULL;
    assert_int_equal(sl_store_runs(s, &runs, &n, &d), SL_OK);
    assert_int_equal(n, 1);
    assert_int_equal(runs[0].run_id, run1);
    assert_int_equal(runs[0].ncells, 2);
    assert_string_equal(runs[0].study, "study_s");
    assert_string_equal(runs[0].config_path, "configs/x.yaml");
    assert_string_equal(runs[0].config_hash, "0123456789abcdef");
    assert_string_equal(runs[0].config_text, "name: study_s\n");
    assert_string_equal(runs[0].prov.git_sha, "abc1234");
    assert_string_equal(runs[0].prov.isa, "x86_64-avx2+fma");
    assert_string_equal(runs[0].prov.embree, "3.13.5");
    assert_int_equal(runs[0].prov.threads, 2);
    sl_store_runs_free(runs, n);

    /* what other tools see in SQL: NaN as NULL, regions by name */
    sqlite3 *raw = NULL;
    assert_int_equal(sqlite3_open(t.db, &raw), SQLITE_OK);
    sqlite3_stmt *q = NULL;
    assert_int_equal(sqlite3_prepare_v2(raw,
                                        "SELECT (SELECT count(*) FROM figures WHERE percent IS NULL), "
                                        "(SELECT count FROM figures WHERE map_size = 1024 AND region = '10px' "
                                        "AND figure = 'wrong'), "
                                        "(SELECT count FROM figures WHERE map_size = 2048 AND figure = 'background'), "
                                        "(SELECT viewport FROM cells WHERE map_size = 2048), "
                                        "(SELECT config_hash FROM runs)",
                                        -1, &q, NULL),
                     SQLITE_OK);
    assert_int_equal(sqlite3_step(q), SQLITE_ROW);
    /* pixels of every region, uncertain of region 1, background: (4+1+1) + (3+1+1) */
    assert_int_equal(sqlite3_column_int(q, 0), 11);
    assert_int_equal(sqlite3_column_int(q, 1), 1000 + 200 + SL_FIG_wrong);
    assert_int_equal(sqlite3_column_int(q, 2), 3000 + 7777);
    assert_string_equal((const char *)sqlite3_column_text(q, 3), "640x480");
    assert_string_equal((const char *)sqlite3_column_text(q, 4), "0123456789abcdef");
    sqlite3_finalize(q);
    sqlite3_close(raw);

    /* survives closing: a fresh handle reads the same */
    fx_close(x);
    s = NULL;
    assert_int_equal(sl_store_open(t.db, &s, &d), SL_OK);
    assert_int_equal(sl_store_query(s, NULL, &cells, &n, &d), SL_OK);
    assert_int_equal(n, 2);
    assert_cell(find(cells, n, "side", 2048), 3000, &f2, "abc1234");
    free(cells);
    sl_store_close(s);
}

/* A soft-shadow cell (area light): no region of hard figures, the soft
 * figures of the whole image, back as stored; and the tables render them. */
static void store_soft_cell(void **st)
{
    struct fx *x = *st;
    struct sl_diag d;
    struct sl_store *s = x->s;
    struct sl_provenance p;
    fill_prov(&p, "abc1234");
    int64_t run = 0;
    assert_int_equal(sl_store_begin_run(s, &p, "soft", "c.yaml", HASH_A, "", &run, &d), SL_OK);
    struct sl_figures f;
    memset(&f, 0, sizeof f);
    f.background = 77;
    struct sl_soft_figures sf;
    for (int k = 0; k < SL_SFIG_COUNT; k++) {
        sf.n[k] = 1000 + (uint64_t)k;
        sf.pct[k] = k == SL_SFIG_soft_pixels ? NAN : 0.5 + k;
    }
    struct sl_cell_record c = make_cell("side", 1024, "soft_a", &f, NULL, 10);
    c.soft = sf;
    c.has_soft = 1;
    assert_int_equal(sl_store_put_cell(s, run, HASH_A, &c, &d), SL_OK);
    struct sl_cell_record *cells = NULL;
    int n = 0;
    assert_int_equal(sl_store_query(s, NULL, &cells, &n, &d), SL_OK);
    assert_int_equal(n, 1);
    assert_true(cells[0].has_soft);
    assert_int_equal(cells[0].fig.nregions, 0);
    assert_int_equal(cells[0].fig.background, 77);
    for (int k = 0; k < SL_SFIG_COUNT; k++) {
        assert_int_equal(cells[0].soft.n[k], 1000 + (uint64_t)k);
        if (k == SL_SFIG_soft_pixels)
            assert_true(isnan(cells[0].soft.pct[k]));
        else
            assert_true(cells[0].soft.pct[k] == 0.5 + k);
    }
    /* rendered: the soft rows, a mean as a percentage of visibility, a count with its share */
    char *md = NULL;
    size_t len = 0;
    FILE *mf = open_memstream(&md, &len);
    assert_int_equal(sl_table_write(mf, SL_TABLE_MD, NULL, cells, n, &d), SL_OK);
    fclose(mf);
    assert_non_null(strstr(md, "| soft_mae | 1.500% |"));
    assert_non_null(strstr(md, "| soft_within_005 | 1004 (4.50%) |"));
    assert_null(strstr(md, "| wrong |"));
    free(md);
    free(cells);
}

static void store_has_cell_matches_key_and_hash(void **st)
{
    struct fx *x = *st;
    struct sl_diag d;
    int64_t run = x->run;
    struct sl_store *s = x->s;
    struct sl_figures f;
    make_fig(&f, 5, thick3, 3);
    struct sl_cell_record c = make_cell("side", 1024, "nsm_a", &f, NULL, 5);
    assert_false(sl_store_has_cell(s, HASH_A, "prim_s", "side", 640, 480, 1024, "nsm_a"));
    assert_int_equal(sl_store_put_cell(s, run, HASH_A, &c, &d), SL_OK);
    assert_true(sl_store_has_cell(s, HASH_A, "prim_s", "side", 640, 480, 1024, "nsm_a"));
    assert_false(sl_store_has_cell(s, HASH_B, "prim_s", "side", 640, 480, 1024, "nsm_a"));
    assert_false(sl_store_has_cell(s, HASH_A, "other", "side", 640, 480, 1024, "nsm_a"));
    assert_false(sl_store_has_cell(s, HASH_A, "prim_s", "with", 640, 480, 1024, "nsm_a"));
    assert_false(sl_store_has_cell(s, HASH_A, "prim_s", "side", 480, 640, 1024, "nsm_a"));
    assert_false(sl_store_has_cell(s, HASH_A, "prim_s", "side", 640, 480, 2048, "nsm_a"));
    assert_false(sl_store_has_cell(s, HASH_A, "prim_s", "side", 640, 480, 1024, "nsm_b"));
}

static void store_latest_run_wins(void **st)
{
    struct fx *x = *st;
    struct sl_diag d;
    struct sl_store *s = x->s;
    struct sl_provenance p1, p2;
    fill_prov(&p1, "abc1234");
    fill_prov(&p2, "def5678");
    int64_t run1 = 0, run2 = 0;
    assert_int_equal(sl_store_begin_run(s, &p1, "study_s", "c.yaml", HASH_A, "name: study_s\n", &run1, &d), SL_OK);
    struct sl_figures f1, f2, f3;
    make_fig(&f1, 1000, thick4, 4);
    make_fig(&f2, 3000, thick3, 3);
    make_fig(&f3, 5000, thick4, 4);
    struct sl_cell_record c1 = make_cell("side", 1024, "nsm_a", &f1, NULL, 1000);
    struct sl_cell_record c2 = make_cell("side", 2048, "nsm_a", &f2, NULL, 3000);
    assert_int_equal(sl_store_put_cell(s, run1, HASH_A, &c1, &d), SL_OK);
    assert_int_equal(sl_store_put_cell(s, run1, HASH_A, &c2, &d), SL_OK);
    assert_int_equal(sl_store_begin_run(s, &p2, "study_s", "c.yaml", HASH_A, "name: study_s\n", &run2, &d), SL_OK);
    assert_true(run2 > run1);
    struct sl_cell_record c3 = make_cell("side", 1024, "nsm_a", &f3, NULL, 5000);  /* c1's key, another config */
    assert_int_equal(sl_store_put_cell(s, run2, HASH_B, &c3, &d), SL_OK);
    assert_int_equal(sl_store_count(s, "runs"), 2);
    assert_int_equal(sl_store_count(s, "cells"), 3);

    struct sl_cell_record *cells = NULL;
    int n = 0;
    assert_int_equal(sl_store_query(s, NULL, &cells, &n, &d), SL_OK);
    assert_int_equal(n, 2);
    const struct sl_cell_record *latest = find(cells, n, "side", 1024);   /* c3, of the other config */
    assert_non_null(latest);
    assert_string_equal(latest->config_hash, "fedcba9876543210");
    assert_string_equal(latest->git_sha, "def5678");
    assert_int_equal(latest->n_pfl, 5001);
    assert_same_fig(&latest->fig, &f3);
    assert_cell(find(cells, n, "side", 2048), 3000, &f2, "abc1234");
    free(cells);

    /* restricted to the first run, its own cell of that key comes back */
    struct sl_store_filter only1 = {.run_id = run1};
    assert_int_equal(sl_store_query(s, &only1, &cells, &n, &d), SL_OK);
    assert_int_equal(n, 2);
    assert_cell(find(cells, n, "side", 1024), 1000, &f1, "abc1234");
    free(cells);

    struct sl_store_filter map2048 = {.map_size = 2048};
    assert_int_equal(sl_store_query(s, &map2048, &cells, &n, &d), SL_OK);
    assert_int_equal(n, 1);
    assert_int_equal(cells[0].map_size, 2048);
    free(cells);

    struct sl_store_filter none = {.viewpoint = "against", .scene = "prim_s"};
    assert_int_equal(sl_store_query(s, &none, &cells, &n, &d), SL_OK);
    assert_int_equal(n, 0);
    free(cells);
}

/* A count that does not fit SQLite's signed 64 bits fails the last region's
 * last figure row, after the cell row and 47 figure rows went in: the whole
 * cell must be gone, and the store must be usable afterwards. */
static void store_failed_put_leaves_no_cell(void **st)
{
    struct fx *x = *st;
    struct tmp t = x->t;
    struct sl_diag d;
    int64_t run = x->run;
    struct sl_store *s = x->s;
    struct sl_figures good, bad;
    make_fig(&good, 10, thick3, 3);
    make_fig(&bad, 20, thick4, 4);
    bad.r[3].n[SL_FIG_COUNT - 1] = UINT64_MAX;
    struct sl_cell_record cg = make_cell("side", 1024, "nsm_a", &good, NULL, 10);
    struct sl_cell_record cb = make_cell("with", 1024, "nsm_a", &bad, NULL, 20);
    assert_int_equal(sl_store_put_cell(s, run, HASH_A, &cg, &d), SL_OK);

    memset(&d, 0, sizeof d);
    assert_int_equal(sl_store_put_cell(s, run, HASH_A, &cb, &d), SL_E_IO);
    assert_string_equal(d.file, t.db);
    assert_non_null(strstr(d.msg, "CHECK constraint failed"));
    char last[80];
    snprintf(last, sizeof last, "%s of region image", sl_figure_name(SL_FIG_COUNT - 1));   /* the last figure */
    assert_non_null(strstr(d.msg, last));
    assert_int_equal(sl_store_count(s, "cells"), 1);
    assert_int_equal(sl_store_count(s, "figures"), 3 * SL_FIG_COUNT + 1);
    assert_false(sl_store_has_cell(s, HASH_A, "prim_s", "with", 640, 480, 1024, "nsm_a"));

    /* no transaction left open: the next put commits */
    bad.r[3].n[SL_FIG_COUNT - 1] = 42;
    cb.fig = bad;
    assert_int_equal(sl_store_put_cell(s, run, HASH_A, &cb, &d), SL_OK);
    assert_int_equal(sl_store_count(s, "cells"), 2);
    assert_int_equal(sl_store_count(s, "figures"), 3 * SL_FIG_COUNT + 1 + 4 * SL_FIG_COUNT + 1);
}

/* The database itself refuses the last row of a cell (a trigger another
 * connection installed, standing in for a full disk or a constraint of a
 * newer schema): the cell row must be rolled back too. */
/* The figures table takes every figure name this build stores and nothing
 * else: not a part of a name, not two names joined by the comma that
 * delimits the CHECK's list, not an empty name. */
static int raw_figure(const char *path, const char *figure)
{
    sqlite3 *raw = NULL;
    assert_int_equal(sqlite3_open(path, &raw), SQLITE_OK);
    sqlite3_stmt *q = NULL;
    assert_int_equal(sqlite3_prepare_v2(raw,
                                        "INSERT INTO figures (cell_id, scene, viewpoint, viewport, map_size, "
                                        "label, region, figure, count) SELECT cell_id, scene, viewpoint, "
                                        "viewport, map_size, label, '9px', ?1, 1 FROM cells LIMIT 1",
                                        -1, &q, NULL),
                     SQLITE_OK);
    sqlite3_bind_text(q, 1, figure, -1, SQLITE_TRANSIENT);
    int rc = sqlite3_step(q);
    sqlite3_finalize(q);
    sqlite3_close(raw);
    return rc;
}

static void store_figure_names_checked(void **st)
{
    struct fx *x = *st;
    struct tmp t = x->t;
    struct sl_diag d;
    int64_t run = x->run;
    struct sl_store *s = x->s;
    struct sl_figures fig;
    make_fig(&fig, 10, thick3, 3);
    struct sl_cell_record c = make_cell("side", 1024, "nsm_a", &fig, NULL, 10);
    assert_int_equal(sl_store_put_cell(s, run, HASH_A, &c, &d), SL_OK);
    fx_close(x);
    for (int k = 0; k < SL_FIG_COUNT; k++)
        assert_int_equal(raw_figure(t.db, sl_figure_name((enum sl_figure)k)), SQLITE_DONE);
    for (int k = 0; k < SL_SFIG_COUNT; k++)
        assert_int_equal(raw_figure(t.db, sl_soft_figure_name((enum sl_soft_figure)k)), SQLITE_DONE);
    for (int k = 0; k < SL_AFIG_COUNT; k++)
        assert_int_equal(raw_figure(t.db, sl_alias_figure_name((enum sl_alias_figure)k)), SQLITE_DONE);
    assert_int_equal(raw_figure(t.db, "background"), SQLITE_DONE);
    const char *bad[] = {"bogus", "pixel", "ixels", "pfl,pnfl", "pixels,", ",pixels", "", "Pixels", "pixels "};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++)
        assert_int_equal(raw_figure(t.db, bad[i]), SQLITE_CONSTRAINT);
}

static void store_refused_last_row_rolls_back(void **st)
{
    struct fx *x = *st;
    struct tmp t = x->t;
    struct sl_diag d;
    int64_t run = x->run;
    struct sl_store *s = x->s;

    sqlite3 *raw = NULL;
    assert_int_equal(sqlite3_open(t.db, &raw), SQLITE_OK);
    assert_int_equal(sqlite3_exec(raw,
                                  "CREATE TRIGGER refuse BEFORE INSERT ON figures "
                                  "WHEN NEW.figure = 'background' BEGIN SELECT RAISE(ABORT, 'disk on fire'); END",
                                  NULL, NULL, NULL),
                     SQLITE_OK);
    sqlite3_close(raw);

    struct sl_figures f;
    make_fig(&f, 10, thick3, 3);
    struct sl_cell_record c = make_cell("side", 1024, "nsm_a", &f, NULL, 10);
    assert_int_equal(sl_store_put_cell(s, run, HASH_A, &c, &d), SL_E_IO);
    assert_string_equal(d.file, t.db);
    assert_non_null(strstr(d.msg, "disk on fire"));
    assert_string_equal(d.key, "prim_s/side/640x480/1024/nsm_a");
    assert_int_equal(sl_store_count(s, "cells"), 0);
    assert_int_equal(sl_store_count(s, "figures"), 0);
}

static void sleep_ms(long ms)
{
    struct timespec ts = {ms / 1000, (ms % 1000) * 1000000L};
    nanosleep(&ts, NULL);
}

/* A writer killed with SIGKILL while putting cells in a loop: every cell
 * that is there has all its figure rows, and no figure row lacks its cell. */
static void store_killed_writer_leaves_whole_cells(void **st)
{
    struct fx *x = *st;
    struct tmp t = x->t;
    struct sl_diag d;
    int64_t run = x->run;
    struct sl_store *s = NULL;
    fx_close(x);

    pid_t pid = fork();
    assert_true(pid >= 0);
    if (pid == 0) {
        struct sl_store *w = NULL;
        if (sl_store_open(t.db, &w, NULL) != SL_OK)
            _exit(3);
        struct sl_figures f;
        make_fig(&f, 10, thick4, 4);
        for (int i = 1;; i++) {
            struct sl_cell_record c = make_cell("side", 64 * i, "nsm_a", &f, NULL, 10);
            if (sl_store_put_cell(w, run, HASH_A, &c, NULL) != SL_OK)
                _exit(4);
        }
    }
    /* let it commit some cells, then kill it wherever it is */
    long cells = 0;
    for (int tries = 0; tries < 2000 && cells < 20; tries++) {
        sleep_ms(2);
        assert_int_equal(sl_store_open_existing(t.db, &s, &d), SL_OK);   /* a reader, beside the writer */
        cells = sl_store_count(s, "cells");
        sl_store_close(s);
    }
    sleep_ms(3);
    kill(pid, SIGKILL);
    int status = 0;
    assert_int_equal(waitpid(pid, &status, 0), pid);
    assert_true(WIFSIGNALED(status));   /* killed, not failed (exit 3 or 4) */

    assert_int_equal(sl_store_open(t.db, &s, &d), SL_OK);
    cells = sl_store_count(s, "cells");
    assert_true(cells >= 20);
    assert_int_equal(sl_store_count(s, "figures"), cells * (4 * SL_FIG_COUNT + 1));
    struct sl_cell_record *out = NULL;
    int n = 0;
    assert_int_equal(sl_store_query(s, NULL, &out, &n, &d), SL_OK);
    assert_int_equal(n, cells);
    struct sl_figures want;
    make_fig(&want, 10, thick4, 4);
    for (int i = 0; i < n; i++)
        assert_same_fig(&out[i].fig, &want);
    free(out);
    sl_store_close(s);
}

static void store_unknown_run_is_refused(void **st)
{
    struct fx *x = *st;
    struct sl_diag d;
    struct sl_store *s = x->s;
    struct sl_figures f;
    make_fig(&f, 10, thick3, 3);
    struct sl_cell_record c = make_cell("side", 1024, "nsm_a", &f, NULL, 10);
    assert_int_equal(sl_store_put_cell(s, 77, HASH_A, &c, &d), SL_E_IO);
    assert_non_null(strstr(d.msg, "FOREIGN KEY"));
    assert_int_equal(sl_store_count(s, "cells"), 0);
    assert_int_equal(sl_store_put_cell(s, 77, HASH_A, NULL, &d), SL_E_USAGE);
}

static void write_file(const char *path, const char *text)
{
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    fputs(text, f);
    fclose(f);
}

static void store_refuses_non_database(void **st)
{
    struct fx *x = *st;
    struct tmp t = x->t;
    const char *text = "scene,viewpoint\nprimitives,side\n";
    write_file(t.db, text);
    struct sl_diag d;
    struct sl_store *s = (struct sl_store *)&d;   /* must be reset to NULL */
    assert_int_equal(sl_store_open(t.db, &s, &d), SL_E_IO);
    assert_null(s);
    assert_string_equal(d.file, t.db);
    assert_non_null(strstr(d.msg, "not a database"));
    /* left untouched */
    char buf[128] = "";
    FILE *f = fopen(t.db, "rb");
    assert_non_null(f);
    size_t got = fread(buf, 1, sizeof buf - 1, f);
    fclose(f);
    assert_int_equal(got, strlen(text));
    assert_string_equal(buf, text);
}

static void raw_exec(const char *path, const char *sql)
{
    sqlite3 *raw = NULL;
    assert_int_equal(sqlite3_open(path, &raw), SQLITE_OK);
    assert_int_equal(sqlite3_exec(raw, sql, NULL, NULL, NULL), SQLITE_OK);
    sqlite3_close(raw);
}

static void store_refuses_other_version(void **st)
{
    struct fx *x = *st;
    struct tmp t = x->t;
    /* t is a copy of the fixture's folder: removed and made again below, the
     * last one removed here (the teardown then finds the first gone) */
    raw_exec(t.db, "CREATE TABLE runs (x); PRAGMA user_version = 7");
    struct sl_diag d;
    struct sl_store *s = NULL;
    assert_int_equal(sl_store_open(t.db, &s, &d), SL_E_IO);
    assert_null(s);
    assert_string_equal(d.file, t.db);
    assert_non_null(strstr(d.msg, "schema version 7"));
    tmp_remove(&t);

    /* someone else's database (user_version 0 but not empty) */
    tmp_make(&t);
    raw_exec(t.db, "CREATE TABLE notes (x)");
    assert_int_equal(sl_store_open(t.db, &s, &d), SL_E_IO);
    assert_non_null(strstr(d.msg, "not a shadowlab results store"));
    tmp_remove(&t);

    /* the right version number over different tables */
    tmp_make(&t);
    char sql[200];
    snprintf(sql, sizeof sql, "CREATE TABLE runs (x); CREATE TABLE cells (y); CREATE TABLE figures (z); "
                              "PRAGMA user_version = %d", sl_store_version());
    raw_exec(t.db, sql);
    assert_int_equal(sl_store_open(t.db, &s, &d), SL_E_IO);
    assert_string_equal(d.key, "runs");
    assert_non_null(strstr(d.msg, "differs"));
    tmp_remove(&t);
}

/* A new store is this build's version, in WAL mode, and an empty file becomes one. */
static void store_new_file_is_current_version_wal(void **st)
{
    struct fx *x = *st;
    struct tmp t = x->t;
    write_file(t.db, "");
    struct sl_diag d;
    struct sl_store *s = NULL;
    assert_int_equal(sl_store_open(t.db, &s, &d), SL_OK);
    sqlite3 *raw = NULL;
    assert_int_equal(sqlite3_open(t.db, &raw), SQLITE_OK);
    sqlite3_stmt *q = NULL;
    assert_int_equal(sqlite3_prepare_v2(raw, "PRAGMA user_version", -1, &q, NULL), SQLITE_OK);
    assert_int_equal(sqlite3_step(q), SQLITE_ROW);
    assert_int_equal(sqlite3_column_int(q, 0), sl_store_version());
    sqlite3_finalize(q);
    assert_int_equal(sqlite3_prepare_v2(raw, "PRAGMA journal_mode", -1, &q, NULL), SQLITE_OK);
    assert_int_equal(sqlite3_step(q), SQLITE_ROW);
    assert_string_equal((const char *)sqlite3_column_text(q, 0), "wal");
    sqlite3_finalize(q);
    sqlite3_close(raw);
    sl_store_close(s);
    /* reopening an existing store checks and accepts it */
    assert_int_equal(sl_store_open(t.db, &s, &d), SL_OK);
    assert_int_equal(sl_store_count(s, "runs"), 0);
    sl_store_close(s);
    sl_store_close(NULL);
}

/* issue 34: one cell per config hash and key, whatever writes it. A cell
 * computed again (a run without --resume) replaces the stored one, figures
 * and all, in its transaction; the schema itself refuses a second row. */
static void store_key_stored_once(void **st)
{
    struct fx *x = *st;
    struct tmp t = x->t;
    struct sl_diag d;
    struct sl_store *s = x->s;
    struct sl_provenance p1, p2;
    fill_prov(&p1, "abc1234");
    fill_prov(&p2, "def5678");
    int64_t run1 = 0, run2 = 0;
    assert_int_equal(sl_store_begin_run(s, &p1, "study_s", "c.yaml", HASH_A, "name: study_s\n", &run1, &d), SL_OK);
    struct sl_figures f1, f2;
    make_fig(&f1, 1000, thick4, 4);
    make_fig(&f2, 3000, thick3, 3);
    struct sl_cell_record c1 = make_cell("side", 1024, "nsm_a", &f1, NULL, 1000);
    struct sl_cell_record c2 = make_cell("side", 1024, "nsm_a", &f2, NULL, 3000);   /* c1's key */
    assert_int_equal(sl_store_put_cell(s, run1, HASH_A, &c1, &d), SL_OK);
    long figs1 = sl_store_count(s, "figures");
    assert_int_equal(sl_store_begin_run(s, &p2, "study_s", "c.yaml", HASH_A, "name: study_s\n", &run2, &d), SL_OK);
    assert_int_equal(sl_store_put_cell(s, run2, HASH_A, &c2, &d), SL_OK);
    assert_int_equal(sl_store_count(s, "cells"), 1);
    assert_true(sl_store_count(s, "figures") < figs1);   /* 3 regions now, not 4 + 3 */
    struct sl_cell_record *cells = NULL;
    int n = 0;
    assert_int_equal(sl_store_query(s, NULL, &cells, &n, &d), SL_OK);
    assert_int_equal(n, 1);
    assert_cell(&cells[0], 3000, &f2, "def5678");
    free(cells);
    fx_close(x);
    /* no path around it: a raw second row of the key breaks the schema */
    sqlite3 *raw = NULL;
    assert_int_equal(sqlite3_open(t.db, &raw), SQLITE_OK);
    char *sql = sqlite3_mprintf("CREATE TEMP TABLE c AS SELECT * FROM cells; UPDATE c SET cell_id = cell_id + 1; "
                                "INSERT INTO cells SELECT * FROM c");
    assert_int_not_equal(sqlite3_exec(raw, sql, NULL, NULL, NULL), SQLITE_OK);
    assert_non_null(strstr(sqlite3_errmsg(raw), "UNIQUE"));
    sqlite3_free(sql);
    sqlite3_close(raw);
}

/* issue 34: each cell's digest covers its figure rows: one changed digit of
 * a stored percent_of, or a count, is found by verify and refused by every
 * reader (query), naming the cell; an untouched store verifies clean. */
static void store_digest_finds_changed_figure(void **st)
{
    struct fx *x = *st;
    struct tmp t = x->t;
    struct sl_diag d;
    struct sl_store *s = x->s;
    struct sl_provenance p1;
    fill_prov(&p1, "abc1234");
    int64_t run1 = 0;
    assert_int_equal(sl_store_begin_run(s, &p1, "study_s", "c.yaml", HASH_A, "name: study_s\n", &run1, &d), SL_OK);
    struct sl_figures f1, f2;
    make_fig(&f1, 1000, thick4, 4);
    make_fig(&f2, 3000, thick3, 3);
    struct sl_cell_record c1 = make_cell("side", 1024, "nsm_a", &f1, NULL, 1000);
    struct sl_cell_record c2 = make_cell("side", 2048, "nsm_a", &f2, NULL, 3000);
    assert_int_equal(sl_store_put_cell(s, run1, HASH_A, &c1, &d), SL_OK);
    assert_int_equal(sl_store_put_cell(s, run1, HASH_A, &c2, &d), SL_OK);
    struct sl_store_verify v;
    assert_int_equal(sl_store_verify(s, &v, &d), SL_OK);
    assert_int_equal(v.cells, 2);
    assert_int_equal(v.ndamaged, 0);
    assert_true(v.figures > 0);
    sl_store_verify_free(&v);
    fx_close(x);

    static const char *const edits[] = {
        "UPDATE figures SET percent_of = 'pixelz' WHERE rowid = (SELECT min(f.rowid) FROM figures f JOIN cells c "
        "USING (cell_id) WHERE c.map_size = 2048 AND f.percent_of IS NOT NULL)",
        "UPDATE figures SET count = count + 1 WHERE rowid = (SELECT max(f.rowid) FROM figures f JOIN cells c "
        "USING (cell_id) WHERE c.map_size = 2048)",
    };
    for (size_t i = 0; i < sizeof edits / sizeof edits[0]; i++) {
        char copy[160];
        snprintf(copy, sizeof copy, "%s/edit%zu.db", t.dir, i);
        sqlite3 *raw = NULL;
        assert_int_equal(sqlite3_open(t.db, &raw), SQLITE_OK);
        char *q = sqlite3_mprintf("VACUUM INTO %Q", copy);
        assert_int_equal(sqlite3_exec(raw, q, NULL, NULL, NULL), SQLITE_OK);
        sqlite3_free(q);
        sqlite3_close(raw);
        assert_int_equal(sqlite3_open(copy, &raw), SQLITE_OK);
        assert_int_equal(sqlite3_exec(raw, edits[i], NULL, NULL, NULL), SQLITE_OK);
        assert_int_equal(sqlite3_changes(raw), 1);
        sqlite3_close(raw);
        assert_int_equal(sl_store_open_existing(copy, &s, &d), SL_OK);
        assert_int_equal(sl_store_verify(s, &v, &d), SL_OK);
        assert_int_equal(v.cells, 2);
        assert_int_equal(v.ndamaged, 1);
        assert_string_equal(v.damaged[0].key, "prim_s/side/640x480/2048/nsm_a");
        sl_store_verify_free(&v);
        struct sl_cell_record *cells = NULL;
        int n = 0;
        assert_int_equal(sl_store_query(s, NULL, &cells, &n, &d), SL_E_IO);
        assert_non_null(strstr(d.msg, "prim_s/side/640x480/2048/nsm_a"));
        assert_non_null(strstr(d.msg, "damaged"));
        assert_null(cells);
        sl_store_close(s);
        unlink(copy);
    }
}

/* issue 34: the writer's lock is the file's, not the path's: a second
 * writer through a symbolic link to the store, or to its folder, is refused;
 * so is a relative spelling. */
static void store_lock_follows_links(void **st)
{
    struct fx *x = *st;
    struct tmp t = x->t;
    struct sl_diag d;
    struct sl_store *a = NULL, *b = NULL;
    assert_int_equal(sl_store_open(t.db, &a, &d), SL_OK);
    char link_file[160], link_dir[160], via_dir[200];
    snprintf(link_file, sizeof link_file, "%s/alias.db", t.dir);
    snprintf(link_dir, sizeof link_dir, "%s-dirlink", t.dir);
    snprintf(via_dir, sizeof via_dir, "%s/shadowlab.db", link_dir);
    assert_int_equal(symlink(t.db, link_file), 0);
    assert_int_equal(symlink(t.dir, link_dir), 0);
    assert_int_equal(sl_store_open(link_file, &b, &d), SL_E_IO);
    assert_null(b);
    assert_non_null(strstr(d.msg, "in use by another run"));
    assert_int_equal(sl_store_open(via_dir, &b, &d), SL_E_IO);
    assert_non_null(strstr(d.msg, "in use by another run"));
    sl_store_close(a);
    assert_int_equal(sl_store_open(link_file, &b, &d), SL_OK);   /* released: through the link too */
    sl_store_close(b);
    unlink(link_file);
    unlink(link_dir);
}

static void store_missing_folder_is_an_error(void **st)
{
    (void)st;
    struct sl_diag d;
    struct sl_store *s = NULL;
    assert_int_equal(sl_store_open("/nonexistent-sl-dir/x/shadowlab.db", &s, &d), SL_E_IO);
    assert_null(s);
    assert_string_equal(d.file, "/nonexistent-sl-dir/x/shadowlab.db");
    assert_non_null(strstr(d.msg, "unable to open"));
}

/* issue 15: one writer per store; a second writer (here the same process on
 * another descriptor, which flock treats alike) is refused, naming the pid;
 * a reader is not. */
static void store_one_writer_at_a_time(void **st)
{
    struct fx *x = *st;
    struct tmp t = x->t;
    struct sl_diag d;
    struct sl_store *a = NULL, *b = NULL, *r = NULL;
    assert_int_equal(sl_store_open(t.db, &a, &d), SL_OK);
    assert_int_equal(sl_store_open(t.db, &b, &d), SL_E_IO);
    assert_null(b);
    char want[64];
    snprintf(want, sizeof want, "in use by another run (pid %ld,", (long)getpid());
    assert_non_null(strstr(d.msg, want));
    assert_int_equal(sl_store_open_existing(t.db, &r, &d), SL_OK);
    sl_store_close(r);
    sl_store_close(a);
    assert_int_equal(sl_store_open(t.db, &b, &d), SL_OK);   /* released on close */
    sl_store_close(b);
}

/* issue 37: a clean close leaves no lock file; the removal does not let two
 * writers in. A late writer that opened the old lock file just before the
 * holder removed it can flock it once the holder is gone (simulated here by
 * hand): sl_storefile_lock_current says that lock is on a file no longer at
 * the path, which is why sl_storefile_lock takes it again; the writers that
 * go through sl_storefile_lock still exclude each other. */
static void store_lock_file_removed_on_close(void **st)
{
    struct fx *x = *st;
    struct tmp t = x->t;
    struct sl_diag d;
    char lock[200];
    snprintf(lock, sizeof lock, "%s.lock", t.db);
    struct sl_store *a = NULL, *b = NULL, *c = NULL;
    assert_int_equal(sl_store_open(t.db, &a, &d), SL_OK);
    assert_int_equal(access(lock, F_OK), 0);
    int late = open(lock, O_RDWR);   /* a second writer, between its open and its flock */
    assert_true(late >= 0);
    sl_store_close(a);
    assert_int_not_equal(access(lock, F_OK), 0);   /* removed by the clean close */
    assert_int_equal(flock(late, LOCK_EX | LOCK_NB), 0);   /* the old file: free now */
    assert_int_equal(sl_storefile_lock_current(late, lock), 0);   /* ... and not the lock any more */
    assert_int_equal(sl_store_open(t.db, &b, &d), SL_OK);   /* a new lock file, not blocked by the old */
    assert_int_equal(access(lock, F_OK), 0);
    assert_int_equal(sl_store_open(t.db, &c, &d), SL_E_IO);   /* and it excludes the next writer */
    assert_non_null(strstr(d.msg, "in use by another run"));
    int fd = -1;
    char lp[4200];
    assert_int_equal(sl_storefile_lock(t.db, &fd, lp, sizeof lp, &d), SL_E_IO);
    assert_int_equal(fd, -1);
    close(late);
    sl_store_close(b);
    assert_int_not_equal(access(lock, F_OK), 0);
    /* a lock file left by a killed writer is locked again, and removed after */
    int stale = open(lock, O_RDWR | O_CREAT, 0644);
    assert_true(stale >= 0);
    close(stale);
    assert_int_equal(sl_store_open(t.db, &b, &d), SL_OK);
    sl_store_close(b);
    assert_int_not_equal(access(lock, F_OK), 0);
}

/* issue 15: a run that failed after cells went into the store keeps the
 * staged overlays the store points at; an empty staging folder goes. */
static void store_failed_run_keeps_staged_overlays(void **st)
{
    (void)st;
    char root[64];
    snprintf(root, sizeof root, "/tmp/sl_stage_XXXXXX");
    assert_non_null(mkdtemp(root));
    struct sl_config *c = calloc(1, sizeof *c);
    assert_non_null(c);
    snprintf(c->name, sizeof c->name, "study");
    c->overlays = 1;
    struct sl_out_dirs o;
    memset(&o, 0, sizeof o);
    struct sl_diag d;
    assert_int_equal(sl_out_stage_begin(c, root, &o, &d), SL_OK);
    char stage[1100], png[1300];
    snprintf(stage, sizeof stage, "%s", o.stage);
    sl_out_stage_drop(&o);
    assert_int_not_equal(access(stage, F_OK), 0);   /* nothing in it: removed */
    assert_int_equal(sl_out_stage_begin(c, root, &o, &d), SL_OK);
    snprintf(png, sizeof png, "%s/cell.png", o.overlays);
    FILE *f = fopen(png, "w");
    assert_non_null(f);
    fclose(f);
    sl_out_stage_drop(&o);
    assert_int_equal(access(png, F_OK), 0);   /* kept for the next --resume */
    unlink(png);
    char sub[1200];
    snprintf(sub, sizeof sub, "%s/overlays", stage);
    rmdir(sub);
    rmdir(stage);
    rmdir(root);
    free(c);
}

/* A case with its fixture: cmocka's per-case setup and teardown
 * (setup_func, teardown_func of the CMUnitTest) on the SL_CASE entry that
 * ctest lists (tests/CMakeLists.txt reads the literal case macro of each entry). */
static struct CMUnitTest fx_case(struct CMUnitTest c, CMFixtureFunction setup)
{
    c.setup_func = setup;
    c.teardown_func = fx_teardown;
    return c;
}
#define SL_FX(setup, c) fx_case((struct CMUnitTest)c, setup)

int main(int argc, char **argv)
{
    const struct CMUnitTest tests[] = {
        SL_FX(fx_store, SL_CASE(store, round_trip)),
        SL_FX(fx_store, SL_CASE(store, soft_cell)),
        SL_FX(fx_run, SL_CASE(store, has_cell_matches_key_and_hash)),
        SL_FX(fx_store, SL_CASE(store, latest_run_wins)),
        SL_FX(fx_run, SL_CASE(store, failed_put_leaves_no_cell)),
        SL_FX(fx_run, SL_CASE(store, figure_names_checked)),
        SL_FX(fx_run, SL_CASE(store, refused_last_row_rolls_back)),
        SL_FX(fx_run, SL_CASE(store, killed_writer_leaves_whole_cells)),
        SL_FX(fx_store, SL_CASE(store, unknown_run_is_refused)),
        SL_FX(fx_temp, SL_CASE(store, refuses_non_database)),
        SL_FX(fx_temp, SL_CASE(store, refuses_other_version)),
        SL_FX(fx_temp, SL_CASE(store, new_file_is_current_version_wal)),
        SL_CASE(store, missing_folder_is_an_error),
        SL_FX(fx_store, SL_CASE(store, key_stored_once)),
        SL_FX(fx_store, SL_CASE(store, digest_finds_changed_figure)),
        SL_FX(fx_temp, SL_CASE(store, lock_follows_links)),
        SL_FX(fx_temp, SL_CASE(store, one_writer_at_a_time)),
        SL_FX(fx_temp, SL_CASE(store, lock_file_removed_on_close)),
        SL_CASE(store, failed_run_keeps_staged_overlays),
    };
    return sl_run_group(argc, argv, "store", tests, NULL, NULL);
}
