/*
 * gputime::* — GPU time (GL_TIME_ELAPSED queries, glctx.h) of the G-buffer
 * and the shadow-map layers: present and positive for a cell that renders,
 * 0 for the layers of a cell that reads none (raytrace), never above the
 * wall time of the same passes (the query sits inside the wall clock's
 * bracket, on llvmpipe and on a GPU alike), written to costs.csv and
 * round-tripped by the store. Runs under whichever backend SHADOWLAB_GL
 * names (CI runs it under both).
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>
#include "sl_test.h"
#include "config.h"
#include "outputs.h"
#include "run.h"
#include "store.h"

static const char *const CONFIG =
    "name: gputime\n"
    "scenes:\n"
    "  - {scene: primitives, viewpoints: [side]}\n"
    "viewports: [{width: 256, height: 256}]\n"
    "map_sizes: [256]\n"
    "contours: [2]\n"
    "methods:\n"
    "  - {label: nsm, method: nsm, self_shadow: front_faces}\n"
    "  - {label: bgsm, method: bgsm}\n"
    "  - {label: raytrace, method: raytrace}\n"
    "outputs: {tables: true, overlays: false}\n"
    "repetitions: {warmup: 1, runs: 3}\n";

/* The value of column `name` in costs.csv's row whose label is `label`. */
static double csv_value(const char *path, const char *label, const char *name)
{
    FILE *f = fopen(path, "r");
    assert_non_null(f);
    char line[4096];
    assert_non_null(fgets(line, sizeof line, f));
    int col = -1, lcol = -1, i = 0;
    for (char *save = NULL, *t = strtok_r(line, ",\n", &save); t; t = strtok_r(NULL, ",\n", &save), i++) {
        if (!strcmp(t, name))
            col = i;
        if (!strcmp(t, "label"))
            lcol = i;
    }
    assert_true(col >= 0 && lcol >= 0);
    double v = NAN;
    while (fgets(line, sizeof line, f)) {
        char *cells[64];
        int n = 0;
        for (char *p = line; n < 64;) {
            cells[n++] = p;
            p = strpbrk(p, ",\n");
            if (!p)
                break;
            *p++ = '\0';
        }
        if (n > col && n > lcol && !strcmp(cells[lcol], label))
            v = strtod(cells[col], NULL);
    }
    fclose(f);
    return v;
}

/* x as costs.csv writes it (%.3f), read back */
static double as_written(double x)
{
    char b[64];
    snprintf(b, sizeof b, "%.3f", x);
    return strtod(b, NULL);
}

static void gputime_cells(void **st)
{
    (void)st;
    struct sl_config c;
    sl_test_config("gputime.yaml", CONFIG, &c);
    char db[400];
    snprintf(db, sizeof db, "%s/s.db", sl_test_dir);
    struct sl_run_opts o = {.out_root = sl_test_dir, .write_files = 1, .store = db, .cache_dir = ""};
    struct sl_run_result r;
    struct sl_diag d;
    enum sl_err e = sl_run(&c, &o, &r, &d);
    if (e)
        fprintf(stderr, "%s\n", d.msg);
    assert_int_equal(e, SL_OK);
    assert_int_equal(r.ncells, 3);
    struct sl_cell_record rec[3];
    char csv[400];
    snprintf(csv, sizeof csv, "%s/gputime/costs.csv", sl_test_dir);
    for (int i = 0; i < 3; i++) {
        sl_out_record(&c, &r.cells[i], &rec[i]);
        const struct sl_cell_record *k = &rec[i];
        int rt = !strcmp(k->label, "raytrace");
        printf("gputime::cells %s: G-buffer wall %.3f ms, GPU %.3f ms; layers wall %.3f ms, GPU %.3f ms\n",
               k->label, k->ms_gbuffer_render, k->ms_gpu_gbuffer, k->ms_map_render, k->ms_gpu_map);
        /* every cell's view has a G-buffer pass */
        assert_true(k->ms_gpu_gbuffer > 0.0);
        assert_true(k->ms_gpu_gbuffer <= k->ms_gbuffer_render);
        if (rt) {
            assert_true(k->ms_map_render == 0.0);
            assert_true(k->ms_gpu_map == 0.0);
        } else {
            assert_true(k->ms_gpu_map > 0.0);
            assert_true(k->ms_gpu_map <= k->ms_map_render);
        }
        /* costs.csv carries them, written %.3f: the very text of the
         * value so written (a bound of half a step, 0.0005, fails on a time
         * of exactly x.xxx5 ms, where the decimal step and the binary
         * values round apart) */
        assert_true(csv_value(csv, k->label, "ms_gpu_gbuffer") == as_written(k->ms_gpu_gbuffer));
        assert_true(csv_value(csv, k->label, "ms_gpu_map") == as_written(k->ms_gpu_map));
    }
    /* the store gives them back exactly */
    struct sl_store *s = NULL;
    assert_int_equal(sl_store_open_existing(db, &s, &d), SL_OK);
    struct sl_cell_record *got = NULL;
    int n = 0;
    assert_int_equal(sl_store_query(s, NULL, &got, &n, &d), SL_OK);
    assert_int_equal(n, 3);
    for (int i = 0; i < n; i++)
        for (int j = 0; j < 3; j++)
            if (!strcmp(got[i].label, rec[j].label)) {
                assert_true(got[i].ms_gpu_gbuffer == rec[j].ms_gpu_gbuffer);
                assert_true(got[i].ms_gpu_map == rec[j].ms_gpu_map);
            }
    free(got);
    sl_store_close(s);
    sl_run_result_free(&r);
    sl_config_free(&c);
}

int main(int argc, char **argv)
{
    const struct CMUnitTest tests[] = {
        SL_CASE(gputime, cells),
    };
    return sl_run_group(argc, argv, "gputime", tests, sl_test_setup, sl_test_teardown);
}
