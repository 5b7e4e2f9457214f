/*
 * cite.c — `shadowlab cite [STORE] [--all]`: BibTeX for what a paper's
 * numbers came from.
 *
 * Without STORE: shadowlab's own entry and Embree's (every truth is
 * Embree's). With STORE: those, then the references of every method the
 * store's cells ran, in the order they first appear: a built-in method's
 * from its declaration (struct sl_method's `cite`: keys of the
 * bibliography below), a technique package's from the `references.bib` in
 * its folder (found on the search path as `run` finds it). A method or
 * package that gives none gets a note on stderr naming it, so nothing is
 * dropped unsaid; stdout stays BibTeX alone, so `shadowlab cite DB >
 * refs.bib` goes straight to bibtex. `--all`: every built-in method's and
 * every package's on the search path (doc/references.md's BibTeX block is
 * that output).
 *
 * Choices the issue left open, with why:
 *  - A package's BibTeX is a `references.bib` file in its folder, not a
 *    key of technique.yaml: BibTeX is multi-line text with braces, which a
 *    YAML string carries badly and a researcher already keeps as a .bib;
 *    technique.yaml's one-line `cite:` stays the reference for people
 *    (`show technique`). An entry of a key already printed (two packages
 *    citing one paper, a package citing what a built-in method cites) is
 *    printed once, the first seen.
 *  - shadowlab's entry is @misc (every BibTeX style knows it; @software is
 *    biblatex's) and names no URL, as the project publishes none yet
 *    (CITATION.cff says the same). With STORE its note names the commits
 *    the store's runs were built from.
 */
#define _GNU_SOURCE   /* getopt_long */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "cli.h"
#include "method.h"
#include "store.h"
#include "technique.h"
#include "util.h"

#ifndef SL_VERSION
#define SL_VERSION "unknown"
#endif

/* The bibliography of the built-in methods and of the truth (doc/references.md
 * says where each is used). Text as BibTeX wants it: LaTeX accents, {{...}}
 * for a name that is not "First Last". */
static const struct bib {
    const char *key, *entry;
} bibliography[] = {
    {"wald2014embree",
     "@article{wald2014embree,\n"
     "  author = {Ingo Wald and Sven Woop and Carsten Benthin and Gregory S. Johnson and Manfred Ernst},\n"
     "  title = {Embree: A Kernel Framework for Efficient {CPU} Ray Tracing},\n"
     "  journal = {ACM Transactions on Graphics},\n"
     "  volume = {33},\n  number = {4},\n  pages = {143:1--143:8},\n  year = {2014},\n"
     "  doi = {10.1145/2601097.2601199}\n}\n"},
    {"moderno2011",
     "@mastersthesis{moderno2011,\n"
     "  author = {Dave Lage Moderno},\n"
     "  title = {Shadow Mapping and Ray-Tracing},\n"
     "  school = {Universidade do Minho},\n"
     "  type = {Master's thesis (Mestrado em Inform{\\'a}tica)},\n"
     "  year = {2011}\n}\n"},
    {"morais2015",
     "@mastersthesis{morais2015,\n"
     "  author = {F{\\'a}bio da Costa Morais},\n"
     "  title = {Rasterization + Ray Tracing: Rendering of Hard Shadows},\n"
     "  school = {Departamento de Inform{\\'a}tica, Escola de Engenharia, Universidade do Minho},\n"
     "  type = {Master's thesis (Mestrado em Engenharia Inform{\\'a}tica)},\n"
     "  year = {2015},\n  month = oct\n}\n"},
    {"hertel2009",
     "@misc{hertel2009,\n"
     "  author = {Stefan Hertel and Kai Hormann and R{\\\"u}diger Westermann},\n"
     "  title = {A Hybrid {GPU} Rendering Pipeline for Alias-Free Hard Shadows},\n"
     "  year = {2009}\n}\n"},
    {"curtis2009",
     "@mastersthesis{curtis2009,\n"
     "  author = {Aaron Curtis},\n"
     "  title = {Real-time Soft Shadows on the {GPU} via {Monte Carlo} Sampling},\n"
     "  school = {University of Maryland, Baltimore County},\n"
     "  type = {Master's thesis (M.S. Computer Science)},\n"
     "  year = {2009}\n}\n"},
    {"williams1978",
     "@inproceedings{williams1978,\n"
     "  author = {Lance Williams},\n"
     "  title = {Casting Curved Shadows on Curved Surfaces},\n"
     "  booktitle = {Proceedings of ACM SIGGRAPH '78},\n"
     "  volume = {12},\n  pages = {270--274},\n  year = {1978}\n}\n"},
    {"wimmer2004",
     "@inproceedings{wimmer2004,\n"
     "  author = {Michael Wimmer and Daniel Scherzer and Werner Purgathofer},\n"
     "  title = {Light Space Perspective Shadow Maps},\n"
     "  booktitle = {Proceedings of the Eurographics Symposium on Rendering 2004},\n"
     "  pages = {143--152},\n  year = {2004}\n}\n"},
    {NULL, NULL},
};

static const char *bib_find(const char *key, size_t n)
{
    for (const struct bib *b = bibliography; b->key; b++)
        if (strlen(b->key) == n && !strncmp(b->key, key, n))
            return b->entry;
    return NULL;
}

/* the keys printed so far (each entry once) */
struct printed {
    char key[128][64];
    int  n;
};

static int printed_has(struct printed *p, const char *key, size_t n)
{
    for (int i = 0; i < p->n; i++)
        if (strlen(p->key[i]) == n && !strncmp(p->key[i], key, n))
            return 1;
    if (p->n < 128)
        snprintf(p->key[p->n++], sizeof p->key[0], "%.*s", (int)n, key);
    return 0;
}

static void print_shadowlab(const char *commits, struct printed *p)
{
    printed_has(p, "shadowlab", 9);
    printf("@misc{shadowlab,\n"
           "  author = {{the shadowlab authors}},\n"
           "  title = {shadowlab: shadow techniques measured pixel by pixel against an exact ray-traced truth},\n"
           "  note = {Version %s%s%s},\n"
           "  year = {2026}\n}\n\n",
           SL_VERSION, commits[0] ? "; results from git " : "", commits);
}

/* A built-in method's keys ("a b"), each entry once; 0, or the exit code
 * when a key is not in the bibliography (a defect of the method's table). */
static int print_keys(const char *who, const char *keys, struct printed *p)
{
    for (const char *q = keys; *q;) {
        q += strspn(q, " ");
        size_t n = strcspn(q, " ");
        if (!n)
            break;
        const char *e = bib_find(q, n);
        if (!e) {
            fprintf(stderr, "shadowlab: cite: %s cites '%.*s', which is not in shadowlab's bibliography "
                            "(harness/cli/cite.c)\n", who, (int)n, q);
            return 3;
        }
        if (!printed_has(p, q, n))
            printf("%s\n", e);
        q += n;
    }
    return 0;
}

/* A package's references.bib: each entry ("@type{key, ... }", braces
 * balanced) printed once by key. 0, or 2 naming the file and line of an
 * entry that does not parse (a package is input). */
static int print_bibfile(const char *path, struct printed *p, int *found)
{
    FILE *f = fopen(path, "rb");
    *found = f != NULL;
    if (!f)
        return 0;
    char *text = NULL;
    size_t cap = 0, len = 0;
    for (;;) {
        if (len + 4096 + 1 > cap) {
            char *g = realloc(text, cap = cap ? 2 * cap : 8192);
            if (!g) {
                free(text);
                fclose(f);
                fprintf(stderr, "shadowlab: cite: %s: out of memory\n", path);
                return 3;
            }
            text = g;
        }
        size_t k = fread(text + len, 1, 4096, f);
        len += k;
        if (k < 4096)
            break;
        if (len > (1u << 20)) {
            free(text);
            fclose(f);
            fprintf(stderr, "shadowlab: cite: %s: over 1 MiB: not a package's references\n", path);
            return 2;
        }
    }
    fclose(f);
    text[len] = 0;
    int rc = 0, line = 1;
    for (size_t i = 0; i < len && !rc;) {
        if (text[i] != '@') {
            line += text[i] == '\n';
            i++;
            continue;
        }
        size_t start = i, b = i + 1;
        int at = line;
        while (b < len && text[b] != '{' && text[b] != '\n')
            b++;
        if (b >= len || text[b] != '{') {
            fprintf(stderr, "shadowlab: cite: %s:%d: '@' starts no entry (expected @type{key, ...})\n", path, at);
            rc = 2;
            break;
        }
        size_t kb = b + 1, kn = strcspn(text + kb, ",}\n");
        while (kn && text[kb + kn - 1] == ' ')
            kn--;
        int depth = 0;
        size_t e = b;
        for (; e < len; e++) {
            line += text[e] == '\n';
            if (text[e] == '{')
                depth++;
            else if (text[e] == '}' && --depth == 0)
                break;
        }
        if (e >= len || !kn) {
            if (!kn)
                fprintf(stderr, "shadowlab: cite: %s:%d: an entry without a key (expected @type{key, ...})\n", path,
                        at);
            else
                fprintf(stderr, "shadowlab: cite: %s:%d: '%.*s': the entry's braces do not close before the end of "
                                "the file\n", path, at, (int)(kn < 64 ? kn : 64), text + kb);
            rc = 2;
            break;
        }
        if (!printed_has(p, text + kb, kn))
            printf("%.*s\n\n", (int)(e + 1 - start), text + start);
        i = e + 1;
    }
    free(text);
    return rc;
}

/* One method by name: built-in, else a package of the search path. */
static int cite_method(const char *name, const struct sl_tech_set *s, struct printed *p)
{
    const struct sl_method *m = sl_method_find(name);
    if (m) {
        if (m->cite && m->cite[0])
            return print_keys(name, m->cite, p);
        fprintf(stderr, "shadowlab: cite: note: method %s declares no reference (%s)\n", name,
                m->family ? "its source names no author: doc/references.md" : "a baseline");
        return 0;
    }
    for (int i = 0; i < s->n; i++) {
        if (strcmp(s->t[i].name, name))
            continue;
        char path[1200];
        int found;
        snprintf(path, sizeof path, "%s/references.bib", s->t[i].dir);
        int rc = print_bibfile(path, p, &found);
        if (!found)
            fprintf(stderr, "shadowlab: cite: note: package %s (%s) has no references.bib%s%s\n", name, s->t[i].dir,
                    s->t[i].cite[0] ? "; its technique.yaml cites: " : "", s->t[i].cite);
        return rc;
    }
    fprintf(stderr, "shadowlab: cite: note: package %s is not on the technique search path: cite it by hand\n",
            name);
    return 0;
}

int cli_cite(int argc, char **argv)
{
    static const struct option lo[] = {OPT_HELP, {"all", no_argument, NULL, OPT_ALL}, {0, 0, 0, 0}};
    const struct cli_parser parser = {"cite", "", cli_usage_cite, lo};
    int all = 0;
    for (int c; (c = cli_opt_next(&parser, argc, argv)) != OPT_DONE;) {
        switch (c) {
        case OPT_ALL: all = 1; break;
        default: return cli_opt_exit(c);
        }
    }
    if (optind + 1 < argc)
        return cli_usage_error("cite: one STORE at most", cli_usage_cite);
    if (all && optind < argc)
        return cli_usage_error("cite: --all takes no STORE", cli_usage_cite);
    const char *db = optind < argc ? argv[optind] : NULL;

    /* the methods to cite, before anything is printed */
    char names[128][64];
    int nnames = 0;
    char commits[256] = "";
    struct sl_diag d;
    memset(&d, 0, sizeof d);
    if (db) {
        FILE *probe = fopen(db, "rb");
        if (!probe) {
            sl_fail(&d, SL_E_IO, db, 0, NULL, "cannot read the results store");
            return cli_fail(SL_E_IO, &d);
        }
        fclose(probe);
        struct sl_store *st = NULL;
        struct sl_store_filter f = {0};
        struct sl_cell_record *cells = NULL;
        struct sl_store_run *runs = NULL;
        int n = 0, nruns = 0;
        enum sl_err e = sl_store_open_existing(db, &st, &d);
        if (!e)
            e = sl_store_query(st, &f, &cells, &n, &d);
        if (!e)
            e = sl_store_runs(st, &runs, &nruns, &d);
        if (!e && n == 0)
            e = sl_fail(&d, SL_E_USAGE, db, 0, NULL, "the store holds no cell: nothing ran to cite");
        for (int i = 0; !e && i < n; i++) {
            int seen = 0;
            for (int j = 0; j < nnames && !seen; j++)
                seen = !strcmp(names[j], cells[i].method);
            if (!seen && nnames < 128)
                snprintf(names[nnames++], sizeof names[0], "%s", cells[i].method);
        }
        for (int i = 0; !e && i < nruns; i++)
            if (!strstr(commits, runs[i].prov.git_sha))
                sl_known_add(commits, sizeof commits, runs[i].prov.git_sha);
        free(cells);
        sl_store_runs_free(runs, nruns);
        sl_store_close(st);
        if (e)
            return cli_fail(e, &d);
    } else if (all) {
        for (int i = 0; i < sl_method_count() && nnames < 128; i++)
            snprintf(names[nnames++], sizeof names[0], "%s", sl_method_at(i)->name);
    }
    struct sl_tech_set s;
    memset(&s, 0, sizeof s);
    int rc = 0;
    if (nnames || all) {
        rc = cli_tech_scan(&s);
        if (rc)
            return rc;
        for (int i = 0; all && i < s.n && nnames < 128; i++)
            snprintf(names[nnames++], sizeof names[0], "%s", s.t[i].name);
    }
    struct printed *p = calloc(1, sizeof *p);
    if (!p) {
        sl_tech_set_free(&s);
        fprintf(stderr, "shadowlab: cite: out of memory\n");
        return 3;
    }
    print_shadowlab(commits, p);
    rc = print_keys("the truth (Embree)", "wald2014embree", p);
    for (int i = 0; i < nnames && !rc; i++)
        rc = cite_method(names[i], &s, p);
    free(p);
    sl_tech_set_free(&s);
    return rc;
}
