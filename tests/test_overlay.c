/*
 * overlay::* — the overlay sheet and the EXR layers as a reader sees them:
 * every wrong or uncertain pixel shows its error colour in the 1:1 view
 * (nothing drawn over it: neither the contour nor the insets' marks), the
 * insets hold the windows with most wrong pixels and show them pixel for
 * pixel, the crop to a small scene, the EXR read by oiiotool, and the
 * sheet's PNG read chunk by chunk with zlib.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <cmocka.h>
#include <zlib.h>
#include "sl_test.h"
#include "config.h"
#include "contour.h"
#include "image.h"
#include "method.h"
#include "overlay.h"
#include "run.h"
#include "view.h"

static int write_file(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    if (!f)
        return 0;
    fputs(text, f);
    return fclose(f) == 0;
}

/* One run shared by the cases: Primitives/side at 512² with a 256² map
 * (hundreds of wrong pixels), NSM and texel coherence (which leaves pixels
 * uncertain), overlays and EXR layers on. */
static struct sl_run_result run;
static int ran;

static void run_once(void)
{
    if (ran)
        return;
    char path[1200];
    snprintf(path, sizeof path, "%s/ov.yaml", sl_test_dir);
    assert_true(write_file(path,
        "name: ov\nscenes: [{scene: primitives, viewpoints: [side]}]\n"
        "viewports: [{width: 512, height: 512}]\nmap_sizes: [256]\ncontours: [2, 4, 6]\n"
        "methods:\n  - {label: nsm, method: nsm, self_shadow: front_faces}\n"
        "  - {label: coh, method: coherence, texels: 9}\n"
        "outputs: {tables: false, overlays: true, overlay_contour: 2, exr: true}\n"));
    struct sl_config c;
    struct sl_diag d;
    assert_int_equal(sl_config_load(path, &c, &d), SL_OK);
    struct sl_run_opts o = {.out_root = sl_test_dir, .write_files = 1, .store = "", .cache_dir = ""};
    enum sl_err e = sl_run(&c, &o, &run, &d);
    if (e)
        fprintf(stderr, "%s\n", d.msg);
    assert_int_equal(e, SL_OK);
    assert_int_equal(run.ncells, 2);
    ran = 1;
    sl_config_free(&c);
}

struct layers {
    int w, h;
    unsigned *truth, *verdict, *contour;
};

static void read_layers(const char *label, struct layers *L)
{
    char p[1400];
    struct sl_diag d;
    int w, h;
    snprintf(p, sizeof p, "%s/ov/exr/primitives-side-512x512-256-%s.exr", sl_test_dir, label);
    assert_int_equal(sl_image_read_layer(p, "truth", &L->w, &L->h, &L->truth, &d), SL_OK);
    assert_int_equal(sl_image_read_layer(p, "verdict", &w, &h, &L->verdict, &d), SL_OK);
    assert_int_equal(sl_image_read_layer(p, "contour", &w, &h, &L->contour, &d), SL_OK);
}

static void free_layers(struct layers *L)
{
    free(L->truth);
    free(L->verdict);
    free(L->contour);
}

/* The class a pixel must show, as overlay.h defines it; -1 when right. */
static int expected_class(const struct layers *L, size_t i)
{
    int inside = sl_in_contour((uint8_t)L->contour[i], 2);
    if (L->verdict[i] == SL_V_LIT && L->truth[i] != SL_T_LIT && L->truth[i] != SL_T_BACKGROUND)
        return inside ? SL_OV_LIT_WRONG : SL_OV_WRONG_OUTSIDE;
    if (L->verdict[i] == SL_V_SHADOW && L->truth[i] == SL_T_LIT)
        return inside ? SL_OV_SHADOW_WRONG : SL_OV_WRONG_OUTSIDE;
    if (L->verdict[i] == SL_V_UNCERTAIN)
        return SL_OV_UNCERTAIN;
    return -1;
}

static int is_error_colour(const unsigned char *p)
{
    for (int k = 0; k < SL_OV_UNCERTAIN + 1; k++)
        if (!memcmp(p, sl_overlay_colour[k], 3))
            return 1;
    return 0;
}

struct sheet {
    int w, h;
    unsigned char *rgb;   /* top-down */
    int view[6];          /* x y w h (frame, top-down) X Y (in the sheet) */
    int ninsets, inset[3][7];
};

static void read_sheet(const char *label, struct sheet *S)
{
    char p[1400], a[200];
    struct sl_diag d;
    snprintf(p, sizeof p, "%s/ov/overlays/primitives-side-512x512-256-%s.png", sl_test_dir, label);
    assert_int_equal(sl_image_read_rgb8(p, &S->w, &S->h, &S->rgb, &d), SL_OK);
    assert_int_equal(sl_image_read_attr(p, "shadowlab:view", a, sizeof a, &d), SL_OK);
    assert_int_equal(sscanf(a, "%d %d %d %d %d %d", &S->view[0], &S->view[1], &S->view[2], &S->view[3],
                            &S->view[4], &S->view[5]), 6);
    S->ninsets = 0;
    for (int k = 0; k < 3; k++) {
        char name[32];
        snprintf(name, sizeof name, "shadowlab:inset%d", k + 1);
        if (sl_image_read_attr(p, name, a, sizeof a, &d) != SL_OK)
            break;
        int *b = S->inset[k];
        assert_int_equal(sscanf(a, "%d %d %d %d %d %d %d", b, b + 1, b + 2, b + 3, b + 4, b + 5, b + 6), 7);
        S->ninsets++;
    }
}

static const unsigned char *at(const struct sheet *S, int x, int y)
{
    assert_true(x >= 0 && x < S->w && y >= 0 && y < S->h);
    return S->rgb + 3 * ((size_t)y * (size_t)S->w + (size_t)x);
}

/* Wrong (or uncertain, when want_uncertain) pixels in the top-down window
 * x, y, s x s of the frame. */
static uint64_t count_window(const struct layers *L, int x, int y, int s, int want_uncertain)
{
    uint64_t n = 0;
    for (int j = y; j < y + s; j++)
        for (int i = x; i < x + s; i++) {
            size_t k = (size_t)(L->h - 1 - j) * (size_t)L->w + (size_t)i;
            int c = expected_class(L, k);
            n += want_uncertain ? c == SL_OV_UNCERTAIN : c >= 0 && c != SL_OV_UNCERTAIN;
        }
    return n;
}

/* The most wrong pixels of any s x s window overlapping none of the first
 * `taken` insets, by sliding column sums (not overlay.c's summed-area table). */
static uint64_t best_window(const struct layers *L, int s, const struct sheet *S, int taken, int want_uncertain)
{
    int W = L->w, H = L->h;
    uint64_t best = 0;
    unsigned *col = calloc((size_t)W, sizeof *col);
    unsigned char *m = malloc((size_t)W * (size_t)H);
    assert_non_null(col);
    assert_non_null(m);
    for (int j = 0; j < H; j++)   /* top-down mask */
        for (int i = 0; i < W; i++) {
            int c = expected_class(L, (size_t)(H - 1 - j) * (size_t)W + (size_t)i);
            m[(size_t)j * (size_t)W + (size_t)i] = want_uncertain ? c == SL_OV_UNCERTAIN : c >= 0 && c != SL_OV_UNCERTAIN;
        }
    for (int j = 0; j < s; j++)
        for (int i = 0; i < W; i++)
            col[i] += m[(size_t)j * (size_t)W + (size_t)i];
    for (int y = 0; y + s <= H; y++) {
        if (y > 0)
            for (int i = 0; i < W; i++)
                col[i] += m[(size_t)(y + s - 1) * (size_t)W + (size_t)i] - m[(size_t)(y - 1) * (size_t)W + (size_t)i];
        int64_t run = 0;
        for (int i = 0; i < s; i++)
            run += col[i];
        for (int x = 0; x + s <= W; x++) {
            if (x > 0)
                run += (int64_t)col[x + s - 1] - (int64_t)col[x - 1];
            int clash = 0;
            for (int k = 0; k < taken; k++) {
                const int *b = S->inset[k];
                clash |= x < b[0] + b[2] && b[0] < x + s && y < b[1] + b[3] && b[1] < y + s;
            }
            if (!clash && (uint64_t)run > best)
                best = (uint64_t)run;
        }
    }
    free(col);
    free(m);
    return best;
}

static void check_cell(const char *label, const struct sl_cell *cell)
{
    struct layers L;
    struct sheet S;
    read_layers(label, &L);
    read_sheet(label, &S);
    const int *v = S.view;
    /* every wrong and every uncertain pixel lies in the view and shows its
     * class's colour there; no other pixel of the view shows one */
    uint64_t errors = 0, coloured = 0, uncertain = 0;
    for (int y = 0; y < L.h; y++)
        for (int x = 0; x < L.w; x++) {
            size_t i = (size_t)(L.h - 1 - y) * (size_t)L.w + (size_t)x;
            int c = expected_class(&L, i);
            int in_view = x >= v[0] && x < v[0] + v[2] && y >= v[1] && y < v[1] + v[3];
            if (c >= 0) {
                assert_true(in_view);
                errors++;
                uncertain += c == SL_OV_UNCERTAIN;
                assert_memory_equal(at(&S, v[4] + x - v[0], v[5] + y - v[1]), sl_overlay_colour[c], 3);
            }
            if (in_view)
                coloured += is_error_colour(at(&S, v[4] + x - v[0], v[5] + y - v[1]));
        }
    assert_int_equal(coloured, errors);
    assert_int_equal(errors - uncertain, cell->fig.wrong_image);
    printf("overlay %s: %llu wrong, %llu uncertain, all shown; %d insets\n", label,
           (unsigned long long)(errors - uncertain), (unsigned long long)uncertain, S.ninsets);

    /* the insets: the windows with most wrong pixels (uncertain ones when
     * none is wrong), greedily, and each shows its window at zoom z pixel for
     * pixel: every error pixel of the window z x z times, in its colour */
    int want_u = errors == uncertain;
    assert_true(S.ninsets >= 1);
    for (int k = 0; k < S.ninsets; k++) {
        const int *b = S.inset[k];
        int s = b[2], z = b[6];
        assert_int_equal(b[3], s);
        uint64_t n = count_window(&L, b[0], b[1], s, want_u);
        assert_true(n > 0);
        assert_int_equal(n, best_window(&L, s, &S, k, want_u));
        uint64_t shown = 0;
        for (int j = 0; j < s * z; j++)
            for (int i = 0; i < s * z; i++) {
                size_t fi = (size_t)(L.h - 1 - (b[1] + j / z)) * (size_t)L.w + (size_t)(b[0] + i / z);
                int c = expected_class(&L, fi);
                const unsigned char *p = at(&S, b[4] + i, b[5] + j);
                if (c >= 0)
                    assert_memory_equal(p, sl_overlay_colour[c], 3);
                else   /* elsewhere the same pixel as the view's (unmarked there: compare off the marks) */
                    assert_false(is_error_colour(p));
                shown += c >= 0 && (want_u ? c == SL_OV_UNCERTAIN : c != SL_OV_UNCERTAIN);
            }
        assert_int_equal(shown, n * (uint64_t)z * (uint64_t)z);
        /* marked on the view: the 2-px white box just outside the window,
         * wherever it does not fall on an error pixel */
        int x0 = b[0] - 2, y0 = b[1] - 2;
        if (x0 >= v[0] && y0 >= v[1]) {
            size_t fi = (size_t)(L.h - 1 - y0) * (size_t)L.w + (size_t)x0;
            if (expected_class(&L, fi) < 0) {
                const unsigned char *p = at(&S, v[4] + x0 - v[0], v[5] + y0 - v[1]);
                assert_true(p[0] == 255 && p[1] == 255 && p[2] == 255);
            }
        }
    }
    free(S.rgb);
    free_layers(&L);
}

static void overlay_errors_on_top(void **st)
{
    (void)st;
    run_once();
    check_cell("nsm", &run.cells[0]);
    check_cell("coh", &run.cells[1]);
}

/* oiiotool reads the layers as they are: non-zero maxima for truth (3,
 * shadowed), verdict (2 or 3) and error; the header names the codes. */
static void overlay_exr_stats(void **st)
{
    (void)st;
    run_once();
    char cmd[1600], line[512];
    snprintf(cmd, sizeof cmd,
             "oiiotool %s/ov/exr/primitives-side-512x512-256-nsm.exr --ch truth,verdict,error,contour "
             "--printstats 2>&1", sl_test_dir);
    FILE *p = popen(cmd, "r");
    assert_non_null(p);
    float mx[4] = {-1, -1, -1, -1};
    int got = 0;
    while (fgets(line, sizeof line, p))
        if (strstr(line, "Stats Max:"))
            got = sscanf(strstr(line, ":") + 1, "%f %f %f %f", &mx[0], &mx[1], &mx[2], &mx[3]);
    assert_int_equal(pclose(p), 0);
    assert_int_equal(got, 4);
    assert_true(mx[0] == SL_T_SHADOW);
    assert_true(mx[1] == SL_V_SHADOW);
    assert_true(mx[2] >= 1.0f);   /* NSM has wrong pixels at 256² */
    assert_true(mx[3] == 3.0f);   /* bands 1-3: the 2, 4 and 6-px contours */
    char a[400];
    struct sl_diag d;
    snprintf(cmd, sizeof cmd, "%s/ov/exr/primitives-side-512x512-256-nsm.exr", sl_test_dir);
    assert_int_equal(sl_image_read_attr(cmd, "shadowlab:verdict", a, sizeof a, &d), SL_OK);
    assert_non_null(strstr(a, "1 lit"));
    assert_int_equal(sl_image_read_attr(cmd, "shadowlab:how", a, sizeof a, &d), SL_OK);
    assert_non_null(strstr(a, "2 map"));
    /* the integer codes beside them, equal */
    unsigned *h, *u;
    int w, hh;
    assert_int_equal(sl_image_read_layer(cmd, "verdict", &w, &hh, &h, &d), SL_OK);
    assert_int_equal(sl_image_read_layer(cmd, "code.verdict", &w, &hh, &u, &d), SL_OK);
    assert_memory_equal(h, u, (size_t)w * (size_t)hh * sizeof *h);
    free(h);
    free(u);
}

/* The crop: a scene filling little of the frame is shown by its bounding
 * box, padded; one filling most of it is not cropped. */
static void overlay_crop_small_scene(void **st)
{
    (void)st;
    enum { W = 100, H = 80 };
    static uint8_t truth[W * H];
    struct sl_view v = {.w = W, .h = H, .truth = truth};
    struct sl_ov_box b;
    memset(truth, SL_T_BACKGROUND, sizeof truth);
    assert_int_equal(sl_overlay_crop(&v, NULL, NULL, 4, &b), 0);   /* nothing: the whole frame */
    assert_true(b.x == 0 && b.y == 0 && b.w == W && b.h == H);
    for (int y = 30; y < 40; y++)
        for (int x = 50; x < 70; x++)
            truth[y * W + x] = SL_T_LIT;
    assert_int_equal(sl_overlay_crop(&v, NULL, NULL, 4, &b), 1);
    assert_int_equal(b.x, 46);
    assert_int_equal(b.y, 26);
    assert_int_equal(b.w, 28);
    assert_int_equal(b.h, 18);
    truth[0] = truth[W * H - 1] = SL_T_SHADOW;   /* two far corners: the box spans the frame */
    assert_int_equal(sl_overlay_crop(&v, NULL, NULL, 4, &b), 0);
    assert_true(b.x == 0 && b.w == W);
    /* a ground filling the frame: the contours' and errors' box, padded by
     * 1/16 of the shorter side (5 px) when that is more than pad */
    static uint8_t band[W * H], err[W * H];
    memset(truth, SL_T_LIT, sizeof truth);
    assert_int_equal(sl_overlay_crop(&v, band, err, 4, &b), 0);   /* no contour, no error */
    for (int x = 20; x < 30; x++)
        band[40 * W + x] = 1;
    err[50 * W + 35] = 255;
    assert_int_equal(sl_overlay_crop(&v, band, err, 4, &b), 1);
    assert_int_equal(b.x, 15);
    assert_int_equal(b.y, 35);
    assert_int_equal(b.w, 26);
    assert_int_equal(b.h, 21);
    assert_int_equal(sl_overlay_crop(&v, NULL, NULL, 4, &b), 0);   /* without bands: the ground's box */
}

/* The greedy windows, the plain way: every window counted from scratch, in
 * the order sl_overlay_insets promises (most errors; ties the lowest, then
 * leftmost; none overlapping one chosen before; none holding no error). */
static int insets_brute(int w, int h, const uint8_t *err, int s, int n, struct sl_ov_box *out, uint64_t *count)
{
    int got = 0;
    for (; got < n; got++) {
        uint64_t best = 0;
        int bx = -1, by = -1;
        for (int y = 0; y + s <= h; y++)
            for (int x = 0; x + s <= w; x++) {
                int clash = 0;
                for (int k = 0; k < got; k++)
                    clash |= x < out[k].x + out[k].w && out[k].x < x + s && y < out[k].y + out[k].h && out[k].y < y + s;
                if (clash)
                    continue;
                uint64_t c = 0;
                for (int j = 0; j < s; j++)
                    for (int i = 0; i < s; i++)
                        c += err[(size_t)(y + j) * (size_t)w + (size_t)(x + i)] != 0;
                if (c > best) {
                    best = c;
                    bx = x;
                    by = y;
                }
            }
        if (bx < 0)
            break;
        out[got] = (struct sl_ov_box){bx, by, s, s};
        count[got] = best;
    }
    return got;
}

/* The windows over masks of every shape (none, one pixel at each corner,
 * clusters, scattered noise, ties, a full frame) are the plain search's. */
static void overlay_insets_exact(void **st)
{
    (void)st;
    enum { W = 61, H = 47 };
    static uint8_t err[W * H];
    unsigned seed = 12345;
    for (int trial = 0; trial < 120; trial++) {
        memset(err, 0, sizeof err);
        int kind = trial % 6;
        if (kind == 1)   /* one pixel, at a corner or an edge */
            err[(trial / 6 % 4 < 2 ? 0 : H - 1) * W + (trial / 6 % 2 ? W - 1 : 0)] = 255;
        for (int i = 0; kind == 2 && i < 3; i++) {   /* clusters */
            seed = seed * 1103515245u + 12345u;
            int cx = (int)(seed >> 8) % W, cy = (int)(seed >> 20) % H;
            for (int y = cy - 3; y <= cy + 3; y++)
                for (int x = cx - 4; x <= cx + 4; x++)
                    if (x >= 0 && y >= 0 && x < W && y < H)
                        err[y * W + x] = 255;
        }
        for (int i = 0; (kind == 3 || kind == 4) && i < W * H; i++) {   /* noise, sparse or dense */
            seed = seed * 1103515245u + 12345u;
            err[i] = (seed >> 16) % (kind == 3 ? 97u : 3u) == 0 ? 255 : 0;
        }
        if (kind == 5)
            memset(err, 255, sizeof err);
        /* up to 8 windows: several chosen ones cut the same row (each row
         * is scanned between the chosen windows' intervals) */
        int s = 4 + trial % 9, n = 1 + trial % 8;
        struct sl_ov_box a[8], b[8];
        uint64_t ca[8], cb[8];
        int na = sl_overlay_insets(W, H, err, s, n, a, ca), nb = insets_brute(W, H, err, s, n, b, cb);
        assert_int_equal(na, nb);
        for (int k = 0; k < na; k++) {
            assert_int_equal(a[k].x, b[k].x);
            assert_int_equal(a[k].y, b[k].y);
            assert_int_equal(a[k].w, s);
            assert_int_equal(ca[k], cb[k]);
        }
        if (kind == 0)
            assert_int_equal(na, 0);
    }
}

/* The sheet's text is OpenImageIO's render_text, pixel for pixel: the sheet
 * draws each glyph once per process and blits it (issue 20), so its title
 * band must equal oiiotool --text of the same string on white. Kerning-prone
 * pairs, digits, punctuation and UTF-8; two sizes (12 px at 480², 22 at
 * 1056²), then 480² again, drawn from the glyphs already cached. */
static void overlay_text_as_oiio(void **st)
{
    (void)st;
    const char *font = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
    if (access(font, R_OK) != 0)
        skip();   /* the sheet then resolves another font: nothing to compare with */
    static const char *const title = "Tj fj AV WA ff 0123456789 wrong/said: x4, map 2048 (\xc3\xa9\xc2\xb5\xc2\xb2)";
    const int sizes[3] = {480, 1056, 480};
    for (int k = 0; k < 3; k++) {
        const int W = sizes[k], H = sizes[k];
        unsigned char *rgb = malloc((size_t)W * (size_t)H * 3);
        assert_non_null(rgb);
        memset(rgb, 90, (size_t)W * (size_t)H * 3);
        struct sl_image_sheet sh;
        memset(&sh, 0, sizeof sh);
        sh.w = W;
        sh.h = H;
        sh.rgb = rgb;
        snprintf(sh.title, sizeof sh.title, "%s", title);
        char path[1200], ref[1200], cmd[4000], a[200];
        snprintf(path, sizeof path, "%s/text%d.png", sl_test_dir, k);
        snprintf(ref, sizeof ref, "%s/text%d-ref.png", sl_test_dir, k);
        struct sl_diag d;
        assert_int_equal(sl_image_write_sheet(path, &sh, &d), SL_OK);
        free(rgb);
        assert_int_equal(sl_image_read_attr(path, "shadowlab:text", a, sizeof a, &d), SL_OK);
        assert_string_equal(a, "1");
        int vx, vy, vw, vh, M, top;
        assert_int_equal(sl_image_read_attr(path, "shadowlab:view", a, sizeof a, &d), SL_OK);
        assert_int_equal(sscanf(a, "%d %d %d %d %d %d", &vx, &vy, &vw, &vh, &M, &top), 6);
        int fs = (vh > H ? vh : H) / 48;
        fs = fs < 12 ? 12 : fs > 22 ? 22 : fs;
        assert_int_equal(M, fs / 2 + 4);
        unsigned char *got, *want;
        int w, h, w2, h2;
        assert_int_equal(sl_image_read_rgb8(path, &w, &h, &got, &d), SL_OK);
        snprintf(cmd, sizeof cmd,
                 "oiiotool --pattern constant:color=1,1,1 %dx%d 3 --text:x=%d:y=%d:font=%s:size=%d:color=0,0,0 "
                 "'%s' -d uint8 -o %s",
                 w, top, M, M + fs, font, fs, title, ref);
        assert_int_equal(system(cmd), 0);
        assert_int_equal(sl_image_read_rgb8(ref, &w2, &h2, &want, &d), SL_OK);
        assert_int_equal(w2, w);
        assert_int_equal(h2, top);
        /* the band above the view: white and the title, nothing else */
        size_t n = (size_t)w * (size_t)top * 3, ink = 0;
        for (size_t i = 0; i < n; i++)
            ink += got[i] < 128;
        assert_true(ink > 100);
        assert_memory_equal(got, want, n);
        free(got);
        free(want);
    }
}

/* The sheets' glyphs come from FreeType itself, called as render_text
 * calls it, so that writing a sheet loads no OpenImageIO (issue 20): every
 * glyph a sheet can draw at every size a sheet uses (12-22 px) is the same
 * as OpenImageIO's render_text draws it: placement, advance, and every
 * coverage value. A sheet can draw code points 0-127 only, '\n' apart (a
 * new line): its strings are decoded as OpenImageIO 2.4 decodes them, a
 * multi-byte character as its last byte's low six bits (image_sheet.cpp;
 * overlay::text_as_oiio draws such a title). Sizes and characters in a
 * scrambled order: FreeType's faces are kept per size and reused,
 * OpenImageIO's opened afresh each time. */
static void overlay_glyphs_as_oiio(void **st)
{
    (void)st;
    if (access("/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf", R_OK) != 0)
        skip();   /* both take OpenImageIO's font search then: nothing to compare */
    uint32_t cps[128];
    int ncp = 0;
    for (uint32_t c = 0; c < 128; c++)
        if (c != '\n')
            cps[ncp++] = c;
    int compared = 0, ink = 0;
    for (int si = 0; si < 11; si++) {
        const int fs = 12 + (si * 7) % 11;   /* 12, 19, 15, 22, ... every size once */
        for (int k = 0; k < ncp; k++) {
            const uint32_t c = cps[(k * 37 + si) % ncp];   /* 37 is prime to 127 */
            struct sl_image_glyph a, b;
            struct sl_diag d;
            int ra = sl_image_glyph(0, fs, c, &a, &d), rb = sl_image_glyph(1, fs, c, &b, &d);
            assert_int_equal(ra, rb);
            assert_int_equal(ra, 1);
            assert_int_equal(a.left, b.left);
            assert_int_equal(a.top, b.top);
            assert_int_equal(a.w, b.w);
            assert_int_equal(a.h, b.h);
            assert_int_equal(a.adv, b.adv);
            assert_true(a.adv > 0 || c < 32 || c == 127);   /* the controls: .notdef or nothing */
            assert_int_equal(a.a == NULL, b.a == NULL);
            if (a.a) {
                assert_memory_equal(a.a, b.a, (size_t)a.w * (size_t)a.h * sizeof(float));
                for (int i = 0; i < a.w * a.h; i++)
                    ink += a.a[i] > 0.5f;
            }
            free(a.a);
            free(b.a);
            compared++;
        }
    }
    assert_int_equal(compared, 11 * ncp);
    assert_true(ink > 10000);
}

/* The lit colours kept per view (sl_overlay_build_shaded) give the very
 * bytes and counts of sl_overlay_build, cell after cell, and are drawn
 * afresh when the view, the bands, the thickness or the light change:
 * were a stale shade used, the n.l greys would differ. */
static uint32_t lcg(uint32_t *s)
{
    *s = *s * 1664525u + 1013904223u;
    return *s >> 8;
}

static float unit(uint32_t *s) { return (float)(lcg(s) & 0xffff) / 65535.0f; }

static void random_view(struct sl_view *v, int w, int h, uint32_t seed, int spot)
{
    size_t n = (size_t)w * (size_t)h;
    memset(v, 0, sizeof *v);
    v->w = w;
    v->h = h;
    v->serial = seed;
    v->pos = malloc(n * 3 * sizeof(float));
    v->nrm = malloc(n * 3 * sizeof(float));
    v->truth = malloc(n);
    v->cls = malloc(n);
    v->outside = spot ? malloc(n) : NULL;
    assert_true(v->pos && v->nrm && v->truth && v->cls && (!spot || v->outside));
    for (size_t i = 0; i < n; i++) {
        for (int k = 0; k < 3; k++) {
            v->pos[3 * i + k] = 40.0f * unit(&seed) - 20.0f;
            v->nrm[3 * i + k] = 2.0f * unit(&seed) - 1.0f;
        }
        v->truth[i] = (uint8_t)(lcg(&seed) % 4);
        v->cls[i] = v->truth[i] >= SL_T_LIT ? SL_C_PFL : v->truth[i] == SL_T_PNFL ? SL_C_PNFL : SL_C_BACKGROUND;
        if (spot)
            v->outside[i] = v->truth[i] == SL_T_PNFL && lcg(&seed) % 2;
    }
}

static void free_view(struct sl_view *v)
{
    free(v->pos); free(v->nrm); free(v->truth); free(v->cls); free(v->outside);
}

static void overlay_shaded_same_bytes(void **st)
{
    (void)st;
    enum { W = 37, H = 23, N = W * H };
    struct sl_view views[2];
    random_view(&views[0], W, H, 7u, 0);
    random_view(&views[1], W, H, 8u, 1);
    uint8_t v8[N], band[N], rgb0[3 * N], rgb1[3 * N], err0[N], err1[N];
    struct sl_verdicts vd;
    memset(&vd, 0, sizeof vd);
    vd.v = v8;
    vd.w = W;
    vd.h = H;
    const float dir[3] = {0.6f, -0.45f, 0.35f}, pos[2][3] = {{3, 40, -2}, {-5, 30, 8}};
    struct sl_overlay_shade sh;
    memset(&sh, 0, sizeof sh);
    uint32_t seed = 99;
    int redrawn = 0;
    /* each round changes one thing, or nothing: view, light position (-1:
     * none), thickness, new bands */
    static const struct { int view, light, th, bands; } rounds[] = {
        {0, -1, 2, 1}, {0, -1, 2, 0}, {0, -1, 4, 0}, {0, 0, 4, 0}, {0, 1, 4, 0}, {0, 1, 4, 1},
        {0, 1, 4, 0},  {1, 1, 4, 0},  {1, 1, 2, 0},  {1, -1, 2, 0}, {1, -1, 2, 1}, {1, -1, 2, 0},
    };
    for (size_t round = 0; round < sizeof rounds / sizeof rounds[0]; round++) {
        const struct sl_view *v = &views[rounds[round].view];
        const float *lp = rounds[round].light < 0 ? NULL : pos[rounds[round].light];
        int th = rounds[round].th;
        if (rounds[round].bands)
            for (int i = 0; i < N; i++)
                band[i] = (uint8_t)(lcg(&seed) % 8);
        for (int i = 0; i < N; i++)
            v8[i] = (uint8_t)(1 + lcg(&seed) % 3);
        uint64_t c0[SL_OV_CLASSES], c1[SL_OV_CLASSES];
        uint64_t before = sh.serial;
        sl_overlay_build(v, dir, lp, &vd, band, th, rgb0, err0, c0);
        sl_overlay_build_shaded(&sh, v, dir, lp, &vd, band, th, rgb1, err1, c1);
        redrawn += before != sh.serial;
        assert_memory_equal(rgb0, rgb1, sizeof rgb0);
        assert_memory_equal(err0, err1, sizeof err0);
        assert_memory_equal(c0, c1, sizeof c0);
        assert_true(c0[SL_OV_CONTOUR] > 0);
    }
    assert_int_equal(redrawn, 2);   /* serial changes: the first view, then the second */
    sl_overlay_shade_free(&sh);
    free_view(&views[0]);
    free_view(&views[1]);
}

/* The overlay's colours and counts as first written (one branchy loop per
 * pixel, before issue 20 made it two passes of codes): the reference
 * overlay::build_as_reference compares sl_overlay_build with. */
static void ref_right(const struct sl_view *v, const float l0[3], const float *lp, int lit, int tint, size_t i,
                      uint8_t *o)
{
    float ndl = 0.0f;
    if (lit) {
        const float *nn = v->nrm + 3 * i;
        ndl = -(nn[0] * l0[0] + nn[1] * l0[1] + nn[2] * l0[2]);
        if (lp) {
            const float *p = v->pos + 3 * i;
            float l[3] = {lp[0] - p[0], lp[1] - p[1], lp[2] - p[2]};
            float len = sqrtf(l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);
            ndl = len > 0.0f ? (nn[0] * l[0] + nn[1] * l[1] + nn[2] * l[2]) / len : 0.0f;
        }
    }
    float g = 255.0f * (0.12f + (ndl > 0.0f ? 0.5f * ndl : 0.0f));
    if (tint) {
        const uint8_t *c = sl_overlay_colour[SL_OV_CONTOUR];
        for (int j = 0; j < 3; j++)
            o[j] = (uint8_t)(0.65f * g + 0.35f * (float)c[j] + 0.5f);
        return;
    }
    o[0] = o[1] = o[2] = (uint8_t)(g + 0.5f);
}

static void ref_build(const struct sl_view *v, const float l0[3], const float *lp, const uint8_t *vd,
                      const uint8_t *band, int th, uint8_t *rgb, uint8_t *err, uint64_t cnt[SL_OV_CLASSES])
{
    memset(cnt, 0, SL_OV_CLASSES * sizeof *cnt);
    for (size_t i = 0; i < (size_t)v->w * (size_t)v->h; i++) {
        uint8_t *o = rgb + 3 * i, t = v->truth[i], verdict = vd[i];
        err[i] = 0;
        if (t == SL_T_BACKGROUND) {
            o[0] = o[1] = o[2] = 0;
            continue;
        }
        int inside = sl_in_contour(band[i], th), truth_lit = t == SL_T_LIT, k = -1;
        if (verdict == SL_V_LIT && !truth_lit)
            k = inside ? SL_OV_LIT_WRONG : SL_OV_WRONG_OUTSIDE;
        else if (verdict == SL_V_SHADOW && truth_lit)
            k = inside ? SL_OV_SHADOW_WRONG : SL_OV_WRONG_OUTSIDE;
        else if (verdict == SL_V_UNCERTAIN)
            k = SL_OV_UNCERTAIN;
        if (k >= 0) {
            memcpy(o, sl_overlay_colour[k], 3);
            err[i] = 255;
            cnt[k]++;
            continue;
        }
        if (v->outside && v->outside[i]) {
            size_t x = i % (size_t)v->w, y = i / (size_t)v->w;
            o[0] = o[1] = o[2] = (x + y) % 8 < 2 ? sl_overlay_colour[SL_OV_OUTSIDE_CONE][0] : 12;
            cnt[SL_OV_OUTSIDE_CONE]++;
            continue;
        }
        int tint = inside && th > 0;
        cnt[SL_OV_CONTOUR] += (uint64_t)tint;
        ref_right(v, l0, lp, verdict == SL_V_LIT, tint, i, o);
    }
}

/* sl_overlay_build and sl_overlay_build_shaded give the reference's bytes,
 * error mask and counts: frames of one pixel, of less than a chunk, and of
 * several chunks with a partial last one (97 x 131); every verdict byte the
 * type holds that a method writes, and 0 and 4 (neither lit, shadowed nor
 * uncertain: drawn right, dark); thicknesses 0 (the whole image) to 7 and
 * bands 0-9; a spot's cone or none; directional and positional light; NULL
 * err and count. */
static void overlay_build_as_reference(void **st)
{
    (void)st;
    static const int dims[][2] = {{1, 1}, {37, 23}, {97, 131}, {64, 64}};
    const float dir[3] = {0.6f, -0.45f, 0.35f}, pos[3] = {3, 40, -2};
    uint32_t seed = 4242;
    int drawn_lit = 0, drawn_err = 0, drawn_cone = 0, drawn_tint = 0;
    for (size_t di = 0; di < sizeof dims / sizeof dims[0]; di++)
        for (int spot = 0; spot < 2; spot++)
            for (int th = 0; th <= 7; th++) {
                const int W = dims[di][0], H = dims[di][1];
                const size_t N = (size_t)W * (size_t)H;
                struct sl_view v;
                random_view(&v, W, H, seed++, spot);
                uint8_t *v8 = malloc(N), *band = malloc(N), *rgb0 = malloc(3 * N), *rgb1 = malloc(3 * N),
                        *rgb2 = malloc(3 * N), *err0 = malloc(N), *err1 = malloc(N), *err2 = malloc(N);
                assert_true(v8 && band && rgb0 && rgb1 && rgb2 && err0 && err1 && err2);
                for (size_t i = 0; i < N; i++) {
                    v8[i] = (uint8_t)(lcg(&seed) % 5);
                    band[i] = (uint8_t)(lcg(&seed) % 10);
                }
                if (di == 3)   /* runs: a row of one truth and verdict, as in a render */
                    for (size_t i = 0; i < N; i++) {
                        v.truth[i] = v.truth[i - i % (size_t)W];
                        v8[i] = v8[i - i % (size_t)W];
                    }
                struct sl_verdicts vd;
                memset(&vd, 0, sizeof vd);
                vd.v = v8;
                vd.w = W;
                vd.h = H;
                const float *lp = th % 2 ? pos : NULL;
                uint64_t c0[SL_OV_CLASSES], c1[SL_OV_CLASSES], c2[SL_OV_CLASSES];
                ref_build(&v, dir, lp, v8, band, th, rgb0, err0, c0);
                sl_overlay_build(&v, dir, lp, &vd, band, th, rgb1, err1, c1);
                struct sl_overlay_shade sh;
                memset(&sh, 0, sizeof sh);
                sl_overlay_build_shaded(&sh, &v, dir, lp, &vd, band, th, rgb2, err2, c2);
                assert_memory_equal(rgb0, rgb1, 3 * N);
                assert_memory_equal(err0, err1, N);
                assert_memory_equal(c0, c1, sizeof c0);
                assert_memory_equal(rgb0, rgb2, 3 * N);
                assert_memory_equal(err0, err2, N);
                assert_memory_equal(c0, c2, sizeof c0);
                /* without the optional outputs: the same pixels */
                memset(rgb1, 0xa5, 3 * N);
                sl_overlay_build_shaded(&sh, &v, dir, lp, &vd, band, th, rgb1, NULL, NULL);
                assert_memory_equal(rgb0, rgb1, 3 * N);
                for (size_t i = 0; i < N; i++)
                    drawn_lit += v8[i] == SL_V_LIT && v.truth[i] == SL_T_LIT;
                drawn_err += c0[SL_OV_LIT_WRONG] > 0 && c0[SL_OV_SHADOW_WRONG] > 0 && c0[SL_OV_UNCERTAIN] > 0;
                drawn_cone += c0[SL_OV_OUTSIDE_CONE] > 0;
                drawn_tint += c0[SL_OV_CONTOUR] > 0;
                sl_overlay_shade_free(&sh);
                free_view(&v);
                free(v8); free(band); free(rgb0); free(rgb1); free(rgb2); free(err0); free(err1); free(err2);
            }
    /* the inputs reached every kind of pixel */
    assert_true(drawn_lit > 1000);
    assert_true(drawn_err > 10);
    assert_true(drawn_cone > 10);
    assert_true(drawn_tint > 10);
}

static uint32_t be32(const unsigned char *p)
{
    return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3];
}

/* The sheet is a standard PNG, read here with zlib alone (not the encoder's
 * library): the signature, IHDR first, every chunk's CRC-32 right, one
 * zlib stream over the IDATs that inflates to exactly one filter byte and
 * 3 * w bytes a row, rows equal to what OpenImageIO decodes, IEND last; the
 * header's text chunks under the keys OpenImageIO wrote (Software,
 * Description, shadowlab:*, a caller's attribute) and read back by
 * OpenImageIO under its names (ImageDescription). */
static void overlay_png_chunks(void **st)
{
    (void)st;
    enum { W = 200, H = 150 };
    unsigned char *rgb = malloc((size_t)W * H * 3), *keep = calloc((size_t)W * H, 1);
    assert_non_null(rgb);
    assert_non_null(keep);
    for (int i = 0; i < W * H; i++) {   /* a gradient with an error square: every filter byte matters */
        rgb[3 * i] = (unsigned char)(i % W), rgb[3 * i + 1] = (unsigned char)(i / W), rgb[3 * i + 2] = 40;
        if (i % W >= 50 && i % W < 60 && i / W >= 70 && i / W < 80) {
            rgb[3 * i] = 213, rgb[3 * i + 1] = 94, rgb[3 * i + 2] = 0;
            keep[i] = 255;
        }
    }
    static const struct sl_image_attr extra[1] = {{"shadowlab:probe", "a b  c"}};
    struct sl_image_sheet sh;
    memset(&sh, 0, sizeof sh);
    sh.w = W, sh.h = H, sh.rgb = rgb, sh.keep = keep, sh.zoom = 4, sh.ninsets = 1;
    sh.inset[0][0] = 48, sh.inset[0][1] = 68, sh.inset[0][2] = sh.inset[0][3] = 16;
    snprintf(sh.inset_caption[0], sizeof sh.inset_caption[0], "1: 100 wrong");
    sh.nlegend = 1;
    memcpy(sh.legend_rgb[0], sl_overlay_colour[SL_OV_LIT_WRONG], 3);
    snprintf(sh.legend_text[0], sizeof sh.legend_text[0], "said lit, shadowed: 100");
    snprintf(sh.title, sizeof sh.title, "png/chunks  nsm  map 256  %dx%d", W, H);
    sh.nattrs = 1, sh.attrs = extra;
    char path[1200];
    snprintf(path, sizeof path, "%s/chunks.png", sl_test_dir);
    struct sl_diag d;
    assert_int_equal(sl_image_write_sheet(path, &sh, &d), SL_OK);
    free(rgb);
    free(keep);

    FILE *f = fopen(path, "rb");
    assert_non_null(f);
    static unsigned char b[1 << 22];
    size_t n = fread(b, 1, sizeof b, f);
    fclose(f);
    assert_true(n > 8 && n < sizeof b);
    static const unsigned char sig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    assert_memory_equal(b, sig, 8);
    static unsigned char z[1 << 22];
    size_t zn = 0, p = 8;
    int sw = 0, shh = 0, nchunks = 0, iend = 0, idat_run = 0, idat_runs = 0;
    char keys[2048] = "";
    while (p + 12 <= n && !iend) {
        uint32_t len = be32(b + p);
        assert_true(p + 12 + len <= n);
        const unsigned char *type = b + p + 4, *data = b + p + 8;
        uLong crc = crc32(0L, type, 4 + (uInt)len);
        assert_int_equal(crc, be32(data + len));
        if (nchunks++ == 0) {   /* IHDR: 8-bit RGB, deflate, adaptive filters, not interlaced */
            assert_memory_equal(type, "IHDR", 4);
            assert_int_equal(len, 13);
            sw = (int)be32(data), shh = (int)be32(data + 4);
            assert_int_equal(data[8], 8);
            assert_int_equal(data[9], 2);
            assert_int_equal(data[10] | data[11] | data[12], 0);
        }
        int is_idat = memcmp(type, "IDAT", 4) == 0;
        if (is_idat) {   /* IDATs: consecutive, one stream */
            assert_true(zn + len <= sizeof z);
            memcpy(z + zn, data, len);
            zn += len;
            idat_runs += !idat_run;
        }
        idat_run = is_idat;
        if (memcmp(type, "tEXt", 4) == 0) {
            size_t kl = strnlen((const char *)data, len);
            assert_true(kl >= 1 && kl <= 79 && kl < len + 1);
            strncat(keys, (const char *)data, kl);
            strcat(keys, ";");
        }
        iend = memcmp(type, "IEND", 4) == 0;
        p += 12 + len;
    }
    assert_true(iend);
    assert_int_equal(p, n);   /* nothing after IEND */
    assert_int_equal(idat_runs, 1);
    assert_string_equal(keys, "Software;Description;shadowlab:view;shadowlab:inset1;shadowlab:legend;"
                              "shadowlab:text;shadowlab:probe;");
    /* the pixels: inflate, undo each row's filter, compare with OpenImageIO's decoding */
    size_t rowb = (size_t)sw * 3, want = (rowb + 1) * (size_t)shh;
    unsigned char *raw = malloc(want + 1), *img = malloc(rowb * (size_t)shh);
    assert_non_null(raw);
    assert_non_null(img);
    uLongf got = (uLongf)(want + 1);
    assert_int_equal(uncompress(raw, &got, z, (uLong)zn), Z_OK);
    assert_int_equal(got, want);
    for (int y = 0; y < shh; y++) {
        const unsigned char *r = raw + (size_t)y * (rowb + 1);
        unsigned char *o = img + (size_t)y * rowb;
        const unsigned char *up = y ? o - rowb : NULL;
        assert_true(r[0] <= 4);
        for (size_t i = 0; i < rowb; i++) {
            int a = i >= 3 ? o[i - 3] : 0, u = up ? up[i] : 0, c = up && i >= 3 ? up[i - 3] : 0;
            int pa = abs(u - c), pb = abs(a - c), pc = abs(a + u - 2 * c);
            int pred = r[0] == 0 ? 0 : r[0] == 1 ? a : r[0] == 2 ? u : r[0] == 3 ? (a + u) / 2
                       : pa <= pb && pa <= pc ? a : pb <= pc ? u : c;
            o[i] = (unsigned char)(r[1 + i] + pred);
        }
    }
    int w, h;
    unsigned char *oi;
    assert_int_equal(sl_image_read_rgb8(path, &w, &h, &oi, &d), SL_OK);
    assert_int_equal(w, sw);
    assert_int_equal(h, shh);
    assert_memory_equal(img, oi, rowb * (size_t)shh);
    free(oi);
    free(raw);
    free(img);
    char a[256];
    assert_int_equal(sl_image_read_attr(path, "ImageDescription", a, sizeof a, &d), SL_OK);
    assert_string_equal(a, sh.title);
    assert_int_equal(sl_image_read_attr(path, "Software", a, sizeof a, &d), SL_OK);
    assert_int_equal(strncmp(a, "shadowlab ", 10), 0);
    assert_int_equal(sl_image_read_attr(path, "shadowlab:probe", a, sizeof a, &d), SL_OK);
    assert_string_equal(a, "a b  c");
    assert_int_equal(sl_image_read_attr(path, "shadowlab:legend", a, sizeof a, &d), SL_OK);
    assert_string_equal(a, "said lit, shadowed: 100");
}

int main(int argc, char **argv)
{
    const struct CMUnitTest tests[] = {
        SL_CASE(overlay, errors_on_top),
        SL_CASE(overlay, exr_stats),
        SL_CASE(overlay, crop_small_scene),
        SL_CASE(overlay, insets_exact),
        SL_CASE(overlay, text_as_oiio),
        SL_CASE(overlay, glyphs_as_oiio),
        SL_CASE(overlay, png_chunks),
        SL_CASE(overlay, shaded_same_bytes),
        SL_CASE(overlay, build_as_reference),
    };
    int rc = sl_run_group(argc, argv, "overlay", tests, sl_test_setup, sl_test_teardown);
    if (ran)
        sl_run_result_free(&run);
    return rc;
}
