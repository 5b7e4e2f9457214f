/*
 * usage.c — the table of verbs and the help text of each: the one source of
 * `shadowlab --help`, `shadowlab VERB --help` and the dispatch in main.c.
 * The top-level help is built from the table's rows (synopsis and summary),
 * so a verb cannot be dispatched without being listed, nor listed without
 * being dispatched. doc/shadowlab.1 is written by hand beside these texts.
 */
#include <stdio.h>
#include <string.h>
#include "cli.h"

const char cli_usage_run[] =
    "usage: shadowlab run CONFIG|SCENE [-o DIR] [--cells A:B] [--resume] [--db FILE] [--no-cache]\n"
    "                     [--cache DIR] [--gl osmesa|egl] [--jobs N] [--stored-in DB] [-j N] [-D KEY=VALUE]...\n"
    "                     [-q|-v]\n"
    "  -o, --out DIR     output root (default results/): tables and overlays go to DIR/<name>/\n"
    "  --cells A:B       compute only cells A..B-1 of the sweep (scene x viewport x viewpoint x map x method)\n"
    "  --resume          skip cells the results store already holds for this config\n"
    "  --db FILE         results store (default: the config's 'store', else DIR/shadowlab.db)\n"
    "  --no-cache        trace the truth even when DIR/cache holds it\n"
    "  --cache DIR       the truth cache (default DIR/cache; written atomically, may be shared)\n"
    "  --jobs N          N worker processes over slices of the sweep (whole views kept together),\n"
    "                    their stores merged into DB; the same cells as one process (the workers\n"
    "                    die with it; SIGINT/SIGTERM is passed on to them)\n"
    "  --stored-in DB    with --resume: skip the cells DB holds too (a --jobs worker: the main store)\n"
    "  --gl B            the GL context: osmesa (the default where built) or egl (GPU machines;\n"
    "                    SHADOWLAB_EGL_DEVICE=N picks an EGL device); replaces the config's 'gl'\n"
    "  -j, --threads N   threads of the truth and the CPU passes (the config's 'threads') and of\n"
    "                    llvmpipe (LP_NUM_THREADS), 1..256\n"
    "  -D KEY=VALUE      replace a config key by its path, the value in YAML, checked as the file is:\n"
    "                    -D map_sizes=[512,1024] -D 'methods[0].bias=0.01' -D outputs.exr=true\n"
    "                    (the results' config hash covers the overrides)\n"
    "  -q, --quiet       print only the 'written to' line (and errors)\n"
    "  -v, --verbose     print every table of the run (the Markdown of table.md) as well\n"
    "  SCENE: a scene file given for a config runs a default study of it (every viewpoint; nsm,\n"
    "  csm and raytrace; 1024x1024 viewport; 2048 map) and prints the config it used.\n"
    "  By default a summary: cells, time, the wrong pixels (soft: the error) per label, where the\n"
    "  files are. Progress goes to stderr: one live line on a terminal, else one line every 10 s\n"
    "  or 5% of the cells. Ctrl-C (SIGINT) or SIGTERM stops after the cell under way, writes the\n"
    "  folder of what is stored and says how to --resume (exit 130 or 143).\n"
    "  One run writes a results store at a time (a lock on DB.lock, DB's real path: a link to\n"
    "  it takes the same lock); a second is refused with exit 2, naming the holder's pid. The\n"
    "  store holds one cell per config hash and key: a cell computed again replaces it.\n"
    "  Exit codes: 0 done, 1 a check failed, 2 bad input or\n"
    "  usage, 3 a system failure (output not writable, GL, Embree, memory).\n";

const char cli_usage_validate[] =
    "usage: shadowlab validate FILE [-D KEY=VALUE]...\n"
    "  Parses and checks an experiment config or a scene file (scene files have 'meshes',\n"
    "  'light' or 'base'); loads the scenes and model files it names; touches no GL or Embree.\n";

const char cli_usage_table[] =
    "usage: shadowlab table DB [--format md|csv|latex] [--scene S] [--viewpoint V] [--label L]\n"
    "                          [--map N] [--run ID] [--figures NAME,NAME,...|all]\n"
    "                          [--summary FIGURE [--region N|image|contours] [--lower-is-better]\n"
    "                           [--average-case SCENE/VIEWPOINT/N[/MAP]]]\n"
    "       shadowlab table DB --rows R --cols C [--figure F] [--of BASE] [--agg A]\n"
    "                          [--where KEY=VALUE]... [--format md|csv|latex|json]\n"
    "  Renders the latest stored cell of each key, filtered, as thesis-style tables; with\n"
    "  --summary, the average, best and worst per map size of one figure's percentage over\n"
    "  the cells of one label (as the theses' summary tables), md or csv.\n"
    "  md and latex leave out the figures a method does not produce (0 in every column past\n"
    "  wrong_caught); --figures picks the rows to show (figures.h names), 'all' shows every one.\n"
    "  A pivot (any of --rows, --cols, --figure, --of, --agg, --where): one table a paper takes.\n"
    "  --rows R, --cols C  label, method, scene, viewpoint, viewport, map_size or region\n"
    "                      (default label x map_size)\n"
    "  --figure F      a figure of figures.h or softfig.h (default wrong), or a counter or time\n"
    "                  of the cell (ms_method, rays, lookups, ...)\n"
    "  --of BASE       the figure's percentage of its own base (the default: figures.csv's\n"
    "                  percent_of), 'count', or of another figure of the region (--of pfl)\n"
    "  --agg A         mean (default), median, sum, min or max over what is left\n"
    "  --where K=V     keep the cells whose key K is V; a key given twice keeps either value\n"
    "                  (--where label=nsm --where label=chain); the region is 'image' unless\n"
    "                  it is a row, a column or a --where\n"
    "  latex: booktabs, names escaped, thin-space thousands separators, never scaled; a table\n"
    "  wider than a plain article's \\columnwidth is transposed or split into several tables,\n"
    "  and stderr says so. json: the columns, and per row the values (null: none) and counts.\n";

const char cli_usage_report[] =
    "usage: shadowlab report RESULTS_DB [-o DIR] [--self-contained] [--latex]\n"
    "  Writes DIR/report.html (offline; it links its images, plots and .tex beside it) and\n"
    "  DIR/report.md: a contents tree, a summary first, then the thesis-style tables of every\n"
    "  study (and their .tex), the chain's steps and accuracy-vs-cost plots\n"
    "  (gnuplot, SVG), costs, the error overlays and the provenance of every run.\n"
    "  -o, --out DIR     output folder (default: <folder of RESULTS_DB>/report)\n"
    "  --self-contained  report.html is one file: images and plots embedded, nothing outside it\n"
    "  --latex           also DIR/report.tex: a pdflatex document that \\inputs the tables and plots\n";

const char cli_usage_check[] =
    "usage: shadowlab check DB --baseline FILE [--study NAME] [--rows N] [--update]\n"
    "                          [--format text|md] [--json FILE] [--junit FILE]\n"
    "  Compares the latest stored cell of each key with the baseline FILE: violations of a\n"
    "  method's exactness always exactly; every count exactly when the store was measured on\n"
    "  the baseline's machine; otherwise each class of figure within the baseline's tolerance\n"
    "  (percentage points). Prints what moved and by how much; exit 1 when anything is outside\n"
    "  tolerance or a baseline cell is missing, 2 on bad input (a cell of DB that fails its\n"
    "  digest, as `shadowlab verify` checks, is named and is bad input).\n"
    "  --study NAME  only cells of that config name\n"
    "  --rows N      show at most N moved values (default 200)\n"
    "  --update      write FILE from DB instead (keeps FILE's tolerances): a deliberate refresh\n"
    "  --format F    text (default: a plain table; colour on a terminal unless NO_COLOR is set)\n"
    "                or md (Markdown)\n"
    "  --json FILE   also write every compared cell and class with its verdict as JSON\n"
    "  --junit FILE  also write JUnit XML: one testcase per cell and class of figure\n";

const char cli_usage_bench[] =
    "usage: shadowlab bench [CONFIG] [--only LIST] [--reps N] [--scene S] [--viewport WxH] [--map N]\n"
    "                       [--csv FILE] [--markdown FILE] [--gl osmesa|egl]\n"
    "  Each measurement against its target, as a Markdown table with PASS/MISS:\n"
    "    truth    the truth pass vs a plain Embree rtcOccluded16 loop over the same rays: its filtered\n"
    "             trace vs the plain trace (>= 0.9x), end to end vs set-up + trace (>= 1x)\n"
    "    layers   the G-buffer and every shadow-map layer vs a plain raster of the same mesh, size\n"
    "             and matrix, with GL counters (render time within 2x)\n"
    "    backends context creation, the G-buffer and each layer through OSMesa and EGL side by\n"
    "             side (EGL's min within 5% of OSMesa's per stage; needs both built)\n"
    "    moderno  configs/moderno-2011.yaml end to end, no files, no cache (< 60 s); then again with its\n"
    "             overlays, tables and store written (CPU <= 12 s)\n"
    "    morais   configs/morais-2015.yaml end to end, no files, no cache (< 300 s)\n"
    "             (each study in a child process of its own, forked before the other stages)\n"
    "    jobs     CONFIG (default configs/morais-2015.yaml) as one process vs run --jobs 2, files and\n"
    "             store, no cache: wall, CPU, views split, merge per 1,000 cells (--jobs 2 not slower)\n"
    "    startup  version, validate CONFIG (default configs/default.yaml) and help run as processes,\n"
    "             against the same binary with its heavy libraries preloaded (validate < 50 ms)\n"
    "    scoring  a cell's contours, figures and exactness count per 1 M pixels vs one histogram\n"
    "             pass over them, fused and as before (<= 3x)\n"
    "    lightfit the light fit at 3840x2160 on the config's threads vs one thread (directional, a\n"
    "             point light's cube), boxes compared bit for bit\n"
    "    bigmap   (only when named) one view's conservative layers at 16384^2 (--map N) as csm and\n"
    "             csm_adj hold them: peak RSS (<= 6 GB), each layer vs a plain render\n"
    "  and the peak RSS after all of it (< 2 GiB). A missed target exits 0; a failure exits 2.\n"
    "  --only LIST     comma-separated stages (default all but bigmap); `--only truth,layers` is the quick mode\n"
    "  --reps N        timed repetitions after one warm-up (default 7)\n"
    "  --scene S       scene of the truth and layer stages (default: CONFIG's first scene, else bench)\n"
    "  --viewport WxH  their viewport (default: CONFIG's first, else 1024x1024)\n"
    "  --map N         the layers' map size (default 2048; bigmap: 16384)\n"
    "  --csv FILE      also write the summary rows as CSV\n"
    "  --markdown FILE also write the Markdown to FILE (atomically, when every stage ran), under a\n"
    "                  header: machine, CPU, GL renderer and backend, git SHA, load, this command\n"
    "  --gl B          the GL context of every stage: osmesa (default where built) or egl\n";

const char cli_usage_list[] =
    "usage: shadowlab list methods|scenes|techniques\n"
    "  scenes: the scene files a config can name, each with where it was found; a name is looked\n"
    "  up in the config's folder, then in each folder of SHADOWLAB_SCENES (colon-separated), then\n"
    "  in the installed share/shadowlab/scenes (or, not installed, the source tree's scenes/)\n"
    "  techniques: the technique packages (technique.yaml + GLSL) a config can name as a method,\n"
    "  each with where it was found: the config's `techniques:` folders, then each folder of\n"
    "  SHADOWLAB_TECHNIQUES (colon-separated), the source tree's techniques/, the installed\n"
    "  share/shadowlab/techniques; the first package of a name wins. A broken package is an error\n"
    "  naming its file, line and key (exit 2).\n";

const char cli_usage_show[] =
    "usage: shadowlab show technique NAME\n"
    "  A technique package's summary, folder, shaders, citation, maps (format, filter, post\n"
    "  passes), reach and texel reads, and its parameters with type, default, range and doc.\n";

const char cli_usage_submit[] =
    "usage: shadowlab submit CONFIG --slurm [--tasks N | --cells-per-task K] [--max-running T]\n"
    "                        [--out DIR] [--partition P] [--time HH:MM:SS] [--mem M] [--dry-run]\n"
    "  Writes DIR/slurm/array.sh, an sbatch job array whose task i runs\n"
    "    shadowlab run CONFIG --cells A:B --out DIR/shards/task-i --db DIR/shards/task-i/shadowlab.db\n"
    "                         --cache DIR/cache --resume\n"
    "  and DIR/slurm/merge.sh, which merges the shards into DIR/shadowlab.db; without --dry-run,\n"
    "  submits both (the merge with --dependency=afterok on the array) and prints the job ids.\n"
    "  --tasks N            N tasks (default: one per 256 cells); cuts move to view boundaries\n"
    "  --cells-per-task K   tasks of about K cells\n"
    "  --max-running T      at most T tasks at once (--array=0-(N-1)%T)\n"
    "  --out DIR            default results/; must be on a filesystem every node sees\n";

const char cli_usage_merge[] =
    "usage: shadowlab merge SHARD.db... -o STORE.db [--allow-mixed]\n"
    "  Copies the runs and cells of each shard (one config, the same in every shard) into STORE.db,\n"
    "  one transaction per shard; a cell already there is a duplicate and is not copied again. The\n"
    "  overlays and EXR files go under STORE.db's folder. Names the cells of the sweep no shard\n"
    "  holds; exit 1 when any is missing. Every shard is checked first, and nothing is written when\n"
    "  one is a folder or device, damaged (SQLite's quick_check, or a cell that fails its digest,\n"
    "  as `verify` checks) or of another config: exit 2 naming it.\n"
    "  --allow-mixed  merge shards whose cells come from other git SHAs, GL renderers or ISAs\n"
    "                 (refused by default; each merged run keeps its own provenance)\n";

const char cli_usage_verify[] =
    "usage: shadowlab verify STORE.db\n"
    "  Checks a results store: SQLite's quick_check, then each cell's digest (a CRC-32 over every\n"
    "  column of the cell row and of each of its figure rows, written with the cell) recomputed\n"
    "  from what is stored. Names each damaged cell (scene/viewpoint/viewport/map/label) on stderr;\n"
    "  exit 0 when every cell is intact, 2 when one is not or the file is not a sound store.\n"
    "  table, report, check and merge check the digest of every cell they read the same way.\n"
    "  Opens the store read-only (a store on read-only media can be verified).\n";

const char cli_usage_preview[] =
    "usage: shadowlab preview SCENE [--viewpoint V] [-o DIR] [--size WxH] [--gl osmesa|egl]\n"
    "  Writes DIR/<scene>-<viewpoint>.png for each viewpoint of SCENE (a scene file or a built-in\n"
    "  scene's name): the G-buffer only, faces shaded by their angle to the light, faces turned\n"
    "  from it dark; no truth, no method, no Embree. For framing cameras before a run.\n"
    "  --viewpoint V  only that viewpoint\n"
    "  -o, --out DIR  output folder (default: the current one)\n"
    "  --size WxH     image size (default 512x512)\n";

/* In the order `shadowlab --help` lists them. run and bench render with
 * OpenMP on the CPU passes: they wait passively (main.c). */
const struct cli_verb cli_verbs[] = {
    {"run", cli_run, cli_usage_run, "CONFIG|SCENE [options]", "run an experiment (shadowlab run --help)", 1},
    {"validate", cli_validate, cli_usage_validate, "FILE [-D K=V]",
     "check a config or a scene file without GL or Embree", 0},
    {"table", cli_table, cli_usage_table, "DB [options]", "regenerate tables from a results store", 0},
    {"report", cli_report, cli_usage_report, "DB [-o DIR]",
     "HTML and Markdown report of a results store (needs gnuplot)", 0},
    {"check", cli_check, cli_usage_check, "DB --baseline FILE",
     "compare a results store with a committed baseline (exit 1 if outside)", 0},
    {"bench", cli_bench, cli_usage_bench, "[CONFIG] [options]",
     "every stage against its plain counterpart, the studies, their targets", 1},
    {"submit", cli_submit, cli_usage_submit, "CONFIG --slurm ...",
     "the sweep as a Slurm job array plus a merge job (shadowlab submit --help)", 0},
    {"merge", cli_merge, cli_usage_merge, "SHARD.db... -o DB",
     "the stores of a split sweep into one; exit 1 if a cell is missing", 0},
    {"verify", cli_verify, cli_usage_verify, "DB", "every stored cell against its digest; exit 2 naming damaged ones",
     0},
    {"preview", cli_preview, cli_usage_preview, "SCENE [options]",
     "a quick shaded PNG per viewpoint, for framing cameras", 0},
    {"list", cli_list, cli_usage_list, "methods|scenes|techniques", "what can be named in a config", 0},
    {"show", cli_show, cli_usage_show, "technique NAME", "a technique package's parameters, maps, reach, citation",
     0},
    {NULL, NULL, NULL, NULL, NULL, 0},
};

const struct cli_verb *cli_verb_find(const char *name)
{
    for (const struct cli_verb *v = cli_verbs; v->name; v++)
        if (!strcmp(v->name, name))
            return v;
    return NULL;
}

/* "  NAME SYNOPSIS" in 26 columns, then the summary; version is not a verb
 * of the table (main.c answers it, and its -V / --version forms) */
static void usage_line(char *buf, size_t size, size_t *len, const char *left, const char *summary)
{
    int k = snprintf(buf + *len, size - *len, "  %-26s %s\n", left, summary);
    if (k > 0 && (size_t)k < size - *len)
        *len += (size_t)k;
}

const char *cli_usage(void)
{
    static char text[4096];
    if (text[0])
        return text;
    size_t len = (size_t)snprintf(text, sizeof text, "usage: shadowlab <command> [--help] ...      "
                                                     "(shadowlab help COMMAND = shadowlab COMMAND --help)\n");
    for (const struct cli_verb *v = cli_verbs; v->name; v++) {
        char left[64];
        snprintf(left, sizeof left, "%s %s", v->name, v->synopsis);
        usage_line(text, sizeof text, &len, left, v->summary);
    }
    usage_line(text, sizeof text, &len, "version, -V, --version", "the git SHA this binary was built from");
    return text;
}
