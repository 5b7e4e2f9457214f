/*
 * bench::* — `shadowlab bench` in its quick mode (truth and layers on a small
 * scene, two repetitions): every row is there, with positive, finite
 * measurements, plain counterparts and counters, in the Markdown and the
 * CSV. No timing thresholds: a benchmark's verdicts depend on the machine.
 */
#include <dirent.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <cmocka.h>
#include "sl_test.h"
#include "bench.h"

static void bench_parse_stages(void **st)
{
    (void)st;
    unsigned bits = 0;
    struct sl_diag d;
    assert_int_equal(sl_bench_parse_stages("truth,layers", &bits, &d), SL_OK);
    assert_int_equal(bits, SL_BENCH_STAGE(TRUTH) | SL_BENCH_STAGE(LAYERS));
    assert_int_equal(sl_bench_parse_stages("morais", &bits, &d), SL_OK);
    assert_int_equal(bits, SL_BENCH_STAGE(MORAIS));
    assert_int_equal(sl_bench_parse_stages("truth,moderno,layers,morais", &bits, &d), SL_OK);
    assert_int_equal(bits, SL_BENCH_STAGE(TRUTH) | SL_BENCH_STAGE(MODERNO) | SL_BENCH_STAGE(LAYERS) |
                               SL_BENCH_STAGE(MORAIS));
    assert_int_equal(sl_bench_parse_stages("truth,moderno,layers,backends,morais,jobs,churn,techniques,startup,scoring,"
                                           "lightfit,bigmap,timing", &bits, &d), SL_OK);
    assert_int_equal(bits, SL_BENCH_ALL);
    assert_int_equal(sl_bench_parse_stages("timing", &bits, &d), SL_OK);
    assert_int_equal(bits, SL_BENCH_STAGE(TIMING));
    assert_int_equal(sl_bench_parse_stages("bigmap", &bits, &d), SL_OK);
    assert_int_equal(bits, SL_BENCH_STAGE(BIGMAP));
    assert_int_equal(sl_bench_parse_stages("scoring", &bits, &d), SL_OK);
    assert_int_equal(bits, SL_BENCH_STAGE(SCORING));
    assert_int_equal(sl_bench_parse_stages("startup", &bits, &d), SL_OK);
    assert_int_equal(bits, SL_BENCH_STAGE(STARTUP));
    assert_int_equal(sl_bench_parse_stages("jobs", &bits, &d), SL_OK);
    assert_int_equal(bits, SL_BENCH_STAGE(JOBS));
    assert_int_equal(sl_bench_parse_stages("churn", &bits, &d), SL_OK);
    assert_int_equal(bits, SL_BENCH_STAGE(CHURN));
    assert_int_equal(sl_bench_parse_stages("lightfit", &bits, &d), SL_OK);
    assert_int_equal(bits, SL_BENCH_STAGE(LIGHTFIT));
    assert_int_equal(sl_bench_parse_stages("techniques", &bits, &d), SL_OK);
    assert_int_equal(bits, SL_BENCH_STAGE(TECHNIQUES));
    assert_int_equal(sl_bench_parse_stages("truth,layer", &bits, &d), SL_E_USAGE);
    assert_non_null(strstr(d.msg, "'layer'"));
    /* every stage named in the message, in the order of SL_BENCH_STAGES */
    assert_non_null(strstr(d.msg, "(known: truth, layers, backends, moderno, morais, jobs, churn, techniques, "
                                  "startup, scoring, lightfit, bigmap, timing)"));
    assert_int_equal(sl_bench_parse_stages("", &bits, &d), SL_E_USAGE);
}

static char *slurp(const char *path)
{
    FILE *f = fopen(path, "rb");
    assert_non_null(f);
    static char buf[1 << 16];
    size_t n = fread(buf, 1, sizeof buf - 1, f);
    buf[n] = '\0';
    fclose(f);
    return buf;
}

/* sl_bench with o, its Markdown into sl_test_dir/mdname (o->out set here);
 * asserts it ran. Returns the Markdown's path in md (n bytes). */
static void run_bench(struct sl_bench_opts *o, const char *mdname, char *md, size_t n, struct sl_bench_result *r)
{
    snprintf(md, n, "%s/%s", sl_test_dir, mdname);
    FILE *out = fopen(md, "w");
    assert_non_null(out);
    o->out = out;
    struct sl_diag d;
    enum sl_err e = sl_bench(o, r, &d);
    fclose(out);
    if (e)
        fprintf(stderr, "bench: %s\n", d.msg);
    assert_int_equal(e, SL_OK);
}

static void bench_quick_mode_rows(void **st)
{
    (void)st;
    char md[300], csv[300];
    snprintf(csv, sizeof csv, "%s/bench.csv", sl_test_dir);
    struct sl_bench_opts o = {.stages = SL_BENCH_STAGE(TRUTH) | SL_BENCH_STAGE(LAYERS), .reps = 2,
                              .scene = "blocks", .width = 128, .height = 96, .map = 256, .csv = csv};
    struct sl_bench_result r;
    run_bench(&o, "bench.md", md, sizeof md, &r);

    /* truth (filtered trace, one thread's CPU; end to end, one thread's
     * CPU and wall), G-buffer, six layers, memory, the first context; no
     * study asked for */
    static const char *const want[] = {"depth_id 256²", "depth_id_back 256²", "bgsm 256²", "bgsm2 256²",
                                       "sgsm 256²", "sgsm_adj 256²"};
    /* then one trace row for each narrower packet width the CPU also runs
     * (bench_truth.c: 8 with isa=avx2, 4 with isa=sse4.2), none when
     * SHADOWLAB_EMBREE_CONFIG says how to trace */
    int extra = 0;
    while (3 + extra < r.nrows && strstr(r.rows[3 + extra].name, ", isa="))
        extra++;
    const char *env_isa = getenv("SHADOWLAB_EMBREE_CONFIG");
    if (env_isa && *env_isa)
        assert_int_equal(extra, 0);
    assert_true(extra <= 2);
    for (int i = 3; i < 3 + extra; i++) {
        const struct sl_bench_row *w = &r.rows[i];
        assert_string_equal(w->stage, "truth");
        assert_true(strstr(w->name, "packets of 8, isa=avx2") || strstr(w->name, "packets of 4, isa=sse4.2"));
        assert_true(isfinite(w->value) && w->value > 0 && isfinite(w->plain) && w->plain > 0);
        assert_int_equal(w->pass, w->ratio >= w->target);
    }
    assert_int_equal(r.nrows, 3 + extra + 1 + 6 + 1 + 1);
    assert_string_equal(r.rows[0].stage, "truth");
    assert_string_equal(r.rows[1].stage, "truth");
    assert_string_equal(r.rows[1].name, "truth, 1 thread, CPU time");
    assert_string_equal(r.rows[2].stage, "truth");
    assert_non_null(strstr(r.rows[2].name, "truth, wall, "));
    for (int i = 0; i < 3; i++) {
        /* each against its plain counterpart and its target */
        const struct sl_bench_row *w = &r.rows[i];
        assert_true(isfinite(w->value) && w->value > 0 && isfinite(w->plain) && w->plain > 0);
        assert_true(fabs(w->ratio - w->value / w->plain) < 1e-9 * w->ratio);
        assert_int_equal(w->pass, w->ratio >= w->target);
    }
    /* drop the second and third truth rows and the narrower widths' rows:
     * the rest keep the places they had */
    memmove(&r.rows[1], &r.rows[3 + extra], sizeof r.rows[0] * (size_t)(r.nrows - 3 - extra));
    r.nrows -= 2 + extra;
    assert_string_equal(r.rows[1].stage, "gbuffer");
    assert_string_equal(r.rows[1].name, "gbuffer 128x96");
    for (int i = 0; i < 6; i++) {
        assert_string_equal(r.rows[2 + i].stage, "layer");
        assert_string_equal(r.rows[2 + i].name, want[i]);
    }
    assert_string_equal(r.rows[8].stage, "memory");
    assert_string_equal(r.rows[9].stage, "context");
    assert_non_null(strstr(r.rows[9].name, "first GL context ("));
    for (int i = 0; i < r.nrows; i++) {
        const struct sl_bench_row *w = &r.rows[i];
        assert_true(isfinite(w->value) && w->value > 0);
        if (i < 8) {
            /* measured against a plain counterpart */
            assert_true(isfinite(w->plain) && w->plain > 0);
            assert_true(fabs(w->ratio - w->value / w->plain) < 1e-9 * w->ratio);
            assert_int_equal(w->pass, w->cmp == SL_BENCH_AT_LEAST ? w->ratio >= w->target : w->ratio <= w->target);
        }
        if (i >= 1 && i < 8) {
            assert_true(w->fragments > 0 && w->plain_fragments > 0);
            assert_string_equal(w->unit, "ms");
        }
    }
    /* the plain raster and the unculled passes run the same fragments;
     * only the conservative layers have a geometry shader */
    assert_int_equal(r.rows[1].fragments, r.rows[1].plain_fragments);
    assert_int_equal(r.rows[2].fragments, r.rows[2].plain_fragments);
    assert_int_equal(r.rows[2].gs_prims, 0);
    for (int i = 4; i < 8; i++)
        assert_true(r.rows[i].gs_prims >= 38);   /* blocks: 38 triangles, each emitted at least once */
    assert_true(r.rows[8].value < 1e6);          /* MiB */

    const char *text = slurp(md);
    assert_non_null(strstr(text, "git_sha: "));
    assert_non_null(strstr(text, "gl_renderer: "));
    assert_non_null(strstr(text, "isa: "));
    assert_non_null(strstr(text, "## Summary"));
    /* the truth row names the packet width it traced with: the device's
     * native one (4 under SSE4.2, 8 under AVX2, CI's platform matrix) */
    const char *row = strstr(text, "| truth | truth blocks, 1 viewpoints, 128x96, packets of ");
    assert_non_null(row);
    int width = atoi(row + strlen("| truth | truth blocks, 1 viewpoints, 128x96, packets of "));
    assert_true(width == 4 || width == 8 || width == 16);
    const char *forced = getenv("SHADOWLAB_EMBREE_CONFIG");
    if (forced && strcmp(forced, "isa=sse4.2") == 0)
        assert_int_equal(width, 4);
    if (forced && strcmp(forced, "isa=avx2") == 0)
        assert_int_equal(width, 8);
    assert_non_null(strstr(text, "| layer | sgsm_adj 256² | ms |"));
    assert_non_null(strstr(text, "| memory | peak RSS after all stages | MiB |"));
    text = slurp(csv);
    int lines = 0;
    for (const char *p = text; *p; p++)
        lines += *p == '\n';
    assert_int_equal(lines, 1 + r.nrows + 2 + extra);   /* + the truth rows dropped above */
    assert_non_null(strstr(text, ",layer,\"bgsm2 256²\",ms,"));
}

/* The threads of this process (/proc/self/task). */
static int threads_here(void)
{
    DIR *dir = opendir("/proc/self/task");
    assert_non_null(dir);
    int n = 0;
    for (struct dirent *e; (e = readdir(dir));)
        n += e->d_name[0] != '.';
    closedir(dir);
    return n;
}

/* The study stages, each in a process of its own (bench_study.c): the
 * rows of Moderno without and with files and of Morais, in that order, the
 * sections of each, none run in the bench's own process when it had one
 * thread (a plain build's test process; a sanitized build links Mesa and
 * Embree at start, whose threads rule a fork out: there each section says
 * it ran in the bench's process); and a study that fails in its process
 * fails the bench with its own message. */
static void bench_studies_in_children(void **st)
{
    (void)st;
    struct sl_config c;
    sl_test_config("tiny.yaml",
                   "name: tiny\nscenes:\n  - {scene: blocks}\nviewports: [{width: 64, height: 48}]\n"
                   "map_sizes: [64]\ncontours: [2]\nmethods:\n  - {label: nsm, method: nsm}\n"
                   "outputs: {tables: true, overlays: true, overlay_contour: 2}\n",
                   &c);
    char cfg[300], md[300];
    snprintf(cfg, sizeof cfg, "%s/tiny.yaml", sl_test_dir);
    struct sl_bench_opts o = {.stages = SL_BENCH_STAGE(MODERNO) | SL_BENCH_STAGE(MORAIS), .reps = 1,
                              .moderno = cfg, .morais = cfg};
    struct sl_bench_result r;
    const int single = threads_here() == 1;
    run_bench(&o, "studies.md", md, sizeof md, &r);
    static const char *const want[] = {
        "moderno-2011, ", "moderno-2011, CPU (user+sys)", "moderno-2011, exactness violations",
        "moderno-2011 overlays on, ", "moderno-2011 overlays on, CPU (user+sys)",
        "moderno-2011 overlays on, exactness violations", "morais-2015, ", "morais-2015, CPU (user+sys)",
        "morais-2015, minor page faults", "morais-2015, peak RSS of the process so far",
        "morais-2015, exactness violations"};
    assert_int_equal(r.nrows, 11 + 2);
    for (int i = 0; i < 11; i++) {
        assert_string_equal(r.rows[i].stage, "study");
        assert_true(!strncmp(r.rows[i].name, want[i], strlen(want[i])));
        if (strstr(want[i], "violations"))
            assert_true(r.rows[i].value == 0.0);
        else
            assert_true(r.rows[i].value > 0.0);   /* measured in the child: its own time, faults, RSS */
    }
    assert_string_equal(r.rows[11].stage, "memory");
    const char *text = slurp(md);
    int sections = 0;
    for (const char *p = text; (p = strstr(p, "## Study tiny")); p++)
        sections++;
    assert_int_equal(sections, 3);
    if (single)
        assert_null(strstr(text, "ran in the bench's own process"));
    else
        assert_non_null(strstr(text, "ran in the bench's own process: it had threads already"));
    assert_non_null(strstr(text, "Overlays and tables written (1 sheets"));

    /* a study that fails in its process */
    char missing[320];
    snprintf(missing, sizeof missing, "%s/no-such.yaml", sl_test_dir);
    o.moderno = o.morais = missing;
    o.stages = SL_BENCH_STAGE(MORAIS);
    FILE *out = fopen(md, "w");
    assert_non_null(out);
    o.out = out;
    struct sl_diag d;
    memset(&d, 0, sizeof d);
    enum sl_err e = sl_bench(&o, NULL, &d);
    fclose(out);
    assert_int_not_equal(e, SL_OK);
    assert_non_null(strstr(d.file, "no-such.yaml"));
    sl_config_free(&c);
}

/* The churn stage: NSM's layer at S and 2S kept and made afresh, three
 * rows (both ratios 2S / S, CPU kept / fresh), each against its plain
 * counterpart, with the sizes in their names and the table printed. */
static void bench_churn_rows(void **st)
{
    (void)st;
    char md[300];
    struct sl_bench_opts o = {.stages = SL_BENCH_STAGE(CHURN), .reps = 3, .scene = "blocks", .width = 64,
                              .height = 64, .map = 256};
    struct sl_bench_result r;
    run_bench(&o, "churn.md", md, sizeof md, &r);
    assert_int_equal(r.nrows, 3 + 2);   /* + memory, context */
    assert_string_equal(r.rows[0].name, "NSM layer 512² / 256², kept");
    assert_string_equal(r.rows[1].name, "NSM layer 512² / 256², fresh (as before)");
    assert_string_equal(r.rows[2].name, "NSM layer 512², CPU kept / fresh");
    for (int i = 0; i < 3; i++) {
        assert_string_equal(r.rows[i].stage, "churn");
        assert_true(r.rows[i].plain > 0 && isfinite(r.rows[i].value));
        assert_true(fabs(r.rows[i].ratio - r.rows[i].value / r.rows[i].plain) < 1e-9 * r.rows[i].ratio);
    }
    const char *text = slurp(md);
    assert_non_null(strstr(text, "| 256² | kept |"));
    assert_non_null(strstr(text, "| 512² | fresh |"));
}

/* The techniques stage on a tiny size: two rows per setting of each
 * package of the source tree (its map against the plain map, its lookup
 * against the plain lookup), pcf at kernel 3 and 5 and nsm_glsl among them,
 * each against its plain counterpart and its target; the table printed,
 * post passes (when a package has them) on rows of their own. */
static void bench_techniques_rows(void **st)
{
    (void)st;
    char md[300];
    struct sl_bench_opts o = {.stages = SL_BENCH_STAGE(TECHNIQUES), .reps = 2, .scene = "blocks", .width = 64,
                              .height = 48, .map = 128};
    struct sl_bench_result r;
    run_bench(&o, "techniques.md", md, sizeof md, &r);
    int ntech = r.nrows - 2;   /* + memory, context */
    assert_true(ntech >= 6 && ntech % 2 == 0);
    assert_string_equal(r.rows[ntech].stage, "memory");
    assert_string_equal(r.rows[ntech + 1].stage, "context");
    static const char *const want[] = {"nsm_glsl map 128²", "nsm_glsl lookup 1 tap", "pcf kernel=3 map 130²",
                                       "pcf kernel=3 lookup 9 taps", "pcf kernel=5 map 132²",
                                       "pcf kernel=5 lookup 25 taps"};
    for (size_t k = 0; k < sizeof want / sizeof want[0]; k++) {
        int found = 0;
        for (int i = 0; i < ntech; i++)
            found += !strcmp(r.rows[i].name, want[k]);
        if (found != 1)
            fail_msg("row '%s' found %d times", want[k], found);
    }
    for (int i = 0; i < ntech; i++) {
        const struct sl_bench_row *w = &r.rows[i];
        assert_string_equal(w->stage, "technique");
        /* map, then lookup, of the same setting */
        const int lookup = i % 2;
        assert_non_null(strstr(w->name, lookup ? " lookup " : " map "));
        assert_true(fabs(w->target - (lookup ? 1.5 : 1.3)) < 1e-12);
        assert_true(isfinite(w->value) && w->value > 0 && isfinite(w->plain) && w->plain > 0);
        assert_true(fabs(w->ratio - w->value / w->plain) < 1e-9 * w->ratio);
        assert_int_equal(w->pass, w->ratio <= w->target);
    }
    const char *text = slurp(md);
    assert_non_null(strstr(text, "## Technique packages vs plain passes"));
    assert_non_null(strstr(text, "| pcf kernel=3 | map | 1 map r32f, 130² (S 128 + 2 × guard 1), cull none | "));
    assert_non_null(strstr(text, "| pcf kernel=5 | lookup | 25 taps × "));
    assert_non_null(strstr(text, "| nsm_glsl | lookup | 1 tap × "));
    /* what a lookup pays before its reads, the plain lookup reading none */
    const char *fl = strstr(text, "| pcf kernel=3 | lookup | ");
    assert_non_null(fl);
    char fline[400];
    snprintf(fline, sizeof fline, "%.*s", (int)strcspn(fl, "\n"), fl);
    assert_non_null(strstr(fline, "; floor (no reads) "));
    assert_non_null(strstr(fline, " ms, above it "));
    assert_non_null(strstr(text, "Whole stage: wall "));
    assert_non_null(strstr(text, "load average before "));
    /* a package with post passes has its row, with what they do */
    const char *post = strstr(text, " | post | ");
    if (post) {
        char line[300];
        snprintf(line, sizeof line, "%.*s", (int)strcspn(post, "\n"), post);
        assert_true(strstr(line, "blur") || strstr(line, "mipmaps") || strstr(line, "nothing at this setting"));
        assert_non_null(strstr(line, " | — | — |  |  | "));   /* no plain counterpart, no target */
    }
    printf("bench::techniques_rows: %d settings%s\n", ntech / 2, post ? ", post passes among them" : "");
}

/* The big-map stage at 1024^2: one row against 6 GB; the printed peak is
 * above the RSS at the start by at least the five 4 MiB arrays csm holds
 * (BGSM depth + id, BGSM2 depth, SGSM depth + id); three layers at most at
 * once; every layer bit-identical to the plain render. */
static void bench_bigmap_rows(void **st)
{
    (void)st;
    char md[300];
    struct sl_bench_opts o = {.stages = SL_BENCH_STAGE(BIGMAP), .reps = 1, .scene = "blocks", .width = 64,
                              .height = 64, .map = 1024};
    struct sl_bench_result r;
    run_bench(&o, "bigmap.md", md, sizeof md, &r);
    assert_int_equal(r.nrows, 1 + 2);   /* + memory, context */
    assert_string_equal(r.rows[0].stage, "bigmap");
    assert_string_equal(r.rows[0].name, "peak RSS, conservative layers 1024²");
    assert_true(fabs(r.rows[0].target - 6e9 / 1048576.0) < 1e-6);
    const char *text = slurp(md);
    const char *p = strstr(text, "| peak RSS | ");
    assert_non_null(p);
    double peak = -1, start = -1;
    assert_int_equal(sscanf(p, "| peak RSS | %lf MiB", &peak), 1);
    assert_true(fabs(peak - r.rows[0].value) < 1.0);
    p = strstr(text, "| RSS at the start (scene, view, GL driver) | ");
    assert_non_null(p);
    assert_int_equal(sscanf(p, "| RSS at the start (scene, view, GL driver) | %lf MiB", &start), 1);
    printf("bench::bigmap_rows: peak %.0f MiB, start %.0f MiB\n", peak, start);
    /* at least three 4 MiB arrays (BGSM's two and BGSM2's, the SGSMs
     * gathered per pixel before) and the target's two 4 MiB textures */
    assert_true(start > 0 && peak >= start + 3 * 4 + 2 * 4 - 1);
    assert_non_null(strstr(text, "| map-sized layers held at once, at most | 2 |"));
    assert_non_null(strstr(text, "layers identical: 4 of 4"));
    int same = 0;
    for (const char *q = text; (q = strstr(q, "bit-identical to the plain render")); q++)
        same++;
    assert_int_equal(same, 4);
    assert_non_null(strstr(text, "| load average before / after | "));
    assert_non_null(strstr(text, "| wall / CPU (user + sys) | "));
}

/* OSMesa and EGL side by side: a row per stage (context, G-buffer, the six
 * layers), EGL's min against OSMesa's, judged at 5%. */
static void bench_backends_rows(void **st)
{
    (void)st;
    if (!sl_gl_backend_built(SL_GL_OSMESA) || !sl_gl_backend_built(SL_GL_EGL))
        skip();
    char md[300];
    struct sl_bench_opts o = {.stages = SL_BENCH_STAGE(BACKENDS), .reps = 2, .scene = "blocks", .width = 64,
                              .height = 48, .map = 128};
    struct sl_bench_result r;
    run_bench(&o, "backends.md", md, sizeof md, &r);
    /* eight backend rows, then memory and the first context */
    assert_int_equal(r.nrows, 8 + 2);
    assert_string_equal(r.rows[0].name, "EGL vs OSMesa: context");
    assert_string_equal(r.rows[1].name, "EGL vs OSMesa: gbuffer 64x48");
    assert_string_equal(r.rows[7].name, "EGL vs OSMesa: sgsm_adj 128²");
    for (int i = 0; i < 8; i++) {
        const struct sl_bench_row *w = &r.rows[i];
        assert_string_equal(w->stage, "backend");
        assert_true(isfinite(w->value) && w->value > 0 && isfinite(w->plain) && w->plain > 0);
        assert_true(fabs(w->ratio - w->value / w->plain) < 1e-9 * w->ratio);
        assert_int_equal(w->pass, w->ratio <= 1.05);
    }
    const char *text = slurp(md);
    assert_non_null(strstr(text, "## GL backends side by side"));
    assert_non_null(strstr(text, "| bgsm2 128² |"));
}

/* The scoring stage on a small view: two rows against the histogram pass,
 * the fused pass and the one before it agreeing on every band, figure and
 * violation (a disagreement fails the row and says so in its note and the
 * Markdown). */
static void bench_scoring_rows(void **st)
{
    (void)st;
    char md[300];
    struct sl_bench_opts o = {.stages = SL_BENCH_STAGE(SCORING), .reps = 2, .scene = "blocks", .width = 128,
                              .height = 96, .map = 256};
    struct sl_bench_result r;
    run_bench(&o, "scoring.md", md, sizeof md, &r);
    assert_int_equal(r.nrows, 2 + 1 + 1);   /* + memory, context */
    for (int i = 0; i < 2; i++) {
        const struct sl_bench_row *w = &r.rows[i];
        assert_string_equal(w->stage, "scoring");
        assert_string_equal(w->unit, "ms/Mpx");
        assert_true(isfinite(w->value) && w->value > 0 && isfinite(w->plain) && w->plain > 0);
        assert_true(fabs(w->ratio - w->value / w->plain) < 1e-9 * w->ratio);
        assert_int_equal(w->pass, w->ratio <= w->target);
        assert_null(strstr(w->note, "DISAGREES"));
    }
    const char *text = slurp(md);
    assert_non_null(strstr(text, "agree on every band, figure and violation"));
    assert_non_null(strstr(text, "| scoring | scoring 128x96, wall, "));
}

/* The light-fit stage (at 3840x2160 whatever the options' viewport, as
 * the issue measured it): three rows, threads against one thread, the
 * boxes identical in every repetition, and the load average printed. */
static void bench_lightfit_rows(void **st)
{
    (void)st;
    char md[300];
    struct sl_bench_opts o = {.stages = SL_BENCH_STAGE(LIGHTFIT), .reps = 1, .scene = "blocks", .width = 128,
                              .height = 96, .map = 256};
    struct sl_bench_result r;
    run_bench(&o, "lightfit.md", md, sizeof md, &r);
    assert_int_equal(r.nrows, 3 + 1 + 1);   /* + memory, context */
    for (int i = 0; i < 3; i++) {
        const struct sl_bench_row *w = &r.rows[i];
        assert_string_equal(w->stage, "lightfit");
        assert_true(isfinite(w->value) && w->value > 0 && isfinite(w->plain) && w->plain > 0);
        assert_int_equal(w->pass, w->ratio <= w->target);
        assert_null(strstr(w->note, "DIFFER"));
    }
    const char *text = slurp(md);
    assert_non_null(strstr(text, "identical in every repetition"));
    assert_non_null(strstr(text, "Load average before "));
    assert_non_null(strstr(text, "3840x2160"));
}

/* --markdown FILE: the very text the stream got, under a header naming the
 * command, stages, git SHA, machine, CPU, GL renderer and backend and the
 * load average; written under a temporary name and renamed (none is left);
 * a FILE that cannot be written is an output error. */
static void bench_markdown_file(void **st)
{
    (void)st;
    char md[300], file[300];
    snprintf(file, sizeof file, "%s/performance.md", sl_test_dir);
    struct sl_bench_opts o = {.stages = SL_BENCH_STAGE(TRUTH), .reps = 1, .scene = "blocks", .width = 64,
                              .height = 48, .map = 128, .markdown = file};
    struct sl_bench_result r;
    run_bench(&o, "stream.md", md, sizeof md, &r);
    assert_true(r.nrows > 0);
    static char stream[1 << 16];
    snprintf(stream, sizeof stream, "%s", slurp(md));
    const char *text = slurp(file);
    assert_true(strncmp(text, "# Performance\n", 14) == 0);
    static const char *const want[] = {"| command | `", "test_bench", "| stages | truth |", "| git SHA | `",
                                       "| time (UTC) | ", "| machine | ", "| CPU | ", "| GL renderer | ",
                                       "| GL backend | ", "| Embree | ",
                                       "| load average (1, 5, 15 min) | "};
    for (size_t i = 0; i < sizeof want / sizeof want[0]; i++)
        if (!strstr(text, want[i]))
            fail_msg("no '%s' in the Markdown file", want[i]);
    /* the body is the stream's text, whole, at the end */
    const char *body = strstr(text, "# shadowlab bench\n");
    assert_non_null(body);
    assert_string_equal(body, stream);
    assert_non_null(strstr(body, "## Summary"));
    DIR *dir = opendir(sl_test_dir);
    assert_non_null(dir);
    for (struct dirent *de; (de = readdir(dir));)
        if (strstr(de->d_name, ".tmp-"))
            fail_msg("temporary file left: %s", de->d_name);
    closedir(dir);

    char bad[300];
    snprintf(bad, sizeof bad, "%s/no-such-folder/performance.md", sl_test_dir);
    o.markdown = bad;
    FILE *out = fopen(md, "w");
    assert_non_null(out);
    o.out = out;
    struct sl_diag d;
    assert_int_equal(sl_bench(&o, NULL, &d), SL_E_OUTPUT);
    fclose(out);
    assert_non_null(strstr(d.msg, "cannot write the Markdown"));
}

int main(int argc, char **argv)
{
    const struct CMUnitTest tests[] = {
        SL_CASE(bench, scoring_rows),
        SL_CASE(bench, lightfit_rows),
        SL_CASE(bench, parse_stages),
        SL_CASE(bench, studies_in_children),
        SL_CASE(bench, quick_mode_rows),
        SL_CASE(bench, backends_rows),
        SL_CASE(bench, churn_rows),
        SL_CASE(bench, techniques_rows),
        SL_CASE(bench, bigmap_rows),
        SL_CASE(bench, markdown_file),
    };
    return sl_run_group(argc, argv, "bench", tests, sl_test_setup, sl_test_teardown);
}
