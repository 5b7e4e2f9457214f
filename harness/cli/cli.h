#ifndef SL_CLI_H
#define SL_CLI_H
/*
 * cli: the command line, one file per verb (run.c, validate.c, table.c,
 * report.c, check.c, store.c for merge and verify, submit.c, bench.c,
 * preview.c, list.c for list and show, test.c, cite.c, version.c) and the table of verbs with their help texts
 * (usage.c). This header is what the verbs share: the option parser, the
 * error printing and the exit codes. The CLI is the only code that prints
 * errors and chooses exit codes (the library stages return sl_err ids and
 * fill an sl_diag): 0 success, 1 a check failed, 2 bad input or usage (and
 * any other failure that leaves no result), 3 a system failure. It holds
 * no experiment logic: each verb parses its options, calls one library
 * entry and prints what came back.
 */
#include <getopt.h>
#include <stddef.h>
#include <stdio.h>
#include "sl_error.h"

/* ---- the verbs ----
 * One row per verb: main.c dispatches through it and `shadowlab --help`
 * lists it, so the two cannot drift. To add a verb: its file here, one row
 * in cli_verbs (usage.c) beside its help text. */
struct cli_verb {
    const char *name;
    int (*fn)(int argc, char **argv);   /* argv[0] is the verb, as getopt_long expects */
    const char *usage;                  /* `shadowlab VERB --help` */
    const char *synopsis;               /* its arguments, in `shadowlab --help` */
    const char *summary;                /* one line, in `shadowlab --help` */
    int passive_omp;                    /* renders: runs itself with OMP_WAIT_POLICY=passive (main.c) */
};
extern const struct cli_verb cli_verbs[];   /* ends with a row whose name is NULL */
const struct cli_verb *cli_verb_find(const char *name);
const char *cli_usage(void);                /* `shadowlab --help`, built from cli_verbs */
/* `shadowlab help --man`: the man page (roff), from cli_verbs and their help
 * texts (doc/shadowlab.1 is this output) */
void cli_man(FILE *f);
int  cli_config_reference(FILE *f);   /* help --config: doc/config.md */
/* `shadowlab help --bash-completion`: the bash completion script, from the
 * same rows (scripts/shadowlab.bash-completion is this output) */
void cli_completion(FILE *f);

int cli_run(int argc, char **argv);
int cli_validate(int argc, char **argv);
int cli_table(int argc, char **argv);
int cli_report(int argc, char **argv);
int cli_check(int argc, char **argv);
int cli_bench(int argc, char **argv);
int cli_submit(int argc, char **argv);
int cli_merge(int argc, char **argv);
int cli_verify(int argc, char **argv);
int cli_preview(int argc, char **argv);
int cli_list(int argc, char **argv);
int cli_show(int argc, char **argv);
int cli_test(int argc, char **argv);
int cli_cite(int argc, char **argv);
int cli_version(int argc, char **argv);   /* also -V and --version (main.c) */
int cli_grade(int argc, char **argv);   /* grade.c, with its help text */
extern const char cli_usage_grade[];

/* the help text of each verb (usage.c) */
extern const char cli_usage_run[];
extern const char cli_usage_validate[];
extern const char cli_usage_table[];
extern const char cli_usage_report[];
extern const char cli_usage_check[];
extern const char cli_usage_bench[];
extern const char cli_usage_list[];
extern const char cli_usage_show[];
extern const char cli_usage_submit[];
extern const char cli_usage_merge[];
extern const char cli_usage_verify[];
extern const char cli_usage_preview[];
extern const char cli_usage_test[];
extern const char cli_usage_cite[];
extern const char cli_usage_version[];

/* ---- errors ----
 * cli_fail prints the diagnostic as one line and returns the exit code of
 * its id (2 bad input, 3 a system failure); cli_usage_error prints msg and
 * the verb's help text and returns 2. */
int cli_fail(enum sl_err e, const struct sl_diag *d);
int cli_usage_error(const char *msg, const char *text);
/* One note on stderr per scene of c that leaves labels out (a scene naming
 * no list runs only the labels that handle its light): the scene, its
 * light and each label with why, so no label is dropped unsaid. */
struct sl_config;
void cli_note_left_out(const struct sl_config *c);
/* The technique packages of the search path, as `list techniques` reads
 * them (no config, no GL); the exit code on failure (printed), else 0. */
struct sl_tech_set;
int cli_tech_scan(struct sl_tech_set *s);

/* ---- options: getopt_long per verb ----
 * Each verb has a table of long options and a short-option string;
 * cli_opt_next returns the next option (as getopt_long does), handles
 * --help itself and turns an unknown option or a missing value into one
 * message that names it. To add an option to a verb: one entry in its
 * `struct option` table (a short letter, or an OPT_* id above 256 for a
 * long-only one) and one case in its switch. */
enum {
    OPT_CELLS = 256, OPT_RESUME, OPT_DB, OPT_NO_CACHE, OPT_GL, OPT_FORMAT, OPT_SCENE, OPT_VIEWPOINT,
    OPT_LABEL, OPT_MAP, OPT_RUN, OPT_SUMMARY, OPT_FIGURES, OPT_REGION, OPT_LOWER, OPT_AVG, OPT_BASELINE, OPT_STUDY,
    OPT_ROWS, OPT_UPDATE, OPT_EXACT, OPT_JSON, OPT_JUNIT, OPT_ONLY, OPT_REPS, OPT_VIEWPORT, OPT_CSV, OPT_SELF_CONTAINED, OPT_LATEX, OPT_CACHE, OPT_JOBS, OPT_SIZE,
    OPT_ALLOW_MIXED, OPT_STORED_IN, OPT_MARKDOWN, OPT_COLS, OPT_FIGURE, OPT_OF, OPT_AGG, OPT_WHERE,
    OPT_ALL,
    OPT_FILES, OPT_NO_FILES,
};
#define OPT_HELP {"help", no_argument, NULL, 'h'}
enum { OPT_DONE = -1, OPT_EXIT_OK = -2, OPT_EXIT_USAGE = -3 };

struct cli_parser {
    const char *verb, *shorts, *help;
    const struct option *longs;
};
int cli_opt_next(const struct cli_parser *p, int argc, char **argv);
/* the exit status of what cli_opt_next returned for --help (0) or a bad option (2) */
int cli_opt_exit(int c);

/* -D KEY=VALUE, repeatable: 0 (the message printed) when arg has no '=' or
 * there are 64 already */
struct cli_overrides {
    const char *v[64];
    int n;
};
int cli_add_override(struct cli_overrides *o, const char *verb, const char *arg, const char *help);

/* An integer an option takes, in lo..hi (see cli.c); 0 with msg otherwise.
 * The _or_usage form prints "shadowlab: VERB: OPT MSG" and the help text. */
int cli_opt_int(const char *s, long long lo, long long hi, long long *out, char *msg, size_t n);
int cli_opt_int_or_usage(const char *verb, const char *opt, const char *s, long long lo, long long hi,
                         long long *out, const char *help);
/* "WxH", each a whole number in lo..hi; 0 when it is not */
int cli_parse_wxh(const char *s, long long lo, long long hi, int *w, int *h);

/* What a merge did, shard by shard, and the cells of the sweep it lacks
 * (store.c; run --jobs prints its merge the same way): 1 when a cell is
 * missing, else 0. */
struct sl_shards_result;
int cli_print_merge(const char *const *shards, const struct sl_shards_result *r, const char *out);
/* "N of M cells" for every sweep (config hash) of the store at db, on
 * stderr, each line "shadowlab: VERB: DB: ..."; missing > 0 lists up to that
 * many missing cells of each incomplete sweep; quiet_whole: only the
 * incomplete sweeps (table and check, whose stderr scripts often merge into
 * their output: a whole sweep is the usual case and says nothing there).
 * Returns the number of incomplete sweeps, -1 when the store cannot be
 * read (said). */
int cli_say_sweeps(const char *verb, const char *db, int missing, int quiet_whole);
#endif
