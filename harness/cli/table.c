/*
 * table.c — `shadowlab table`: the stored cells of a results store,
 * filtered, as thesis-style tables, or with --summary (and its --region,
 * --lower-is-better, --average-case) one figure's average, best and worst
 * per map size, or with --rows/--cols/--figure/--of/--agg/--where one pivot
 * table a paper takes (pivot.h).
 */
#define _GNU_SOURCE   /* getopt_long */
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "cli.h"
#include "util.h"
#include "store.h"
#include "pivot.h"
#include "suggest.h"
#include "summary.h"
#include "table.h"

/* Every label --label names is one the store holds (under the other
 * filters): a typo is an error with the nearest stored label, never a
 * label silently dropped from the table. The store is asked again, without
 * the label filter, only when a label found no cell. */
static enum sl_err check_labels(struct sl_store *st, const struct sl_store_filter *f, const char *labels,
                                const struct sl_cell_record *cells, int n, struct sl_diag *d)
{
    struct sl_cell_record *all = NULL;
    int nall = 0, asked = 0;
    enum sl_err e = SL_OK;
    for (const char *q = labels; *q && !e;) {
        size_t len = strcspn(q, ",");
        char want[64];
        snprintf(want, sizeof want, "%.*s", (int)(len < sizeof want ? len : sizeof want - 1), q);
        q += len;
        q += *q == ',';
        int found = 0;
        for (int i = 0; i < n && !found; i++)
            found = !strcmp(cells[i].label, want);
        if (found)
            continue;
        if (!asked) {
            struct sl_store_filter g = *f;
            g.label = NULL;
            asked = 1;
            e = sl_store_query(st, &g, &all, &nall, d);
            if (e)
                break;
        }
        struct sl_suggest sg;
        char known[512] = "", hint[96];
        sl_suggest_init(&sg, want);
        for (int i = 0; i < nall; i++) {
            int seen = 0;
            for (int j = 0; j < i && !seen; j++)
                seen = !strcmp(all[j].label, all[i].label);
            if (seen)
                continue;
            sl_known_add(known, sizeof known, all[i].label);
            sl_suggest_add(&sg, all[i].label);
        }
        int stored = 0;
        for (int i = 0; i < nall && !stored; i++)
            stored = !strcmp(all[i].label, want);
        if (stored)
            continue;   /* stored, only not under the other filters: "no stored cell matches" says so */
        e = sl_fail(d, SL_E_USAGE, NULL, 0, "--label", "no label '%s' in the store%s (stored%s: %s)", want,
                    sl_suggest_text(&sg, hint, sizeof hint), f->scene || f->viewpoint || f->map_size || f->run_id
                    ? " under the other filters" : "", known[0] ? known : "none");
    }
    free(all);
    return e;
}

int cli_table(int argc, char **argv)
{
    static const struct option lo[] = {
        OPT_HELP,
        {"format", required_argument, NULL, OPT_FORMAT},     {"scene", required_argument, NULL, OPT_SCENE},
        {"viewpoint", required_argument, NULL, OPT_VIEWPOINT}, {"label", required_argument, NULL, OPT_LABEL},
        {"map", required_argument, NULL, OPT_MAP},           {"run", required_argument, NULL, OPT_RUN},
        {"summary", required_argument, NULL, OPT_SUMMARY},   {"region", required_argument, NULL, OPT_REGION},
        {"figures", required_argument, NULL, OPT_FIGURES},
        {"lower-is-better", no_argument, NULL, OPT_LOWER},   {"average-case", required_argument, NULL, OPT_AVG},
        {"rows", required_argument, NULL, OPT_ROWS},          {"cols", required_argument, NULL, OPT_COLS},
        {"figure", required_argument, NULL, OPT_FIGURE},      {"of", required_argument, NULL, OPT_OF},
        {"agg", required_argument, NULL, OPT_AGG},            {"where", required_argument, NULL, OPT_WHERE},
        {0, 0, 0, 0},
    };
    const struct cli_parser p = {"table", "", cli_usage_table, lo};
    struct sl_store_filter f = {0};
    int fmt = SL_TABLE_MD;
    struct sl_summary_opts so = {.figure = -1, .region = -1};
    const char *figures = NULL;
    char summary[512] = "", labels[512] = "";   /* repeated or "a,b": joined by ',' */
    char avg_scene[64] = "", avg_vp[32] = "";
    struct sl_pivot_desc pd = {0};
    int pivot = 0;
    struct sl_diag pdg;
    memset(&pdg, 0, sizeof pdg);
    for (int c; (c = cli_opt_next(&p, argc, argv)) != OPT_DONE;) {
        const char *v = optarg;
        switch (c) {
        case OPT_FORMAT:
            fmt = sl_table_format_parse(v);
            if (fmt < 0)
                return cli_usage_error("table: --format md, csv, latex or json", cli_usage_table);
            break;
        case OPT_ROWS:
        case OPT_COLS: {
            int k = sl_pivot_key_parse(v);
            if (k < 0)
                return cli_usage_error("table: --rows/--cols label, method, scene, viewpoint, viewport, map_size "
                                       "or region", cli_usage_table);
            *(c == OPT_ROWS ? &pd.rows : &pd.cols) = (enum sl_pivot_key)k;
            pivot = 1;
            break;
        }
        case OPT_FIGURE: pd.figure = v; pivot = 1; break;
        case OPT_OF: pd.of = v; pivot = 1; break;
        case OPT_AGG: {
            int a = sl_pivot_agg_parse(v);
            if (a < 0)
                return cli_usage_error("table: --agg mean, median, sum, min or max", cli_usage_table);
            pd.agg = (enum sl_pivot_agg)a;
            pivot = 1;
            break;
        }
        case OPT_WHERE:
            if (sl_pivot_where_parse(&pd, v, &pdg))
                return cli_fail(SL_E_USAGE, &pdg);
            pivot = 1;
            break;
        case OPT_SCENE: f.scene = v; break;
        case OPT_VIEWPOINT: f.viewpoint = v; break;
        case OPT_LABEL:
        case OPT_SUMMARY: {
            char *to = c == OPT_LABEL ? labels : summary;
            size_t len = strlen(to);
            if (len + strlen(v) + 2 > sizeof labels)
                return cli_usage_error(c == OPT_LABEL ? "table: --label: too many labels"
                                                      : "table: --summary: too many figures", cli_usage_table);
            snprintf(to + len, sizeof labels - len, "%s%s", len ? "," : "", v);
            break;
        }
        case OPT_MAP: {
            long long x;
            if (!cli_opt_int_or_usage("table", "--map", v, 1, 16384, &x, cli_usage_table))
                return 2;
            f.map_size = (int)x;
            break;
        }
        case OPT_RUN: {
            long long x;
            if (!cli_opt_int_or_usage("table", "--run", v, 1, LLONG_MAX, &x, cli_usage_table))
                return 2;
            f.run_id = x;
            break;
        }
        case OPT_FIGURES: figures = v; break;
        case OPT_REGION:
            if (!strcmp(v, "image") || !strcmp(v, "contours"))
                so.region = !strcmp(v, "image") ? 0 : -1;
            else {
                long long x;
                if (!cli_opt_int_or_usage("table", "--region", v, 0, 64, &x, cli_usage_table))
                    return 2;
                so.region = (int)x;
            }
            if (so.region > 0 && so.region % 2)
                return cli_usage_error("table: --region N (even), image or contours", cli_usage_table);
            break;
        case OPT_LOWER: so.lower_is_better = 1; break;
        case OPT_AVG:
        {
            char nr[32] = "", nm[32] = "";
            long long x;
            int k = sscanf(v, "%63[^/]/%31[^/]/%31[^/]/%31s", avg_scene, avg_vp, nr, nm);
            if (k < 3)
                return cli_usage_error("table: --average-case SCENE/VIEWPOINT/N[/MAP]", cli_usage_table);
            if (!cli_opt_int_or_usage("table", "--average-case N", nr, 0, 64, &x, cli_usage_table))
                return 2;
            so.avg_region = (int)x;
            if (k == 4) {
                if (!cli_opt_int_or_usage("table", "--average-case MAP", nm, 1, 16384, &x, cli_usage_table))
                    return 2;
                so.avg_map = (int)x;
            }
        }
            so.avg_scene = avg_scene;
            so.avg_viewpoint = avg_vp;
            break;
        default: return cli_opt_exit(c);
        }
    }
    if (optind >= argc)
        return cli_usage_error("table: missing DB", cli_usage_table);
    if (labels[0])
        f.label = labels;
    if (pivot && (summary[0] || figures))
        return cli_usage_error("table: a pivot (--rows, --cols, --figure, --of, --agg, --where) takes no "
                               "--summary or --figures", cli_usage_table);
    if (!pivot && fmt == SL_TABLE_JSON)
        return cli_usage_error("table: --format json is a pivot's (--rows, --cols, --figure)", cli_usage_table);
    if (optind + 1 < argc)
        return cli_usage_error("table: one DB", cli_usage_table);
    const char *db = argv[optind];
    struct sl_diag d;
    memset(&d, 0, sizeof d);
    FILE *probe = fopen(db, "rb");
    if (!probe) {
        sl_fail(&d, SL_E_IO, db, 0, NULL, "cannot read the results store");
        return cli_fail(SL_E_IO, &d);
    }
    fclose(probe);
    struct sl_store *st = NULL;
    struct sl_cell_record *cells = NULL;
    int n = 0;
    enum sl_err e = sl_store_open_existing(db, &st, &d);
    if (!e)
        e = sl_store_query(st, &f, &cells, &n, &d);
    if (!e && labels[0])
        e = check_labels(st, &f, labels, cells, n, &d);
    if (!e && n == 0)
        e = sl_fail(&d, SL_E_USAGE, db, 0, NULL, "no stored cell matches");
    if (!e && pivot) {
        struct sl_pivot_info info;
        e = sl_pivot_write(stdout, (enum sl_table_format)fmt, cells, n, &pd, &info, &d);
        if (!e && info.nrows == 0)
            e = sl_fail(&d, SL_E_USAGE, db, 0, NULL, "no stored value of %s matches", pd.figure ? pd.figure : "wrong");
        if (!e && info.parts > 1)
            fprintf(stderr, "table: %d columns do not fit \\columnwidth: split into %d tables\n",
                    info.transposed ? info.nrows : info.ncols, info.parts);
        else if (!e && info.transposed)
            fprintf(stderr, "table: %d columns do not fit \\columnwidth: transposed (%s as rows)\n", info.ncols,
                    sl_pivot_key_name(pd.cols ? pd.cols : SL_PK_map_size));
    } else if (!e && summary[0]) {
        /* every figure checked before anything is written */
        int figs[SL_FIG_COUNT], nfigs = 0;
        for (const char *q = summary; *q && !e;) {
            size_t len = strcspn(q, ",");
            int k = 0;
            while (k < SL_FIG_COUNT && !(strlen(sl_figure_name((enum sl_figure)k)) == len &&
                                         !strncmp(sl_figure_name((enum sl_figure)k), q, len)))
                k++;
            if (k == SL_FIG_COUNT) {
                char word[64], hint[96];
                struct sl_suggest sg;
                snprintf(word, sizeof word, "%.*s", (int)(len < sizeof word ? len : sizeof word - 1), q);
                sl_suggest_init(&sg, word);
                for (int j = 0; j < SL_FIG_COUNT; j++)
                    sl_suggest_add(&sg, sl_figure_name((enum sl_figure)j));
                e = sl_fail(&d, SL_E_USAGE, NULL, 0, "--summary", "unknown figure '%s'%s", word,
                            sl_suggest_text(&sg, hint, sizeof hint));
            }
            else if (!sl_figure_of((enum sl_figure)k)[0])
                e = sl_fail(&d, SL_E_USAGE, NULL, 0, "--summary", "'%s' is a count, not a percentage",
                            sl_figure_name((enum sl_figure)k));
            else if (nfigs < SL_FIG_COUNT)
                figs[nfigs++] = k;
            q += len;
            q += *q == ',';
        }
        for (int k = 0; k < nfigs && !e; k++) {
            so.figure = figs[k];
            so.continued = k > 0;
            e = sl_summary_write(stdout, (enum sl_table_format)fmt, cells, n, &so, &d);
        }
    } else if (!e) {
        /* the terminal's tables: only what the methods produce, unless --figures says */
        struct sl_table_rows rows = {0};
        e = sl_table_figures_parse(figures, &rows, &d);
        if (!figures)
            rows.produced = fmt != SL_TABLE_CSV;
        if (!e)
            e = sl_table_write_rows(stdout, (enum sl_table_format)fmt, db, cells, n, &rows, &d);
    }
    free(cells);
    sl_store_close(st);
    if (e)
        return cli_fail(e, &d);
    /* on stderr: stdout is the table, in whatever format was asked */
    return cli_say_sweeps("table", db, 0, 1) < 0 ? 2 : 0;
}
