/*
 * ovwriter::* — overlay sheets written by the run's worker thread
 * (harness/results/ovwriter.h): the same bytes as a cell writing them itself, a
 * worker's write error still fails the run with the image error naming the
 * file, every sheet in the folder when it is renamed into place (an
 * interrupted run too), and the queue's bound and sticky error on their own.
 */
#include <dirent.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include <cmocka.h>
#include "sl_test.h"
#include "config.h"
#include "image.h"
#include "ovwriter.h"
#include "run.h"

/* Hard and soft sheets: Primitives/side (hundreds of wrong pixels: insets)
 * with NSM and coherence (uncertain pixels), two map sizes; and Curtis's box
 * under its area light (the heat-map sheet, and a hard method's verdicts
 * scored as a visible fraction). */
static const char *const hard_cfg =
    "scenes: [{scene: primitives, viewpoints: [side, with]}]\n"
    "viewports: [{width: 256, height: 192}]\nmap_sizes: [256, 512]\ncontours: [2, 4]\n"
    "methods:\n  - {label: nsm, method: nsm, self_shadow: front_faces}\n"
    "  - {label: coh, method: coherence, texels: 9}\n"
    "outputs: {tables: false, overlays: true, overlay_contour: 2}\n";
static const char *const soft_cfg =
    "scenes: [{scene: curtis_box}]\nviewports: [{width: 128, height: 96}]\nmap_sizes: [512]\n"
    "methods:\n  - {label: point, method: hard_point}\n  - {label: mc, method: soft_mc, grid: 2}\n"
    "area_samples: 4\noutputs: {tables: false, overlays: true}\n";

static void load(const char *name, const char *body, struct sl_config *c)
{
    char text[2048];
    snprintf(text, sizeof text, "name: %s\n%s", name, body);
    sl_test_config(name, text, c);
}

static unsigned char *slurp(const char *path, long *n)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    fseek(f, 0, SEEK_END);
    *n = ftell(f);
    fseek(f, 0, SEEK_SET);
    unsigned char *b = malloc((size_t)*n + 1);
    if (b && fread(b, 1, (size_t)*n, f) != (size_t)*n) {
        free(b);
        b = NULL;
    }
    fclose(f);
    return b;
}

/* The files of dir (names into names[], up to max), sorted; returns how many. */
static int list(const char *dir, char names[][256], int max)
{
    DIR *dp = opendir(dir);
    int n = 0;
    if (!dp)
        return -1;
    struct dirent *e;
    while ((e = readdir(dp)))
        if (e->d_name[0] != '.' && n < max)
            snprintf(names[n++], 256, "%s", e->d_name);
    closedir(dp);
    qsort(names, (size_t)n, 256, (int (*)(const void *, const void *))strcmp);
    return n;
}

static void run_into(const char *name, const char *body, const char *sub, int inl, struct sl_run_result *r)
{
    struct sl_config c;
    load(name, body, &c);
    char root[1200];
    snprintf(root, sizeof root, "%s/%s", sl_test_dir, sub);
    struct sl_run_opts o = {.out_root = root, .write_files = 1, .store = "", .cache_dir = "", .overlay_inline = inl};
    struct sl_diag d;
    enum sl_err e = sl_run(&c, &o, r, &d);
    if (e)
        fprintf(stderr, "%s: %s\n", d.file, d.msg);
    assert_int_equal(e, SL_OK);
    sl_config_free(&c);
}

/* The worker writes the very bytes a cell writes itself, one sheet per cell,
 * no temporary left over. */
static void same_bytes(const char *name, const char *body, int cells)
{
    struct sl_run_result a, b;
    run_into(name, body, "inline", 1, &a);
    run_into(name, body, "worker", 0, &b);
    assert_int_equal(a.ncells, cells);
    assert_int_equal(b.ncells, cells);
    char da[1400], db[1400];
    snprintf(da, sizeof da, "%s/inline/%s/overlays", sl_test_dir, name);
    snprintf(db, sizeof db, "%s/worker/%s/overlays", sl_test_dir, name);
    static char na[64][256], nb[64][256];
    int n = list(da, na, 64), m = list(db, nb, 64);
    assert_int_equal(n, cells);
    assert_int_equal(m, cells);
    for (int i = 0; i < n; i++) {
        assert_string_equal(na[i], nb[i]);
        assert_null(strstr(nb[i], ".tmp"));
        char pa[1700], pb[1700];
        snprintf(pa, sizeof pa, "%s/%s", da, na[i]);
        snprintf(pb, sizeof pb, "%s/%s", db, nb[i]);
        long la = 0, lb = 0;
        unsigned char *x = slurp(pa, &la), *y = slurp(pb, &lb);
        assert_non_null(x);
        assert_non_null(y);
        assert_true(la > 1000);
        assert_int_equal(la, lb);
        assert_memory_equal(x, y, (size_t)la);
        free(x);
        free(y);
    }
    sl_run_result_free(&a);
    sl_run_result_free(&b);
}

static void ovwriter_same_bytes(void **st)
{
    (void)st;
    same_bytes("ovhard", hard_cfg, 2 * 2 * 2);
}

static void ovwriter_same_bytes_soft(void **st)
{
    (void)st;
    same_bytes("ovsoft", soft_cfg, 2 * 2);   /* two viewpoints, two labels */
}

/* After the first cell: replace the staging folder's overlays/ with a file
 * (a full disk, a folder gone), or ask the run to stop. */
struct sabotage {
    const char *root, *name;
    int stop_after;             /* 1: set *stop after the first cell; 0: break overlays/ */
    volatile int stop;
    int events;
};

static void on_event(const struct sl_run_event *ev, void *user)
{
    struct sabotage *s = user;
    if (ev->kind != SL_EVENT_PROGRESS || s->events++ > 0)
        return;
    if (s->stop_after) {
        s->stop = 1;
        return;
    }
    char dir[1400], cmd[1500];
    snprintf(dir, sizeof dir, "%s/.%s.partial-%ld/overlays", s->root, s->name, (long)getpid());
    snprintf(cmd, sizeof cmd, "rm -rf '%s' && echo x > '%s'", dir, dir);
    assert_int_equal(system(cmd), 0);
}

/* A sheet the worker cannot write fails the run as a cell's own failed write
 * does: the image error, the file named, nothing renamed into place. */
static void ovwriter_write_error(void **st)
{
    (void)st;
    for (int inl = 0; inl < 2; inl++) {
        struct sl_config c;
        load("overr", hard_cfg, &c);
        char root[1200];
        snprintf(root, sizeof root, "%s/err%d", sl_test_dir, inl);
        struct sabotage s = {.root = root, .name = "overr"};
        struct sl_run_opts o = {.out_root = root, .write_files = 1, .store = "", .cache_dir = "",
                                .on_event = on_event, .user = &s, .overlay_inline = inl};
        struct sl_run_result r;
        struct sl_diag d;
        memset(&d, 0, sizeof d);
        enum sl_err e = sl_run(&c, &o, &r, &d);
        char where[1400];
        snprintf(where, sizeof where, "%s/.overr.partial-%ld/overlays/primitives-", root, (long)getpid());
        printf("ovwriter::write_error (%s): %s: %s\n", inl ? "inline" : "worker", d.file, d.msg);
        assert_int_equal(e, SL_E_IMAGE);
        assert_int_equal(strncmp(d.file, where, strlen(where)), 0);
        assert_non_null(strstr(d.file, ".png"));
        assert_non_null(strstr(d.msg, "write failed"));
        char fin[1300];
        struct stat sb;
        snprintf(fin, sizeof fin, "%s/overr", root);
        assert_int_not_equal(stat(fin, &sb), 0);   /* nothing half-written under the final name */
        sl_run_result_free(&r);
        sl_config_free(&c);
    }
}

/* Stopped after the first cell (SIGINT's flag): the folder renamed into place
 * holds that cell's sheet, whole (it reads back at the frame's size or
 * larger). */
static void ovwriter_complete_at_rename(void **st)
{
    (void)st;
    struct sl_config c;
    load("ovstop", hard_cfg, &c);
    char root[1200];
    snprintf(root, sizeof root, "%s/stop", sl_test_dir);
    struct sabotage s = {.root = root, .name = "ovstop", .stop_after = 1};
    struct sl_run_opts o = {.out_root = root, .write_files = 1, .store = "", .cache_dir = "",
                            .on_event = on_event, .user = &s, .stop = &s.stop};
    struct sl_run_result r;
    struct sl_diag d;
    assert_int_equal(sl_run(&c, &o, &r, &d), SL_OK);
    assert_true(r.interrupted);
    assert_int_equal(r.ncells, 1);
    char dir[1400];
    snprintf(dir, sizeof dir, "%s/ovstop/overlays", root);
    static char names[8][256];
    assert_int_equal(list(dir, names, 8), 1);
    char p[1700];
    snprintf(p, sizeof p, "%s/%s", dir, names[0]);
    int w, h;
    unsigned char *rgb = NULL;
    assert_int_equal(sl_image_read_rgb8(p, &w, &h, &rgb, &d), SL_OK);
    assert_true(w >= 64 && h >= 64);
    free(rgb);
    sl_run_result_free(&r);
    sl_config_free(&c);
}

/* The writer alone: at most depth slots out at once (a third acquire waits
 * until a sheet is written), and a failed write is returned, with its file,
 * by every later acquire and wait. */
static void ovwriter_bound_and_error(void **st)
{
    (void)st;
    struct sl_ovw *w;
    struct sl_diag d;
    assert_int_equal(sl_ovw_open(2, &w, &d), SL_OK);
    struct sl_ovw_slot *a, *b, *c;
    assert_int_equal(sl_ovw_acquire(w, 32, 16, &a, &d), SL_OK);
    assert_int_equal(sl_ovw_acquire(w, 32, 16, &b, &d), SL_OK);
    assert_ptr_not_equal(a, b);
    struct sl_image_sheet sh;
    memset(&sh, 0, sizeof sh);
    sh.w = 32;
    sh.h = 16;
    memset(a->rgb, 90, 3 * 32 * 16);
    sh.rgb = a->rgb;
    char good[1200], bad[1200];
    snprintf(good, sizeof good, "%s/ovw-good.png", sl_test_dir);
    snprintf(bad, sizeof bad, "%s/no-such-folder/ovw-bad.png", sl_test_dir);
    assert_int_equal(sl_ovw_submit(w, a, good, &sh, &d), SL_OK);
    /* b is still out: the next acquire gets a's slot back only once written */
    assert_int_equal(sl_ovw_acquire(w, 32, 16, &c, &d), SL_OK);
    assert_ptr_equal(c, a);
    struct stat sb;
    assert_int_equal(stat(good, &sb), 0);
    sl_ovw_release(w, c);
    memset(b->rgb, 200, 3 * 32 * 16);
    sh.rgb = b->rgb;
    assert_int_equal(sl_ovw_submit(w, b, bad, &sh, &d), SL_OK);   /* queued: not failed yet */
    memset(&d, 0, sizeof d);
    assert_int_equal(sl_ovw_wait(w, &d), SL_E_IMAGE);
    assert_string_equal(d.file, bad);
    memset(&d, 0, sizeof d);
    assert_int_equal(sl_ovw_acquire(w, 32, 16, &c, &d), SL_E_IMAGE);
    assert_null(c);
    assert_string_equal(d.file, bad);
    int written;
    double ms, cpu;
    sl_ovw_stats(w, &written, &ms, &cpu);
    assert_int_equal(written, 1);
    sl_ovw_close(w);
    sl_ovw_close(NULL);
}

int main(int argc, char **argv)
{
    const struct CMUnitTest tests[] = {
        SL_CASE(ovwriter, same_bytes),
        SL_CASE(ovwriter, same_bytes_soft),
        SL_CASE(ovwriter, write_error),
        SL_CASE(ovwriter, complete_at_rename),
        SL_CASE(ovwriter, bound_and_error),
    };
    return sl_run_group(argc, argv, "ovwriter", tests, sl_test_setup, sl_test_teardown);
}
