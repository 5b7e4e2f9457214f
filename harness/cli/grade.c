/*
 * grade.c — `shadowlab grade`: a visibility image rendered by another
 * program, registered against shadowlab's own view of the scene and scored
 * against the truth as a cell of method `external` (harness/run/grade.h,
 * doc/grade.md). Its options are its own (ids from GOPT_FIRST), so the verb
 * is this file, one row in the verb table and its declarations.
 */
#define _GNU_SOURCE
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "cli.h"
#include "grade.h"

const char cli_usage_grade[] =
    "usage: shadowlab grade --scene S --viewpoint V --viewport WxH --image FILE --label NAME\n"
    "                       [--depth FILE [--depth-kind linear|window] [--reversed-z]\n"
    "                       [--near N --far F]] [-o OUT] [--db FILE] [--map N] [--contour nsm|own]\n"
    "                       [--threshold T] [--tolerance P] [--depth-tolerance R] [--gl osmesa|egl]\n"
    "                       [-j THREADS]\n"
    "  Grades a visibility image rendered by another program (an engine's shadow term before\n"
    "  lighting): one channel (V, Y or R; other colour channels must equal it), 1 lit, 0 shadowed,\n"
    "  fractions allowed, EXR (half or float) or a 16-bit PNG; background alpha 0 or NaN; rows as\n"
    "  image files store them (top row first), pixel centres at half-integers (doc/grade.md).\n"
    "  First registration: the image must show the view shadowlab renders of S from V at WxH. With\n"
    "  --depth, the engine's depth against the G-buffer's; without, the image's background against\n"
    "  the view's. When more than the tolerance of the pixels disagree, or a flipped or one-pixel-\n"
    "  shifted image would agree better, the grade is refused (exit 2) with the share of\n"
    "  misregistered pixels and the likely cause; an image with no background and no depth is\n"
    "  graded with a warning. Then the cell, exactly as a method's: PFL/PnFL, light and shadow\n"
    "  correct per contour band, fractional figures (leaking, over-darkening, mean error), overlay;\n"
    "  stored as method `external` under NAME, so table, report, check and pivot read it as any\n"
    "  cell. The grade's config is written as OUT/grade-NAME.yaml, its results in\n"
    "  OUT/grade-NAME/, its cell in OUT/shadowlab.db. `outputs.visibility: exr` in a config\n"
    "  writes a run's own visibility in this form (V, A, Z): grading it back gives the same figures.\n"
    "  --scene S          a scene file or a built-in scene's name\n"
    "  --viewpoint V      its viewpoint (the camera the engine used: doc/grade.md)\n"
    "  --viewport WxH     the image's size\n"
    "  --image FILE       the visibility\n"
    "  --label NAME       the cell's label (letters, digits, -, _)\n"
    "  --depth FILE       the engine's depth buffer (channel Z or depth, else its first)\n"
    "  --depth-kind K     linear: eye-space distance along the view axis (default); window: a\n"
    "                     depth buffer as it is, 0 near .. 1 far (the same in OpenGL, Vulkan, D3D)\n"
    "  --reversed-z       the depth buffer holds 1 - depth (reversed-Z)\n"
    "  --near N, --far F  the engine's near and far planes (window depths)\n"
    "  -o, --out OUT      output folder (default results)\n"
    "  --db FILE          the store (default OUT/shadowlab.db)\n"
    "  --map N            the map size NSM's contours are drawn at (default 1024; give a package's\n"
    "                     cell's map size to compare with it)\n"
    "  --contour nsm|own  contours from NSM's image (default, the thesis's) or the image's own\n"
    "  --threshold T      a pixel is lit iff its visibility >= T (default 0.5)\n"
    "  --tolerance P      misregistered pixels allowed, % of the image (default 1)\n"
    "  --depth-tolerance R  a depth disagrees beyond R % of the view's (default 1)\n"
    "  --gl osmesa|egl    the GL backend\n"
    "  -j, --threads N    CPU threads (default every core)\n";

enum {
    GOPT_FIRST = 1000, GOPT_SCENE = GOPT_FIRST, GOPT_VIEWPOINT, GOPT_VIEWPORT, GOPT_IMAGE, GOPT_LABEL, GOPT_DEPTH,
    GOPT_DEPTH_KIND, GOPT_REVERSED, GOPT_NEAR, GOPT_FAR, GOPT_DB, GOPT_MAP, GOPT_CONTOUR, GOPT_THRESHOLD,
    GOPT_TOLERANCE, GOPT_DEPTH_TOL, GOPT_GL,
};

/* A number in lo..hi; 0 after printing the usage error. */
static int opt_num(const char *opt, const char *s, double lo, double hi, double *out)
{
    char *end;
    double x = strtod(s, &end);
    if (end == s || *end || !isfinite(x) || x < lo || x > hi) {
        char msg[160];
        snprintf(msg, sizeof msg, "grade: %s wants a number in %g..%g, not '%s'", opt, lo, hi, s);
        cli_usage_error(msg, cli_usage_grade);
        return 0;
    }
    *out = x;
    return 1;
}

int cli_grade(int argc, char **argv)
{
    static const struct option lo[] = {
        OPT_HELP,
        {"scene", required_argument, NULL, GOPT_SCENE},
        {"viewpoint", required_argument, NULL, GOPT_VIEWPOINT},
        {"viewport", required_argument, NULL, GOPT_VIEWPORT},
        {"image", required_argument, NULL, GOPT_IMAGE},
        {"label", required_argument, NULL, GOPT_LABEL},
        {"depth", required_argument, NULL, GOPT_DEPTH},
        {"depth-kind", required_argument, NULL, GOPT_DEPTH_KIND},
        {"reversed-z", no_argument, NULL, GOPT_REVERSED},
        {"near", required_argument, NULL, GOPT_NEAR},
        {"far", required_argument, NULL, GOPT_FAR},
        {"out", required_argument, NULL, 'o'},
        {"db", required_argument, NULL, GOPT_DB},
        {"map", required_argument, NULL, GOPT_MAP},
        {"contour", required_argument, NULL, GOPT_CONTOUR},
        {"threshold", required_argument, NULL, GOPT_THRESHOLD},
        {"tolerance", required_argument, NULL, GOPT_TOLERANCE},
        {"depth-tolerance", required_argument, NULL, GOPT_DEPTH_TOL},
        {"gl", required_argument, NULL, GOPT_GL},
        {"threads", required_argument, NULL, 'j'},
        {0, 0, 0, 0},
    };
    const struct cli_parser p = {"grade", "o:j:", cli_usage_grade, lo};
    struct sl_grade_desc g = {0};
    double x;
    long long n;
    for (int c; (c = cli_opt_next(&p, argc, argv)) != OPT_DONE;) {
        switch (c) {
        case GOPT_SCENE: g.scene = optarg; break;
        case GOPT_VIEWPOINT: g.viewpoint = optarg; break;
        case GOPT_VIEWPORT:
            if (!cli_parse_wxh(optarg, 16, 8192, &g.w, &g.h))
                return cli_usage_error("grade: --viewport wants WxH, 16..8192 each", cli_usage_grade);
            break;
        case GOPT_IMAGE: g.image = optarg; break;
        case GOPT_LABEL: g.label = optarg; break;
        case GOPT_DEPTH: g.depth = optarg; break;
        case GOPT_DEPTH_KIND:
            if (!strcmp(optarg, "linear"))
                g.depth_kind = SL_DEPTH_LINEAR;
            else if (!strcmp(optarg, "window"))
                g.depth_kind = SL_DEPTH_WINDOW;
            else
                return cli_usage_error("grade: --depth-kind wants linear or window", cli_usage_grade);
            break;
        case GOPT_REVERSED: g.reversed_z = 1; break;
        case GOPT_NEAR:
            if (!opt_num("--near", optarg, 1e-9, 1e12, &g.near_z))
                return 2;
            break;
        case GOPT_FAR:
            if (!opt_num("--far", optarg, 1e-9, 1e12, &g.far_z))
                return 2;
            break;
        case 'o': g.out_root = optarg; break;
        case GOPT_DB: g.store = optarg; break;
        case GOPT_MAP:
            if (!cli_opt_int_or_usage("grade", "--map", optarg, 64, 16384, &n, cli_usage_grade))
                return 2;
            g.map_size = (int)n;
            break;
        case GOPT_CONTOUR:
            if (strcmp(optarg, "nsm") && strcmp(optarg, "own"))
                return cli_usage_error("grade: --contour wants nsm or own", cli_usage_grade);
            g.contour_own = !strcmp(optarg, "own");
            break;
        case GOPT_THRESHOLD:
            if (!opt_num("--threshold", optarg, 1e-6, 1.0, &g.threshold))
                return 2;
            break;
        case GOPT_TOLERANCE:
            if (!opt_num("--tolerance", optarg, 1e-6, 100.0, &x))
                return 2;
            g.tolerance = x / 100.0;
            break;
        case GOPT_DEPTH_TOL:
            if (!opt_num("--depth-tolerance", optarg, 1e-6, 100.0, &x))
                return 2;
            g.depth_tolerance = x / 100.0;
            break;
        case GOPT_GL:
            if (!(g.gl = sl_gl_backend_parse(optarg)))
                return cli_usage_error("grade: --gl wants osmesa or egl", cli_usage_grade);
            break;
        case 'j':
            if (!cli_opt_int_or_usage("grade", "--threads", optarg, 1, 256, &n, cli_usage_grade))
                return 2;
            g.threads = (int)n;
            break;
        default: return cli_opt_exit(c);
        }
    }
    if (optind < argc)
        return cli_usage_error("grade: no arguments besides the options", cli_usage_grade);
    const char *missing = !g.scene ? "--scene" : !g.viewpoint ? "--viewpoint" : !g.w ? "--viewport"
                          : !g.image ? "--image" : !g.label ? "--label" : NULL;
    if (missing) {
        char msg[80];
        snprintf(msg, sizeof msg, "grade: missing %s", missing);
        return cli_usage_error(msg, cli_usage_grade);
    }
    if (!g.depth && (g.depth_kind || g.reversed_z || g.near_z > 0 || g.far_z > 0))
        return cli_usage_error("grade: --depth-kind, --reversed-z, --near and --far describe --depth FILE",
                               cli_usage_grade);
    struct sl_diag d;
    memset(&d, 0, sizeof d);
    struct sl_grade_result r;
    enum sl_err e = sl_grade(&g, stdout, &r, &d);
    if (e)
        return cli_fail(e, &d);
    if (!r.reg.checked)
        fprintf(stderr, "shadowlab: warning: %s: registration not checked: neither the image nor the view has "
                        "background%s, and no --depth was given; a flipped or shifted image would be graded as "
                        "a bad technique\n",
                g.image, "");
    else
        fprintf(stderr, "shadowlab: %s: registered by %s: %.3f %% of the pixels disagree (tolerance %.2f %%)\n",
                g.image, r.reg.by_depth ? "depth" : "background", 100.0 * r.reg.share,
                100.0 * (g.tolerance ? g.tolerance : 0.01));
    if (r.nonfinite)
        fprintf(stderr, "shadowlab: warning: %llu surface pixel(s) have no finite visibility (NaN): counted, "
                        "flagged in the store\n",
                (unsigned long long)r.nonfinite);
    printf("written to %s and %s (config %s)\n", r.out_dir, r.store_path, r.config);
    return 0;
}
