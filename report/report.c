/*
 * report.c — see report.h. Reads the store, groups the cells by study and
 * writes the page section by section (doc.c, layouts.c, plots.c).
 *
 * Invariants:
 * - Nothing is written before the input is known good: a missing, empty or
 *   foreign database, a store without cells and a missing gnuplot are
 *   refused before the staging folder exists.
 * - The pages are registered last-moved (SL_REPORT_PAGE), so the folder never
 *   holds a report.html whose images are not there yet.
 * - Overlays are read from the database's folder and copied; one that is not
 *   there is listed on the page, never an error (runs with overlays: false
 *   store none, and results folders get pruned).
 */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include "provenance.h"
#include "report_int.h"
#include "util.h"

static const char css[] =
    "body{font:14px/1.45 system-ui,-apple-system,'Segoe UI',Roboto,'DejaVu Sans',sans-serif;color:#1d1d1f;"
    "background:#fff;margin:0 auto;max-width:1200px;padding:1.5em 2em}"
    "h1{font-size:1.7em;border-bottom:2px solid #333;padding-bottom:.2em}"
    "h2{font-size:1.35em;margin-top:2.2em;border-bottom:1px solid #999;padding-bottom:.15em}"
    "h3{font-size:1.12em;margin-top:1.8em}h4{font-size:1em}"
    "nav{background:#f3f4f6;border:1px solid #ddd;padding:.4em 1em;margin:1em 0}"
    ".tab{overflow-x:auto;margin:1em 0 1.6em}"
    "table{border-collapse:collapse;font-size:12.5px;font-variant-numeric:tabular-nums}"
    "caption{caption-side:top;text-align:left;font-weight:600;padding:.3em 0}"
    "th,td{padding:.2em .6em;text-align:right;white-space:nowrap}"
    "th.k,td.k{text-align:left}table.wrap td{white-space:normal;min-width:5em}thead tr:last-child th{border-bottom:1.5px solid #333}"
    "thead tr:first-child th{border-top:2px solid #333}th.grp{border-bottom:1px solid #999;text-align:center}"
    "tbody tr:last-child td{border-bottom:2px solid #333}tr.blk td{border-top:1px solid #ccc}tr.muted td{color:#777}"
    "tbody tr:hover td{background:#f5f8ff}"
    ".note{font-size:12px;color:#555;margin:.3em 0}"
    "figure{margin:1em 0}figure img{max-width:100%;height:auto;border:1px solid #ddd}"
    "figcaption{font-size:12px;color:#555}"
    ".gallery{display:grid;grid-template-columns:repeat(auto-fill,minmax(230px,1fr));gap:12px}"
    ".gallery figure{margin:0}.gallery img{width:100%;image-rendering:pixelated}"
    "details{margin:.4em 0}summary{cursor:pointer}"
    "pre{background:#f6f8fa;border:1px solid #ddd;padding:.6em;overflow-x:auto;font-size:12px}"
    "footer{margin-top:3em;font-size:12px;color:#666;border-top:1px solid #ccc;padding-top:.5em}"
    "nav.toc ul{margin:.1em 0;padding-left:1.3em}nav.toc li{margin:.05em 0}nav.toc>ul{columns:2 22em}"
    "a.anc{color:#aaa;text-decoration:none;font-weight:400;font-size:.8em;visibility:hidden}"
    "h1:hover a.anc,h2:hover a.anc,h3:hover a.anc,h4:hover a.anc,h5:hover a.anc{visibility:visible}"
    "details.sec{border-left:3px solid #ddd;padding-left:.8em;margin:.5em 0}"
    "details.sec>summary>h5,details.sec>summary>h4{display:inline;margin:0}"
    ".filters{background:#f3f4f6;border:1px solid #ddd;padding:.4em .8em;margin:.6em 0}"
    ".filters label{margin-right:1em}.filters .count{color:#555}"
    ".gallery figure:target{grid-column:1/-1}.gallery figure:target img{width:auto;max-width:100%}"
    /* printed (issue 47): a wide table is never clipped by the scroll box a
     * screen gives it; it wraps its heads and names, never below 8 pt, and
     * keeps its heads on every page; a plot keeps its size up to the line */
    "@page{size:A4;margin:12mm}"
    "@media print{body{max-width:none;padding:0;font-size:10pt}"
    ".tab{overflow:visible}table{font-size:8pt;max-width:100%}"
    "th,td.k{white-space:normal}th,td{padding:.1em .3em}table.wrap td{min-width:0}"
    "thead{display:table-header-group}tr{break-inside:avoid}"
    "figure{break-inside:avoid}figure img{max-width:100%}figcaption,.note,footer{font-size:8pt}"
    "nav.toc>ul{columns:1}a.anc,.filters{display:none}tbody tr:hover td{background:none}"
    "pre{white-space:pre-wrap;font-size:8pt}}";

/* The gallery's filters: the only script, inline, no network. */
static const char filter_js[] =
    "<script>\n"
    "document.querySelectorAll('.filters').forEach(function(f){\n"
    "  var g=document.getElementById(f.dataset.for),s=f.querySelectorAll('select');\n"
    "  function u(){var n=0;g.querySelectorAll('figure').forEach(function(x){var ok=true;\n"
    "    s.forEach(function(e){if(e.value&&x.dataset[e.dataset.k]!==e.value)ok=false;});\n"
    "    x.hidden=!ok;if(ok)n++;});f.querySelector('.count').textContent=n+' shown';}\n"
    "  s.forEach(function(e){e.addEventListener('change',u);});u();});\n"
    "</script>\n";


/* ---- overlays ---- */

static enum sl_err copy_file(const char *from, const char *to, int *missing, char *why, size_t nwhy,
                             struct sl_diag *d)
{
    *missing = 0;
    FILE *in = fopen(from, "rb");
    if (!in) {
        *missing = 1;
        snprintf(why, nwhy, "%s", strerror(errno));
        return SL_OK;
    }
    FILE *out = fopen(to, "wb");
    if (!out) {
        fclose(in);
        return sl_fail(d, SL_E_OUTPUT, to, 0, NULL, "cannot write: %s", strerror(errno));
    }
    char buf[65536];
    size_t got;
    int bad = 0;
    while ((got = fread(buf, 1, sizeof buf, in)) > 0)
        if (fwrite(buf, 1, got, out) != got)
            bad = 1;
    int rbad = ferror(in);
    fclose(in);
    if (fclose(out) != 0 || bad)
        return sl_fail(d, SL_E_OUTPUT, to, 0, NULL, "write failed");
    if (rbad)
        return sl_fail(d, SL_E_IO, from, 0, NULL, "read error while copying the overlay");
    return SL_OK;
}

/* The gallery id of a cell's overlay (a slug, unique per study). */
static void overlay_id(const struct sl_report_study *s, const struct sl_cell_record *c, char *buf, size_t n)
{
    char sc[64], vp[32], lb[48];
    sl_tab_slug(c->scene, sc, sizeof sc);
    sl_tab_slug(c->viewpoint, vp, sizeof vp);
    sl_tab_slug(c->label, lb, sizeof lb);
    snprintf(buf, n, "ov-%s-%s-%s-%dx%d-%d-%s", s->slug, sc, vp, c->vw, c->vh, c->map_size, lb);
}

static enum sl_err section_overlays(struct sl_report_doc *doc, const struct sl_report_study *s,
                                    const char *source_dir, struct sl_store *store, struct sl_diag *d)
{
    int n = 0, none = 0;
    for (int i = 0; i < s->n; i++)
        if (s->cells[i].overlay[0])
            n++;
        else
            none++;
    if (n == 0) {
        sl_report_doc_para(doc, "No cell of this study stored an error overlay (the config's outputs.overlays "
                                "was off, or the store predates overlay paths).");
        return SL_OK;
    }
    sl_report_doc_para(doc,
                       "The error overlays the runs wrote, one per cell (colours: the README's Output "
                       "section). Pick a scene, view, map size or method to narrow the gallery; a thumbnail "
                       "opens the overlay at full "
                       "size.");
    /* per shown overlay: rel, caption, scene, view, map, method, id */
    char (*str)[7][400] = sl_calloc((size_t)n, sizeof *str);
    struct sl_report_thumb *th = sl_calloc((size_t)n, sizeof *th);
    char **miss = sl_calloc((size_t)n, sizeof *miss);
    if (!str || !th || !miss) {
        free(str);
        free(th);
        free(miss);
        return sl_fail(d, SL_E_NOMEM, NULL, 0, s->name, "overlay list");
    }
    int nshown = 0, nmiss = 0;
    enum sl_err e = SL_OK;
    for (int i = 0; i < s->n && !e; i++) {
        const struct sl_cell_record *c = &s->cells[i];
        if (!c->overlay[0])
            continue;
        char src[1600], sc[64], vp[32], lb[48], path[1400], why[128] = "";
        char (*v)[400] = str[nshown];
        if (c->overlay[0] == '/' || !source_dir || !source_dir[0])
            snprintf(src, sizeof src, "%s", c->overlay);
        else
            snprintf(src, sizeof src, "%s/%s", source_dir, c->overlay);
        sl_tab_slug(c->scene, sc, sizeof sc);
        sl_tab_slug(c->viewpoint, vp, sizeof vp);
        sl_tab_slug(c->label, lb, sizeof lb);
        snprintf(v[0], sizeof v[0], "overlays/%s/%s-%s-%dx%d-%d-%s.png", s->slug, sc, vp, c->vw, c->vh,
                 c->map_size, lb);
        snprintf(v[1], sizeof v[1], c->light[0] ? "%s (%s) / %s / %d×%d / %d² / %s" : "%s%s / %s / %d×%d / %d² / %s",
                 c->scene, c->light, c->viewpoint, c->vw, c->vh, c->map_size, c->label);
        snprintf(v[2], sizeof v[2], "%s", c->scene);
        snprintf(v[3], sizeof v[3], "%s %d×%d", c->viewpoint, c->vw, c->vh);
        snprintf(v[4], sizeof v[4], "%d²", c->map_size);
        snprintf(v[5], sizeof v[5], "%s", c->label);
        overlay_id(s, c, v[6], sizeof v[6]);
        struct stat st;
        int missing = 1;
        if (stat(src, &st) != 0)
            snprintf(why, sizeof why, "%s", strerror(errno));
        else if (!S_ISREG(st.st_mode))
            snprintf(why, sizeof why, "not a file");
        else
            missing = 0;
        /* a file the store recorded is copied only as it was written: one
         * that no longer matches its size and CRC-32 is damaged, and the
         * report refuses it rather than show it */
        long long want_size = 0, size = 0;
        uint32_t want_crc = 0, crc = 0;
        if (!missing && store && sl_store_file_recorded(store, c->overlay, &want_size, &want_crc) == 1 &&
            sl_store_file_digest(src, &size, &crc, NULL) == SL_OK && (size != want_size || crc != want_crc))
            e = sl_fail(d, SL_E_IO, src, 0, NULL, "damaged overlay of cell %s/%s/%dx%d/%d/%s: %lld bytes, CRC-32 %08x, "
                        "but the store recorded %lld bytes, CRC-32 %08x; refusing to copy it into the report "
                        "(`shadowlab run CONFIG --resume` writes it again; `shadowlab verify` names every damaged "
                        "file)", c->scene, c->viewpoint, c->vw, c->vh, c->map_size, c->label, size, crc, want_size,
                        want_crc);
        if (!e && !missing && !(e = sl_report_out_path(doc->out, v[0], 1, path, sizeof path, d)))
            e = copy_file(src, path, &missing, why, sizeof why, d);
        if (e)
            break;
        if (missing) {
            char line[2000];
            snprintf(line, sizeof line, "%s: %s (%s)", v[1], c->overlay, why);
            miss[nmiss] = strdup(line);
            if (!miss[nmiss])
                e = sl_fail(d, SL_E_NOMEM, NULL, 0, s->name, "overlay list");
            else
                nmiss++;
            continue;
        }
        th[nshown] = (struct sl_report_thumb){v[0], v[1], v[2], v[3], v[4], v[5], v[6]};
        nshown++;
    }
    if (!e) {
        if (nshown)
            sl_report_doc_filter_gallery(doc, th, nshown);
        if (nmiss) {
            sl_report_doc_para(doc, "%d overlay(s) recorded in the store but missing from %s:", nmiss,
                               source_dir && source_dir[0] ? source_dir : "the database's folder");
            sl_report_doc_list(doc, (const char *const *)miss, nmiss);
        }
        if (none)
            sl_report_doc_para(doc, "%d cell(s) of this study stored no overlay.", none);
    }
    for (int k = 0; k < nmiss; k++)
        free(miss[k]);
    free(str);
    free(th);
    free(miss);
    return e;
}

/* ---- per scene and view: collapsible, the headline figures of each cell ---- */

static enum sl_err section_views(struct sl_report_doc *doc, const struct sl_report_study *s, struct sl_diag *d)
{
    sl_report_doc_para(doc, "Per view (scene, viewpoint, viewport), the whole image's figures of every method "
                            "and map size; open a view for its table and the links to its overlays.");
    enum sl_err e = SL_OK;
    for (int sc = 0; sc < s->nscenes && !e; sc++) {
        char anchor[160], slug[64];
        sl_tab_slug(s->scenes[sc], slug, sizeof slug);
        snprintf(anchor, sizeof anchor, "%s-scene-%s", s->slug, slug);
        /* the light in words after the scene's name, in every heading: its first view's */
        const char *light = "";
        for (int v = 0; v < s->nviews && !light[0]; v++)
            if (!strcmp(s->views[v].scene, s->scenes[sc]))
                light = s->views[v].light;
        char lw[64] = "";
        if (light[0])
            snprintf(lw, sizeof lw, " (%s)", light);
        sl_report_doc_heading(doc, 4, anchor, "%s / %s%s", s->name, s->scenes[sc], lw);
        for (int v = 0; v < s->nviews && !e; v++) {
            const struct sl_report_view *w = &s->views[v];
            if (strcmp(w->scene, s->scenes[sc]))
                continue;
            char vs[32], id[200];
            sl_tab_slug(w->viewpoint, vs, sizeof vs);
            snprintf(anchor, sizeof anchor, "%s-view-%s-%s-%dx%d", s->slug, slug, vs, w->vw, w->vh);
            sl_report_doc_section_begin(doc, 5, anchor, "%s / %s%s / %s / %d×%d", s->name, w->scene, lw,
                                        w->viewpoint, w->vw, w->vh);
            if (w->n_outside_cone) {
                /* a spot light's cone leaves part of the view unlit by definition (view.h) */
                sl_report_doc_para(doc, "Outside the spot's cone: %llu px, %.2f%% of the image (unlit by "
                                        "definition: counted with the PnFL pixels, never scored as errors).",
                                   (unsigned long long)w->n_outside_cone,
                                   100.0 * (double)w->n_outside_cone / (double)w->n_image);
            }
            snprintf(id, sizeof id, "%s-view-%s-%s-%dx%d", s->slug, slug, vs, w->vw, w->vh);
            struct sl_tab t;
            sl_tab_init(&t, id, 8, 2, "%s / %s%s / %s / %d×%d: whole image, %% of its non-background pixels",
                               s->name, w->scene, lw, w->viewpoint, w->vw, w->vh);
            static const char *const heads[] = {"method", "map", "wrong %", "wrongly lit %", "wrongly shadowed %",
                                                "uncertain %", "traced %", "layers + step ms"};
            const char *rel[2 * SL_REPORT_MAXKEYS], *text[2 * SL_REPORT_MAXKEYS];
            char rels[2 * SL_REPORT_MAXKEYS][200], texts[2 * SL_REPORT_MAXKEYS][80];
            int nl = 0, once = 0;
            for (int k = 0; k < 8; k++)
                sl_tab_head(&t, k, "%s", heads[k]);
            for (int l = 0; l < s->nlabels; l++)
                for (int m = 0; m < s->nmaps; m++) {
                    const struct sl_cell_record *c = sl_report_study_cell(s, w, s->labels[l], s->maps[m]);
                    int r = c ? sl_report_region(c, 0) : -1;
                    if (!c || r < 0)
                        continue;
                    const uint64_t *n = c->fig.r[r].n;
                    double px = n[SL_FIG_pixels] ? (double)n[SL_FIG_pixels] : NAN;
                    sl_tab_row(&t, m == 0);
                    sl_tab_cell(&t, 0, "%s", sl_report_display(s, c->label));
                    sl_tab_cell(&t, 1, "%d²", c->map_size);
                    sl_tab_cell(&t, 2, "%.3f", 100.0 * (double)n[SL_FIG_wrong] / px);
                    sl_tab_cell(&t, 3, "%.3f", 100.0 * (double)n[SL_FIG_light_incorrect] / px);
                    sl_tab_cell(&t, 4, "%.3f", 100.0 * (double)n[SL_FIG_shadow_incorrect] / px);
                    sl_tab_cell(&t, 5, "%.3f", 100.0 * (double)n[SL_FIG_uncertain] / px);
                    sl_tab_cell(&t, 6, "%.3f", 100.0 * (double)n[SL_FIG_traced] / px);
                    sl_tab_cell(&t, 7, "%.3f%s", sl_report_cell_ms(c, 0), c->runs == 1 ? SL_REPORT_ONCE : "");
                    once |= c->runs == 1;
                    char ov[200], file[300], sc2[64], lb[48];
                    sl_tab_slug(c->label, lb, sizeof lb);
                    sl_tab_slug(c->scene, sc2, sizeof sc2);
                    snprintf(file, sizeof file, "overlays/%s/%s-%s-%dx%d-%d-%s.png", s->slug, sc2, vs, c->vw,
                             c->vh, c->map_size, lb);
                    /* only overlays the gallery holds: a link never points at nothing */
                    if (c->overlay[0] && sl_report_out_has(doc->out, file) && nl < 2 * SL_REPORT_MAXKEYS) {
                        overlay_id(s, c, ov, sizeof ov);
                        snprintf(rels[nl], sizeof rels[nl], "#%s", ov);
                        snprintf(texts[nl], sizeof texts[nl], "%s %d²", c->label, c->map_size);
                        rel[nl] = rels[nl];
                        text[nl] = texts[nl];
                        nl++;
                    }
                }
            /* layers + step ms: the same sum as the accuracy table's, so one name */
            sl_tab_notef(&t, "layers + step ms: the cell's stages summed (ms_cost: the shadow maps it reads or "
                             "renders, post passes, lookup, readback, rays), medians over the timed repetitions.");
            if (once)
                sl_report_tab_once(&t);
            e = sl_report_doc_table(doc, &t, d);
            sl_tab_free(&t);
            if (!e && nl)
                sl_report_doc_links(doc, "Overlays:", rel, text, nl);
            sl_report_doc_section_end(doc);
        }
    }
    return e;
}

/* ---- the full figure tables of a study (table.c), linked ---- */

static enum sl_err section_all_figures(struct sl_report_doc *doc, const struct sl_report_study *s,
                                       struct sl_diag *d)
{
    static const struct { enum sl_table_format fmt; const char *ext, *name; } forms[] = {
        {SL_TABLE_MD, "md", "Markdown"}, {SL_TABLE_CSV, "csv", "CSV"}, {SL_TABLE_LATEX, "tex", "LaTeX"}};
    char rels[3][200];
    const char *rel[3], *text[3];
    for (int k = 0; k < 3; k++) {
        char path[1400];
        snprintf(rels[k], sizeof rels[k], "data/%s-figures.%s", s->slug, forms[k].ext);
        enum sl_err e = sl_report_out_path(doc->out, rels[k], 1, path, sizeof path, d);
        if (e)
            return e;
        FILE *f = fopen(path, "w");
        if (!f)
            return sl_fail(d, SL_E_OUTPUT, path, 0, NULL, "cannot write: %s", strerror(errno));
        e = sl_table_write(f, forms[k].fmt, s->name, s->cells, s->n, d);
        if (fclose(f) != 0 && !e)
            e = sl_fail(d, SL_E_OUTPUT, path, 0, NULL, "write failed");
        if (e)
            return e;
        rel[k] = rels[k];
        text[k] = forms[k].name;
    }
    sl_report_doc_links(doc, "Every figure of every cell (figures.h), one table per scene, viewpoint, viewport "
                             "and method, with each cell's git SHA, config hash and machine:", rel, text, 3);
    return SL_OK;
}

/* ---- one study ---- */

static void join_names(char *buf, size_t n, const char (*names)[64], int count)
{
    size_t k = 0;
    buf[0] = '\0';
    for (int i = 0; i < count && k < n; i++)
        k += (size_t)snprintf(buf + k, n - k, "%s%s", i ? ", " : "", names[i]);
}

/* The study's summary: what was run, the headline table, the plots. */
static enum sl_err section_summary(struct sl_report_doc *doc, struct sl_report_study *s, const char *gnuplot,
                                   struct sl_diag *d)
{
    char anchor[96], scenes[1024] = "", labels[2048] = "", maps[512] = "", runs[512] = "", other[512] = "";
    snprintf(anchor, sizeof anchor, "summary-%s", s->slug);
    sl_report_doc_heading(doc, 3, anchor, "Study %s", s->name);
    join_names(scenes, sizeof scenes, (const char (*)[64])s->scenes, s->nscenes);
    size_t k = 0, ko = 0;
    for (int l = 0; l < s->nlabels; l++) {
        k += (size_t)snprintf(labels + k, k < sizeof labels ? sizeof labels - k : 0, "%s%s (%s)", l ? ", " : "",
                              s->labels[l], s->methods[l]);
        if (!sl_report_label_in(s, l, SL_REPORT_MODERNO) && !sl_report_label_in(s, l, SL_REPORT_MORAIS) &&
            !sl_report_label_in(s, l, SL_REPORT_CURTIS))
            ko += (size_t)snprintf(other + ko, ko < sizeof other ? sizeof other - ko : 0, "%s%s", ko ? ", " : "",
                                   s->labels[l]);
        if (k >= sizeof labels || ko >= sizeof other)
            break;
    }
    k = 0;
    for (int m = 0; m < s->nmaps && k < sizeof maps; m++)
        k += (size_t)snprintf(maps + k, sizeof maps - k, "%s%d²", m ? ", " : "", s->maps[m]);
    int64_t seen[64];
    int nseen = 0;
    k = 0;
    for (int i = 0; i < s->n; i++) {
        int j = 0;
        while (j < nseen && seen[j] != s->cells[i].run_id)
            j++;
        if (j == nseen && nseen < 64 && k < sizeof runs) {
            seen[nseen++] = s->cells[i].run_id;
            k += (size_t)snprintf(runs + k, sizeof runs - k, "%s%lld", j ? ", " : "", (long long)s->cells[i].run_id);
        }
    }
    sl_report_doc_para(doc, "%d cell(s) from run(s) %s; %d view(s) of the scene(s) %s; shadow maps %s; methods %s.",
                       s->n, runs, s->nviews, scenes, maps, labels);
    if (!s->moderno && !s->morais && !s->curtis)
        sl_report_doc_para(doc, "No method of Moderno 2011, Morais 2015 or Curtis 2009 ran in this study (each "
                                "method says which work it comes from): it gets the sections every study gets, this summary "
                                "with its plots, %s%sthe costs, the overlays and the figure tables, and no thesis "
                                "section.", s->area ? "the soft-shadow table of its area-light cells, " : "",
                           s->frac ? "the fractional errors, " : "");
    else
        sl_report_doc_para(doc, "Thesis sections, from the methods that ran: %s%s%s%s%s%s%s",
                           s->moderno ? "Moderno 2011's tables" : "", s->moderno && (s->morais || s->curtis) ? ", " : "",
                           s->morais ? "Morais 2015's tables" : "", s->morais && s->curtis ? ", " : "",
                           s->curtis ? "Curtis 2009's soft-shadow table" : "", ".",
                           other[0] ? "" : " Every method belongs to one of them.");
    if (other[0] && (s->moderno || s->morais || s->curtis))
        sl_report_doc_para(doc, "Methods of no thesis (%s) appear in the summary, the plots, %s%sthe costs and "
                                "the figure tables.", other, s->area ? "the soft-shadow table, " : "",
                           s->frac ? "the fractional errors, " : "");
    /* values not finite are a result of their own, left out of the figures:
     * said before any figure is read */
    uint64_t nonfinite = 0;
    int nbad = 0;
    char badcells[1024] = "";
    k = 0;
    for (int i = 0; i < s->n; i++) {
        const struct sl_cell_record *c = &s->cells[i];
        if (!c->nonfinite)
            continue;
        nonfinite += c->nonfinite;
        if (nbad++ < 8 && k < sizeof badcells)
            k += (size_t)snprintf(badcells + k, sizeof badcells - k, "%s%s/%s %d² %s (%llu)", nbad > 1 ? ", " : "",
                                  c->scene, c->viewpoint, c->map_size, c->label, (unsigned long long)c->nonfinite);
    }
    if (nbad)
        sl_report_doc_para(doc, "NON-FINITE: %d cell(s) hold %llu value(s) not finite (NaN, ±inf) or out of range: "
                                "%s%s. Their pixels are left out of the figures (a package's verdict there is "
                                "uncertain), so those cells' figures describe the rest of the image only.",
                           nbad, (unsigned long long)nonfinite, badcells, nbad > 8 ? ", ..." : "");
    int point = 0;   /* hard figures of cells under an area light */
    for (int i = 0; i < s->n && !point; i++)
        point = s->cells[i].has_soft && s->cells[i].fig.nregions > 0 && !s->cells[i].frac;
    if (point)
        sl_report_doc_para(doc, "Under an area light the hard-shadow methods take the light for a point at its "
                                "centre: their wrong pixels and decisions in the hard-shadow tables and plots are "
                                "counted against that point's own truth; the soft-shadow table scores the same "
                                "verdicts (lit 1, shadowed 0, uncertain 0.5) against the area truth.");
    return sl_report_plot_accuracy(doc, s, gnuplot, d);
}

static int has_chain(const struct sl_report_study *s)
{
    for (int l = 0; l < s->nlabels; l++)
        if (strcmp(s->methods[l], "chain") == 0)
            return 1;
    return 0;
}

/* The study's detail: the thesis tables (only where the thesis's methods
 * ran, layouts.c), costs, overlays, views, figures. */
static enum sl_err section_study(struct sl_report_doc *doc, struct sl_report_study *s, const char *gnuplot,
                                 const char *source_dir, struct sl_store *store, struct sl_diag *d)
{
    char anchor[96];
    snprintf(anchor, sizeof anchor, "study-%s", s->slug);
    sl_report_doc_heading(doc, 2, anchor, "Study %s in detail", s->name);
    enum sl_err e = SL_OK;
    if (s->moderno) {
        sl_report_doc_heading(doc, 3, NULL, "%s: tables in Moderno 2011's layout", s->name);
        e = sl_report_moderno(doc, s, d);
    }
    if (!e && s->moderno && sl_report_fidelity_applies(s->cells, s->n)) {
        sl_report_doc_heading(doc, 3, NULL, "%s: fidelity to Moderno 2011 (Primitives)", s->name);
        e = sl_report_fidelity(doc, s, d);
    }
    if (!e && sl_report_fidelity_scenes_applies(s)) {
        sl_report_doc_heading(doc, 3, NULL, "%s: validation against Moderno 2011 (Bench, Trees, Flowers)", s->name);
        e = sl_report_fidelity_scenes(doc, s, d);
    }
    if (!e && s->morais) {
        sl_report_doc_heading(doc, 3, NULL, "%s: tables in Morais 2015's layout", s->name);
        e = sl_report_morais(doc, s, d);
        if (!e)
            e = sl_report_fidelity_morais(doc, s, d);
    }
    if (!e && s->area) {   /* the only table of an area light's soft figures: any study that has them */
        sl_report_doc_heading(doc, 3, NULL, "%s: soft shadows (area lights)%s", s->name,
                              s->curtis ? ", Curtis 2009" : "");
        e = sl_report_curtis(doc, s, d);
    }
    if (!e && s->frac) {
        sl_report_doc_heading(doc, 3, NULL, "%s: fractional errors", s->name);
        e = sl_report_fractional(doc, s, gnuplot, d);
    }
    if (!e)   /* a heading of its own when the study has paths */
        e = sl_report_motion(doc, s, gnuplot, d);
    /* not a thesis's: any shadow map's pixels have an aliasing error m, and
     * seed 004's own study (configs/aliasing.yaml) runs none of the theses' methods */
    if (!e && sl_report_aliasing_applies(s)) {
        sl_report_doc_heading(doc, 3, NULL, "%s: aliasing error m", s->name);
        e = sl_report_aliasing(doc, s, gnuplot, d);
    }
    if (!e && has_chain(s)) {
        sl_report_doc_heading(doc, 3, NULL, "%s: the chain's steps per scene", s->name);
        e = sl_report_plot_chain(doc, s, gnuplot, d);
    }
    if (!e) {
        sl_report_doc_heading(doc, 3, NULL, "%s: cost", s->name);
        e = sl_report_costs(doc, s, d);
    }
    if (!e) {
        sl_report_doc_heading(doc, 3, NULL, "%s: error overlays", s->name);
        e = section_overlays(doc, s, source_dir, store, d);
    }
    if (!e) {
        sl_report_doc_heading(doc, 3, NULL, "%s: scenes and views", s->name);
        e = section_views(doc, s, d);
    }
    if (!e) {
        sl_report_doc_heading(doc, 3, NULL, "%s: all figures", s->name);
        e = section_all_figures(doc, s, d);
    }
    return e;
}

/* ---- completeness ---- */

/* "N of M cells" of every sweep the store holds, from the plan its runs
 * recorded, and the cells an incomplete one lacks. */
static enum sl_err section_completeness(struct sl_report_doc *doc, const struct sl_report_input *in,
                                        struct sl_diag *d)
{
    if (!in->store)
        return SL_OK;
    struct sl_store_sweep *w = NULL;
    int n = 0;
    enum sl_err e = sl_store_sweeps(in->store, &w, &n, d);
    if (e)
        return e;
    sl_report_doc_heading(doc, 2, "completeness", "Completeness");
    for (int i = 0; i < n && !e; i++) {
        const struct sl_store_sweep *s = &w[i];
        if (s->planned < 0) {
            sl_report_doc_para(doc, "Sweep %s (config hash %s, run(s) %s): %d cell(s); its plan is not recorded "
                               "(a store written before schema 23), so whether it is complete is unknown.",
                               s->study, s->config_hash, s->runs, s->stored);
            continue;
        }
        if (s->stored >= s->planned) {
            sl_report_doc_para(doc, "Sweep %s (config hash %s, run(s) %s): %d of %d cells: complete.", s->study,
                               s->config_hash, s->runs, s->stored, s->planned);
            continue;
        }
        sl_report_doc_para(doc, "Sweep %s (config hash %s, run(s) %s): %d of %d cells: INCOMPLETE; "
                           "every table and plot of this report lacks the %d cell(s) below (`shadowlab run CONFIG "
                           "--resume`, or a merge of the missing shards, completes it).", s->study, s->config_hash,
                           s->runs, s->stored, s->planned, s->planned - s->stored);
        struct sl_store_key *k = NULL;
        int nk = 0;
        if ((e = sl_store_missing(in->store, s->config_hash, &k, &nk, d)))
            break;
        char anchor[64];
        snprintf(anchor, sizeof anchor, "missing-%s", s->config_hash);
        struct sl_tab t;
        sl_tab_init(&t, anchor, 6, 6, "Cells of the sweep the store lacks");
        static const char *const heads[] = {"cell", "scene", "viewpoint", "viewport", "map size", "label"};
        for (int c = 0; c < 6; c++)
            sl_tab_head(&t, c, "%s", heads[c]);
        for (int j = 0; j < nk; j++) {
            sl_tab_row(&t, 0);
            sl_tab_cell(&t, 0, "%d", k[j].index);
            sl_tab_cell(&t, 1, "%s", k[j].scene);
            sl_tab_cell(&t, 2, "%s", k[j].viewpoint);
            sl_tab_cell(&t, 3, "%dx%d", k[j].vw, k[j].vh);
            sl_tab_cell(&t, 4, "%d", k[j].map_size);
            sl_tab_cell(&t, 5, "%s", k[j].label);
        }
        e = sl_report_doc_table(doc, &t, d);
        sl_tab_free(&t);
        free(k);
    }
    free(w);
    return e;
}

/* ---- provenance ---- */

static enum sl_err section_provenance(struct sl_report_doc *doc, const struct sl_report_input *in,
                                      struct sl_diag *d)
{
    sl_report_doc_heading(doc, 2, "provenance", "Provenance");
    sl_report_doc_para(doc,
                       "Every number above comes from a cell stored by one of these runs (the run ids in each "
                       "study's summary; each cell's git SHA, config hash and machine are in the figure tables). "
                       "Each run's filled-in config follows the table.");
    if (in->nruns == 0) {
        sl_report_doc_para(doc, "The store lists no runs.");
        return SL_OK;
    }
    struct sl_tab t;
    sl_tab_init(&t, "provenance-runs", 12, 12, "Runs in the results store");
    t.wrap = 1;
    static const char *const heads[] = {"run", "study", "time (UTC)", "git SHA", "config", "config hash", "host",
                                        "CPU", "ISA", "GL renderer", "Embree", "threads"};
    for (int k = 0; k < 12; k++)
        sl_tab_head(&t, k, "%s", heads[k]);
    for (int i = 0; i < in->nruns; i++) {
        const struct sl_store_run *r = &in->runs[i];
        sl_tab_row(&t, 0);
        sl_tab_cell(&t, 0, "%lld (%d cells)", (long long)r->run_id, r->ncells);
        sl_tab_cell(&t, 1, "%s", r->study);
        sl_tab_cell(&t, 2, "%s", r->prov.time_utc);
        sl_tab_cell(&t, 3, "%s", r->prov.git_sha);
        sl_tab_cell(&t, 4, "%s", r->config_path);
        sl_tab_cell(&t, 5, "%s", r->config_hash);
        sl_tab_cell(&t, 6, "%s", r->prov.host);
        sl_tab_cell(&t, 7, "%s", r->prov.cpu);
        sl_tab_cell(&t, 8, "%s", r->prov.isa);
        sl_tab_cell(&t, 9, "%s (%s)", r->prov.gl_renderer, r->prov.gl_version);
        sl_tab_cell(&t, 10, "%s", r->prov.embree);
        sl_tab_cell(&t, 11, "%d (LP_NUM_THREADS %s)", r->prov.threads,
                           r->prov.lp_threads[0] ? r->prov.lp_threads : "unset");
    }
    enum sl_err e = sl_report_doc_table(doc, &t, d);
    sl_tab_free(&t);
    for (int i = 0; i < in->nruns && !e; i++) {
        const struct sl_store_run *r = &in->runs[i];
        char summary[800];
        snprintf(summary, sizeof summary, "Run %lld: config %s (hash %s)", (long long)r->run_id, r->config_path,
                 r->config_hash);
        if (r->config_text && r->config_text[0])
            sl_report_doc_details(doc, summary, r->config_text);
        else
            sl_report_doc_para(doc, "%s: the config text was not stored.", summary);
    }
    return e;
}

/* ---- pages ---- */

static void page_begin(struct sl_report_doc *doc, const struct sl_report_input *in, int nstudies)
{
    sl_report_doc_heading(doc, 1, "top", "shadowlab report");
    sl_report_doc_para(doc,
                       "Shadow-map errors against an Embree ray-traced truth, pixel by pixel: %d cell(s) of %d "
                       "study(ies) from %d run(s)%s%s. The summary comes first (what was run, the headline "
                       "table, the plots); each study's detail follows.",
                       in->ncells, nstudies, in->nruns, in->source && in->source[0] ? " in " : "",
                       in->source ? in->source : "");
}

static char *page_head(void)
{
    char *h = NULL;
    size_t n = 0;
    FILE *m = open_memstream(&h, &n);
    if (!m)
        return NULL;
    fputs("<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
          "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
          "<title>shadowlab report</title>\n<style>", m);
    fputs(css, m);
    fputs("</style>\n</head>\n<body>\n", m);
    if (fclose(m) != 0) {
        free(h);
        return NULL;
    }
    return h;
}

/* The footer goes into the body (Markdown too); the script and closing tags are the tail. */
static void page_end(struct sl_report_doc *doc, const struct sl_report_input *in, int self_contained)
{
    char when[32] = "";
    time_t now = time(NULL);
    struct tm tm;
    if (gmtime_r(&now, &tm))
        strftime(when, sizeof when, "%Y-%m-%dT%H:%M:%SZ", &tm);
    sl_report_doc_raw_html(doc, "<footer>");
    fprintf(doc->md, "---\n\n");
    sl_report_doc_para(doc, "Written by shadowlab %s at %s from %s. %s", sl_git_sha(), when,
                       in->source && in->source[0] ? in->source : "cells in memory",
                       self_contained ? "One file: every image and plot is embedded, nothing is fetched."
                                          : "Offline page: it links its images, plots and .tex files in this "
                                            "folder and fetches nothing from the network.");
    sl_report_doc_raw_html(doc, "</footer>\n");
}

enum sl_err sl_report_build(const struct sl_report_input *in, const char *out_dir, const char *gnuplot,
                            struct sl_diag *d)
{
    return sl_report_build_with(in, out_dir, gnuplot, 0, 0, d);
}

enum sl_err sl_report_build_with(const struct sl_report_input *in, const char *out_dir, const char *gnuplot,
                                 int self_contained, int latex, struct sl_diag *d)
{
    if (!in || in->ncells < 0 || (in->ncells > 0 && !in->cells) || in->nruns < 0 || (in->nruns > 0 && !in->runs))
        return sl_fail(d, SL_E_USAGE, NULL, 0, NULL, "sl_report_build: bad arguments");
    if (in->ncells == 0)
        return sl_fail(d, SL_E_USAGE, in->source, 0, NULL, "no stored cell: nothing to report");
    char gp[1024];
    enum sl_err e = sl_report_gnuplot_find(gnuplot, gp, sizeof gp, d);
    if (e)
        return e;

    /* studies in order of first appearance; each study's cells contiguous, in input order */
    struct sl_cell_record *cells = sl_calloc((size_t)in->ncells, sizeof *cells);
    struct sl_report_study *studies = sl_calloc((size_t)in->ncells, sizeof *studies);
    if (!cells || !studies) {
        free(cells);
        free(studies);
        return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "%d cells", in->ncells);
    }
    int nstudies = 0, pos = 0;
    for (int i = 0; i < in->ncells; i++) {
        int seen = 0;
        for (int j = 0; j < i && !seen; j++)
            seen = strcmp(in->cells[j].study, in->cells[i].study) == 0;
        if (seen)
            continue;
        struct sl_report_study *s = &studies[nstudies++];
        snprintf(s->name, sizeof s->name, "%s", in->cells[i].study[0] ? in->cells[i].study : "(unnamed)");
        sl_tab_slug(in->cells[i].study[0] ? in->cells[i].study : "unnamed", s->slug, sizeof s->slug);
        s->cells = cells + pos;
        for (int j = i; j < in->ncells; j++)
            if (strcmp(in->cells[j].study, in->cells[i].study) == 0)
                cells[pos++] = in->cells[j];
        s->n = (int)(cells + pos - s->cells);
    }
    for (int k = 0; k < nstudies && !e; k++)
        e = sl_report_study_keys(&studies[k], d);
    /* two studies whose names fold to one slug get numbered anchors and files */
    for (int k = 1; k < nstudies; k++)
        for (int j = 0; j < k; j++)
            if (strcmp(studies[k].slug, studies[j].slug) == 0) {
                char t[64];
                snprintf(t, sizeof t, "%.50s-%d", studies[k].slug, k + 1);
                snprintf(studies[k].slug, sizeof studies[k].slug, "%s", t);
            }

    struct sl_report_out out;
    memset(&out, 0, sizeof out);
    struct sl_report_doc doc;
    memset(&doc, 0, sizeof doc);
    doc.out = &out;
    doc.self_contained = self_contained;
    if (!e)
        e = sl_report_out_begin(&out, out_dir, d);
    if (!e)
        e = sl_report_doc_open(&doc, latex, d);
    if (!e) {
        page_begin(&doc, in, nstudies);
        e = section_completeness(&doc, in, d);   /* first: what the numbers below lack */
    }
    if (!e)
        sl_report_doc_heading(&doc, 2, "summary", "Summary");
    for (int k = 0; k < nstudies && !e; k++)
        e = section_summary(&doc, &studies[k], gp, d);
    for (int k = 0; k < nstudies && !e; k++)
        e = section_study(&doc, &studies[k], gp, in->source_dir, in->store, d);
    if (!e)
        e = section_provenance(&doc, in, d);
    if (!e)
        page_end(&doc, in, self_contained);
    char *head = e ? NULL : page_head();
    if (!e && !head)
        e = sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "report page");
    if (!e) {
        char tail[sizeof filter_js + 32];
        snprintf(tail, sizeof tail, "%s</body>\n</html>\n", filter_js);
        e = sl_report_doc_finish(&doc, head, tail, "shadowlab report", d);
    }
    free(head);
    sl_report_doc_free(&doc);
    sl_theses_free();   /* the theses' numbers the sections read (theses.h); the next report reads them anew */
    if (!e)
        e = sl_report_out_commit(&out, d);
    else
        sl_report_out_abort(&out);
    free(cells);
    free(studies);
    return e;
}
