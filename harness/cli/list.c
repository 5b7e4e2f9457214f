/*
 * list.c — `shadowlab list methods|scenes|techniques`: what a config can
 * name, and where each scene file and technique package was found; `shadowlab
 * show method NAME`: a built-in method's parameters from its declarations;
 * `shadowlab show technique NAME`: one package's parameters, maps, reach and
 * citation.
 * Packages are read as a run reads them (technique.h: the search path
 * without a config, C method names refused), with no GL.
 */
#define _GNU_SOURCE   /* getopt_long */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "cli.h"
#include "method.h"
#include "scenefile.h"
#include "suggest.h"
#include "technique.h"
#include "util.h"

/* The packages of the search path (no config: SHADOWLAB_TECHNIQUES, the
 * source tree, the installed ones); exit code on failure, else 0. */
static int tech_scan(struct sl_tech_set *s, char (*dirs)[1024], const char **origin, int *nd);

int cli_tech_scan(struct sl_tech_set *s)
{
    char dirs[SL_TECH_MAX_DIRS][1024];
    const char *origin[SL_TECH_MAX_DIRS];
    int nd;
    return tech_scan(s, dirs, origin, &nd);
}

static int tech_scan(struct sl_tech_set *s, char (*dirs)[1024], const char **origin, int *nd)
{
    static const char *c_names[64];
    int nc = 0;
    for (int i = 0; i < sl_method_count() && nc < 63; i++)
        c_names[nc++] = sl_method_at(i)->name;
    c_names[nc] = NULL;
    *nd = sl_tech_dirs(NULL, 0, NULL, dirs, origin, SL_TECH_MAX_DIRS);
    struct sl_diag d;
    enum sl_err e = sl_tech_set_scan(s, dirs, origin, *nd, c_names, &d);
    return e ? cli_fail(e, &d) : 0;
}

static int list_techniques(void)
{
    struct sl_tech_set s;
    char dirs[SL_TECH_MAX_DIRS][1024];
    const char *origin[SL_TECH_MAX_DIRS];
    int nd, rc = tech_scan(&s, dirs, origin, &nd);
    if (rc)
        return rc;
    for (int i = 0; i < s.n; i++)
        printf("%-14s %-60s [%s: %s]\n", s.t[i].name, s.t[i].summary, s.t[i].origin, s.t[i].dir);
    if (s.n == 0) {
        fprintf(stderr, "shadowlab: no technique packages in");
        for (int i = 0; i < nd; i++)
            fprintf(stderr, "%s %s (%s)", i ? "," : "", dirs[i], origin[i]);
        fputc('\n', stderr);
    }
    sl_tech_set_free(&s);
    return 0;
}

/* The parameters block `show method` and `show technique` share: one
 * line each, name, type, default, range or words, unit, doc. */
static void show_params(const struct sl_param *decl, int n)
{
    printf("  parameters%s\n", n ? "" : " none");
    for (int i = 0; i < n; i++) {
        const struct sl_param *p = &decl[i];
        char range[160], def[64];
        sl_param_range_text(p, range, sizeof range);
        sl_param_text(p, p->def, def, sizeof def);
        printf("    %-12s %-5s default %-8s %-12s %s%s%s%s\n", p->name, sl_param_type_names[p->type], def, range,
               p->unit[0] ? "(" : "", p->unit, p->unit[0] ? ") " : "", p->doc);
    }
}

static void scaled_text(const struct sl_technique *t, const struct sl_tech_scaled *x, char *buf, size_t n)
{
    if (x->param < 0)
        snprintf(buf, n, "%g", x->texels);
    else if (x->power == 1.0)
        snprintf(buf, n, "%g + %g x %s", x->texels, x->scale, t->param[x->param].name);
    else
        snprintf(buf, n, "%g + %g x %s^%g", x->texels, x->scale, t->param[x->param].name, x->power);
}

static void show_technique(const struct sl_technique *t)
{
    struct sl_params v;
    sl_tech_defaults(t, &v);
    printf("%s — %s\n", t->name, t->summary);
    printf("  package    %s (%s)\n", t->dir, t->origin ? t->origin : "given");
    printf("  shaders    %s, %s\n", t->map_shader, t->lookup_shader);
    printf("  cite       %s\n", t->cite[0] ? t->cite : "(none given)");
    printf("  family     %s\n", t->family);
    printf("  threshold  %g (lit iff visibility >= it)\n", t->threshold);
    if (t->trace)
        printf("  trace      visibility in [%g, %g]: traced with the truth's rays (a hybrid)\n", t->trace_lo,
               t->trace_hi);
    printf("  cull       %s\n", sl_tech_cull_names[t->cull]);
    printf("  maps\n");
    for (int i = 0; i < t->nmaps; i++) {
        const struct sl_tech_map *m = &t->map[i];
        printf("    %-12s %-8s filter %-8s post %s%s%s\n", m->name, sl_tech_format_names[m->format],
               sl_tech_filter_names[m->filter], sl_tech_post_names[m->post], m->blur >= 0 ? ", radius " : "",
               m->blur >= 0 ? t->param[m->blur].name : "");
    }
    char buf[160];
    scaled_text(t, &t->reach, buf, sizeof buf);
    printf("  reach      ceil(%s) texels (%d at the defaults; guard band %d)\n", buf, sl_tech_reach(t, &v),
           sl_tech_guard(t, &v));
    scaled_text(t, &t->taps, buf, sizeof buf);
    printf("  taps       %s texel reads a pixel (%g at the defaults)\n", buf, sl_tech_taps(t, &v));
    show_params(t->param, t->nparams);
}

static void show_method(const struct sl_method *m)
{
    printf("%s — %s\n", m->name, m->summary);
    printf("  display    %s\n", m->display ? m->display : m->name);
    printf("  family     %s\n", m->family ? m->family : "(none: a baseline)");
    printf("  exact      %s%s%s%s\n", m->exact ? "" : "nothing", m->exact & SL_EXACT_LIT ? "lit " : "",
           m->exact & SL_EXACT_SHADOW ? "shadow " : "", m->exact & SL_EXACT_PROVED ? "proved" : "");
    printf("  lights     %s\n", m->lights & SL_LIGHTS_AREA ? "area (soft shadows)"
                                : m->lights & SL_LIGHTS_DIRECTIONAL ? "directional" : "any (hard shadows)");
    show_params(m->params, m->nparams);
}

int cli_show(int argc, char **argv)
{
    static const struct option lo[] = {OPT_HELP, {0, 0, 0, 0}};
    const struct cli_parser p = {"show", "", cli_usage_show, lo};
    for (int c; (c = cli_opt_next(&p, argc, argv)) != OPT_DONE;)
        return cli_opt_exit(c);
    argc -= optind - 1;
    argv += optind - 1;
    if (argc != 3 || (strcmp(argv[1], "technique") != 0 && strcmp(argv[1], "method") != 0))
        return cli_usage_error("show: method NAME or technique NAME", cli_usage_show);
    if (!strcmp(argv[1], "method")) {
        const struct sl_method *m = NULL;
        char names[600] = "", hint[96];
        struct sl_suggest sg;
        sl_suggest_init(&sg, argv[2]);
        for (int i = 0; i < sl_method_count(); i++) {
            if (!strcmp(sl_method_at(i)->name, argv[2]))
                m = sl_method_at(i);
            sl_known_add(names, sizeof names, sl_method_at(i)->name);
            sl_suggest_add(&sg, sl_method_at(i)->name);
        }
        if (!m) {
            struct sl_diag d;
            sl_fail(&d, SL_E_METHOD, NULL, 0, argv[2], "no built-in method of that name%s (there are: %s; a "
                    "technique package: `shadowlab show technique NAME`)", sl_suggest_text(&sg, hint, sizeof hint),
                    names);
            return cli_fail(SL_E_METHOD, &d);
        }
        show_method(m);
        return 0;
    }
    struct sl_tech_set s;
    char dirs[SL_TECH_MAX_DIRS][1024];
    const char *origin[SL_TECH_MAX_DIRS];
    int nd, rc = tech_scan(&s, dirs, origin, &nd);
    if (rc)
        return rc;
    const struct sl_technique *t = sl_tech_find(&s, argv[2]);
    if (!t) {
        struct sl_diag d;
        char names[600] = "", hint[96];
        struct sl_suggest sg;
        sl_suggest_init(&sg, argv[2]);
        for (int i = 0; i < s.n; i++) {
            snprintf(names + strlen(names), sizeof names - strlen(names), "%s%s", i ? ", " : "", s.t[i].name);
            sl_suggest_add(&sg, s.t[i].name);
        }
        sl_fail(&d, SL_E_METHOD, NULL, 0, argv[2], "no technique package of that name%s (found: %s; "
                "`shadowlab list techniques` says where)", sl_suggest_text(&sg, hint, sizeof hint),
                s.n ? names : "none");
        sl_tech_set_free(&s);
        return cli_fail(SL_E_METHOD, &d);
    }
    show_technique(t);
    sl_tech_set_free(&s);
    return 0;
}

int cli_list(int argc, char **argv)
{
    static const struct option lo[] = {OPT_HELP, {0, 0, 0, 0}};
    const struct cli_parser p = {"list", "", cli_usage_list, lo};
    for (int c; (c = cli_opt_next(&p, argc, argv)) != OPT_DONE;)
        return cli_opt_exit(c);
    argc -= optind - 1;
    argv += optind - 1;
    if (argc == 2 && strcmp(argv[1], "methods") == 0) {
        for (int i = 0; i < sl_method_count(); i++)
            printf("%-12s %s\n", sl_method_at(i)->name, sl_method_at(i)->summary);
        return 0;
    }
    if (argc == 2 && strcmp(argv[1], "scenes") == 0) {
        static char names[256][64], descr[256][160], paths[256][1024];
        static const char *origin[256];
        int n = sl_scene_list_where(names, descr, paths, origin, 256);
        for (int i = 0; i < n; i++)
            printf("%-14s %-50s [%s: %s]\n", names[i], descr[i], origin[i], paths[i]);
        if (n == 0) {
            char dirs[16][1024];
            const char *o[16];
            int nd = sl_scene_dirs(NULL, dirs, o, 16);
            fprintf(stderr, "shadowlab: no scene files in");
            for (int i = 0; i < nd; i++)
                fprintf(stderr, "%s %s (%s)", i ? "," : "", dirs[i], o[i]);
            fputc('\n', stderr);
        }
        return 0;
    }
    if (argc == 2 && strcmp(argv[1], "techniques") == 0)
        return list_techniques();
    return cli_usage_error("list: methods, scenes or techniques", cli_usage_list);
}
