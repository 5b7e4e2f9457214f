/*
 * usage.c — the table of verbs and the help text of each: the one source of
 * `shadowlab --help`, `shadowlab VERB --help` and the dispatch in main.c.
 * The top-level help is built from the table's rows (synopsis and summary),
 * so a verb cannot be dispatched without being listed, nor listed without
 * being dispatched. The man page (doc/shadowlab.1) is written from the same
 * rows and texts by `shadowlab help --man` (cli_man, below), with the
 * sections only it has (environment, configuration, files, exit status) kept
 * here too; doc::package_man fails when the committed page differs.
 */
#include <ctype.h>
#include <stdio.h>
#include <string.h>
#include "bench.h"
#include "config.h"
#include "cli.h"
#include "figrec.h"
#include "pivot.h"
#include "softfig.h"

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
    "  -D, --define K=V  replace a config key by its path, the value in YAML, checked as the file is:\n"
    "                    -D map_sizes=[512,1024] -D 'methods[0].self_shadow=slope'\n"
    "                    -D outputs.exr=true (the results' config hash covers the overrides)\n"
    "  -q, --quiet       print only the 'written to' line (and errors)\n"
    "  -v, --verbose     print every table of the run (the Markdown of table.md) as well\n"
    "  SCENE: a scene file given for a config runs a default study of it (every viewpoint; nsm,\n"
    "  csm and raytrace; 1024x1024 viewport; 2048 map) and prints the config it used.\n"
    "  By default a summary: cells, time, the wrong pixels (soft: the error) per label, where the\n"
    "  files are. Progress goes to stderr: one live line on a terminal, else one line every 10 s\n"
    "  or 5% of the cells. Ctrl-C (SIGINT) or SIGTERM stops after the cell under way, writes the\n"
    "  folder of what is stored and says how to --resume (exit 130 or 143).\n"
    "  Timing: every stage is computed once; the default 'repetitions: {mode: adaptive}' times a\n"
    "  stage again until 5 runs are timed, their spread is within 10%, 100 ms are spent on it, or\n"
    "  all repetitions reach 30% of the run's other time: a study takes at most 1.3x the wall\n"
    "  time of computing it once (Moderno study, CPU: 1.04x-1.26x measured); with\n"
    "  -D 'repetitions={mode: off}' each stage's one run is its time. The summary says how often\n"
    "  each kind of stage ran and why it stopped.\n"
    "  One run writes a results store at a time (a lock on DB.lock, DB's real path: a link to\n"
    "  it takes the same lock; removed when the run ends); a second is refused with exit 2,\n"
    "  naming the holder's pid. The store holds one cell per config hash and key: a cell computed\n"
    "  again replaces it. Exit codes: 0 done, 1 a check failed, 2 bad input or usage, 3 a system\n"
    "  failure (output not writable, GL, Embree, memory).\n";

const char cli_usage_validate[] =
    "usage: shadowlab validate FILE [-D|--define KEY=VALUE]...\n"
    "  Parses and checks an experiment config or a scene file (scene files have 'meshes',\n"
    "  'light' or 'base'); loads the scenes and model files it names, compiles the shaders of\n"
    "  the technique packages its labels run (glslang) and checks their maps' size against every\n"
    "  map size; touches no GL or Embree. Names on stderr the labels a scene without a\n"
    "  'methods' list leaves out (those that cannot run under its light).\n";

const char cli_usage_table[] =
    "usage: shadowlab table DB [--format md|csv|latex] [--scene S] [--viewpoint V]\n"
    "                          [--label L,L,...]... [--map N] [--run ID] [--figures NAME,NAME,...|all]\n"
    "                          [--summary FIGURE,FIGURE,...]... [--region N|image|contours]\n"
    "                          [--lower-is-better] [--average-case SCENE/VIEWPOINT/N[/MAP]]\n"
    "       shadowlab table DB --rows R --cols C [--figure F] [--of BASE] [--agg A]\n"
    "                          [--where KEY=VALUE]... [--format md|csv|latex|json]\n"
    "  Renders the latest stored cell of each key, filtered, as thesis-style tables; --label\n"
    "  keeps the labels named (a,b or repeated). With --summary, per figure named and per label,\n"
    "  the average, best and worst per map size of the figure's percentage over the label's\n"
    "  cells (as the theses' summary tables): md, csv or latex (a booktabs float each).\n"
    "  md and latex leave out the figures a method does not produce (0 in every column past\n"
    "  wrong_caught); --figures picks the rows to show (names of figures.h and softfig.h: wrong,\n"
    "  uncertain, ..., soft_mae, leaking, over_dark, ...), 'all' shows every one.\n"
    "  A pivot (any of --rows, --cols, --figure, --of, --agg, --where): one table a paper takes.\n"
    "  --rows R          the rows: label, method, scene, viewpoint, viewport, map_size or region\n"
    "  --cols C          the columns: one of the same keys\n"
    "                    (default label x map_size)\n"
    "  --figure F      a figure of figures.h (default wrong; uncertain, light_incorrect, ...) or\n"
    "                  of softfig.h (soft_mae, soft_bias, leaking, over_dark, soft_class_right,\n"
    "                  ...), or a counter or time of the cell (ms_method, rays, lookups,\n"
    "                  nonfinite, ...)\n"
    "  --of BASE       the figure's percentage of its own base (the default: figures.csv's\n"
    "                  percent_of), 'count', or of another figure of the region (--of pfl);\n"
    "                  a counter: count, or pfl, its share of the cell's PFL pixels (rays:\n"
    "                  the share of raytrace's, one ray a PFL pixel)\n"
    "  --agg A         mean (default), median, sum, min or max over what is left\n"
    "  --where K=V     keep the cells whose key K is V; a key given twice keeps either value\n"
    "                  (--where label=nsm --where label=chain); the region is 'image' unless\n"
    "                  it is a row, a column or a --where\n"
    "  latex: booktabs, names escaped, thin-space thousands separators, never scaled; a table\n"
    "  wider than a plain article's \\columnwidth is transposed or split into several tables,\n"
    "  and stderr says so. json: the columns, and per row the values (null: none) and counts.\n"
    "  A time of a cell timed once (repetitions runs: 1) is marked with a dagger in md and latex\n"
    "  (and a footnote); json: per row timed_once.\n";

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
    "usage: shadowlab check DB --baseline FILE [--study NAME] [--rows N] [--update] [--exact]\n"
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
    "  --exact       every count exactly, whatever machine measured DB: results are meant to be\n"
    "                the same on every ISA and llvmpipe width (CI's platform matrix)\n"
    "  --format F    text (default: a plain table; colour on a terminal unless NO_COLOR is set)\n"
    "                or md (Markdown)\n"
    "  --json FILE   also write every compared cell and class with its verdict as JSON\n"
    "  --junit FILE  also write JUnit XML: one testcase per cell and class of figure\n";

const char cli_usage_bench[] =
    "usage: shadowlab bench [CONFIG] [--only LIST] [--reps N] [--scene S] [--viewport WxH] [--map N]\n"
    "                       [--csv FILE] [--markdown FILE] [--gl osmesa|egl]\n"
    "  Each measurement against its target, as a Markdown table with PASS/MISS:\n"
    "    truth    the truth pass vs a plain Embree packet loop over the same rays, both in the\n"
    "             device's native width: its filtered trace vs the plain trace (>= 0.9x), end to end\n"
    "             vs set-up + trace (>= 1x); then the trace again with each narrower width the CPU\n"
    "             runs (isa=avx2: 8, isa=sse4.2: 4; not when SHADOWLAB_EMBREE_CONFIG is set)\n"
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
    "    churn    NSM's layer at the map size S and 2S through the pass's kept render target and pooled\n"
    "             arrays vs ones made afresh: wall, CPU, minor page faults (2S at most 5x S)\n"
    "    techniques each technique package of the source tree (pcf at kernel 3 and 5) at the map size\n"
    "             and viewport: its map pass vs a plain one writing the same maps (<= 1.3x), its post\n"
    "             passes, its lookup vs a plain one reading as many texels (<= 1.5x)\n"
    "    startup  version, validate CONFIG (default configs/default.yaml) and help run as processes,\n"
    "             against the same binary with its heavy libraries preloaded (validate < 50 ms)\n"
    "    scoring  a cell's contours, figures and exactness count per 1 M pixels vs one histogram\n"
    "             pass over them, fused and as before (<= 3x)\n"
    "    lightfit the light fit at 3840x2160 on the config's threads vs one thread (directional, a\n"
    "             point light's cube), boxes compared bit for bit\n"
    "    bigmap   (only when named) one view's conservative layers at 16384^2 (--map N) as csm and\n"
    "             csm_adj hold them: peak RSS (<= 6 GB), each layer vs a plain render\n"
    "    timing   (only when named) the Moderno study with its default repetitions against\n"
    "             'repetitions: {mode: off}', --reps pairs (default 3) alternating, each a process:\n"
    "             CPU (user+sys) and wall min, median, max (<= 1.5x the CPU median)\n"
    "  and the peak RSS after all of it (< 2 GiB). A missed target exits 0; a failure exits 2.\n"
    "  --only LIST     comma-separated stages (default all but bigmap and timing); `--only truth,layers` is the quick mode\n"
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
    "  share/shadowlab/techniques. Two different packages of one name, a package named like a\n"
    "  built-in method, or a broken package is an error naming its file, line and key (exit 2).\n";

const char cli_usage_show[] =
    "usage: shadowlab show method|technique NAME\n"
    "  method: a built-in method's summary, family, exactness, lights and its parameters (the keys\n"
    "  a config's method entry may give) with type, default, range or words, unit and doc.\n"
    "  technique: a technique package's summary, folder, shaders, citation, maps (format, filter,\n"
    "  post passes), reach and texel reads, and its parameters in the same form.\n";

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
    "  -o, --out STORE.db  the store the shards are merged into\n"
    "  --allow-mixed       merge shards whose cells come from other git SHAs, GL renderers or ISAs\n"
    "                      (refused by default; each merged run keeps its own provenance)\n";

const char cli_usage_verify[] =
    "usage: shadowlab verify STORE.db [--files | --no-files]\n"
    "  Checks a results store as an archive: SQLite's quick_check; each cell's digest (a CRC-32\n"
    "  over every column of the cell row and of each of its figure rows, written with the cell)\n"
    "  recomputed from what is stored; each file the runs wrote (overlays, EXR files, tables: path,\n"
    "  size and CRC-32 recorded in the store) against the file at its path; each sweep against the\n"
    "  plan its runs recorded (\"N of M cells\", the missing ones named). Names each damaged cell\n"
    "  (scene/viewpoint/viewport/map/label) and each missing or damaged file on stderr.\n"
    "  Exit 0 when all is whole, 1 when a sweep is incomplete, 2 when a cell or file is damaged or\n"
    "  missing or the file is not a sound store. table, report, check and merge check the digest\n"
    "  of every cell they read the same way. Opens the store read-only (a store on read-only media\n"
    "  can be verified, a -wal beside it read through a private copy; an older schema's store\n"
    "  is read through a private upgraded copy).\n"
    "  --files     check the recorded files even when none lies beside the store (each is missing)\n"
    "  --no-files  do not check them (by default they are checked when any lies at its path)\n";

const char cli_usage_preview[] =
    "usage: shadowlab preview SCENE [--viewpoint V] [-o DIR] [--size WxH] [--gl osmesa|egl]\n"
    "  Writes DIR/<scene>-<viewpoint>.png for each viewpoint of SCENE (a scene file or a built-in\n"
    "  scene's name): the G-buffer only, faces shaded by their angle to the light, faces turned\n"
    "  from it dark; no truth, no method, no Embree. For framing cameras before a run.\n"
    "  --viewpoint V  only that viewpoint\n"
    "  -o, --out DIR  output folder (default: the current one)\n"
    "  --size WxH     image size (default 512x512)\n";

const char cli_usage_test[] =
    "usage: shadowlab test technique NAME [--scene S] [--viewpoint V] [--viewport WxH] [--map N]\n"
    "                      [--gl osmesa|egl]\n"
    "  Tries a technique package (found as `show technique` finds it) on one view before a study\n"
    "  runs it: its shaders compiled (glslang, then the GL), then, at its defaults:\n"
    "    determinism  the maps and the lookup drawn twice: every visibility the same, bit for bit\n"
    "    reach        the maps grown by 16 texels a side beyond the declared guard band, those\n"
    "                 texels filled once with a surface at the near plane (sl_map(0)) and once with\n"
    "                 none (sl_map(1)): a pixel whose visibility or verdict differs reads beyond the\n"
    "                 declared reach (the count and the first pixel are named)\n"
    "    non-finite   lookups returning NaN or +-inf, map texels not finite\n"
    "    taps         texel reads per pixel (texture, texelFetch, textureLod, textureGrad calls,\n"
    "                 counted in the shader): least, mean, most, against the declared `taps`; a\n"
    "                 declared count outside least..most is a finding\n"
    "    time         the map, post and lookup passes, and the lookup per pixel\n"
    "  Under a point light, each face of its cube with receivers, over its own pixels. Nothing is\n"
    "  traced or written. Exit 0 when every check passes, 1 on a finding, 2 when the package cannot\n"
    "  be tested (not found, a technique.yaml or GLSL error: its file and line; an unknown scene).\n"
    "  --scene S       a scene file or a built-in scene's name (default primitives)\n"
    "  --viewpoint V   its viewpoint (default: its first)\n"
    "  --viewport WxH  the view (default 256x256)\n"
    "  --map N         the light frame's map size, texels a side (default 512)\n"
    "  --gl B          the GL context: osmesa (default where built) or egl\n";

/* In the order `shadowlab --help` lists them. run and bench render with
 * OpenMP on the CPU passes: they wait passively (main.c). */
const char cli_usage_cite[] =
    "usage: shadowlab cite [STORE] [--all]\n"
    "  BibTeX on stdout for what the numbers came from: shadowlab's entry and Embree's (the\n"
    "  truth), then, with STORE, the references of every method its cells ran (a built-in\n"
    "  method's declared ones; a technique package's references.bib, from its folder on the\n"
    "  search path). A method or package that gives none gets a note on stderr, naming it.\n"
    "  --all   every built-in method's and every package's on the search path\n"
    "  Exit 2 for a package's references.bib that does not parse (its file and line named),\n"
    "  a STORE that cannot be read or one with no cell.\n";

const char cli_usage_version[] =
    "usage: shadowlab version [--verbose]\n"
    "  (also: shadowlab -V [--verbose], shadowlab --version [--verbose])\n"
    "  The release and the git commit this binary was built from (\"-dirty\" when tracked files\n"
    "  differed from that commit), the build type and the Embree headers it was compiled with;\n"
    "  this form loads no library.\n"
    "  --verbose, -v   also opens a GL context and an Embree device as a run would (SHADOWLAB_GL,\n"
    "                  SHADOWLAB_EGL_DEVICE, SHADOWLAB_EMBREE_CONFIG obeyed) and prints the CPU, the\n"
    "                  GL renderer, version and backend, and Embree's version and native packet\n"
    "                  width (the ISA of its kernels); a part that cannot open says why\n";

const struct cli_verb cli_verbs[] = {
    {"run", cli_run, cli_usage_run, "CONFIG|SCENE [options]", "run an experiment (shadowlab run --help)", 1},
    {"validate", cli_validate, cli_usage_validate, "FILE [-D K=V]",
     "check a config or a scene file without GL or Embree", 0},
    {"table", cli_table, cli_usage_table, "DB [options]", "regenerate tables from a results store", 0},
    {"report", cli_report, cli_usage_report, "DB [-o DIR]",
     "HTML and Markdown report of a results store (needs gnuplot)", 0},
    {"check", cli_check, cli_usage_check, "DB --baseline FILE",
     "compare a results store with a committed baseline (exit 1 if outside)", 0},
    {"grade", cli_grade, cli_usage_grade, "--scene S --viewpoint V --viewport WxH --image FILE --label L",
     "score another program's visibility image against the truth (doc/grade.md)", 1},
    {"bench", cli_bench, cli_usage_bench, "[CONFIG] [options]",
     "every stage against its plain counterpart, the studies, their targets", 1},
    {"submit", cli_submit, cli_usage_submit, "CONFIG --slurm ...",
     "the sweep as a Slurm job array plus a merge job (shadowlab submit --help)", 0},
    {"merge", cli_merge, cli_usage_merge, "SHARD.db... -o DB",
     "the stores of a split sweep into one; exit 1 if a cell is missing", 0},
    {"verify", cli_verify, cli_usage_verify, "DB [--files]",
     "cells, files and sweeps of a store; exit 1 incomplete, 2 naming damage", 0},
    {"preview", cli_preview, cli_usage_preview, "SCENE [options]",
     "a quick shaded PNG per viewpoint, for framing cameras", 0},
    {"list", cli_list, cli_usage_list, "methods|scenes|techniques", "what can be named in a config", 0},
    {"show", cli_show, cli_usage_show, "method|technique NAME", "a method's or a technique package's parameters",
     0},
    {"test", cli_test, cli_usage_test, "technique NAME [options]",
     "a technique package's determinism, reach, finite values, taps and time; exit 1 on a finding", 0},
    {"cite", cli_cite, cli_usage_cite, "[STORE] [--all]", "BibTeX for shadowlab and every method a store ran", 0},
    {"version", cli_version, cli_usage_version, "[--verbose]",
     "the version, git SHA and build; --verbose: GL renderer and Embree too (also -V, --version)", 0},
    {NULL, NULL, NULL, NULL, NULL, 0},
};

const struct cli_verb *cli_verb_find(const char *name)
{
    for (const struct cli_verb *v = cli_verbs; v->name; v++)
        if (!strcmp(v->name, name))
            return v;
    return NULL;
}

/* "  NAME SYNOPSIS" in 26 columns, then the summary */
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
    usage_line(text, sizeof text, &len, "help --man", "this reference as a man page (roff: doc/shadowlab.1)");
    usage_line(text, sizeof text, &len, "help --bash-completion", "the bash completion script for these verbs");
    usage_line(text, sizeof text, &len, "help --config", "every config key, from the parser's schema (doc/config.md)");
    return text;
}

/* ---- the man page -------------------------------------------------------
 * `shadowlab help --man` writes doc/shadowlab.1: each verb's row and help
 * text above, and the sections below, which only the man page has. Text is
 * plain (no roff in it): man_text escapes it, a blank line starts a
 * paragraph. The page carries no date, so the same binary writes the same
 * bytes (doc::package_man compares them with the committed page). */

/* the environment variables the program reads, in the ENVIRONMENT section */
static const struct {
    const char *name, *text;
} man_env[] = {
    {"SHADOWLAB_GL", "The GL context when neither --gl nor the config's 'gl' names one: osmesa or egl (any "
                     "other value is an error). CI runs the rendering tests a second time with "
                     "SHADOWLAB_GL=egl."},
    {"SHADOWLAB_EGL_DEVICE", "The EGL device (its index) to use with --gl egl."},
    {"SHADOWLAB_EMBREE_CONFIG", "Appended to the device config given to Embree (rtcNewDevice) for every "
                                "ray trace: key=value pairs separated by commas, e.g. isa=sse4.2 or "
                                "isa=avx2 to run Embree's SSE or AVX2 kernels on any CPU that has them, or "
                                "threads=1. Keys and ISA names Embree 3 does not document, and an isa= this "
                                "CPU cannot run, are refused (exit 2). Recorded in run.yaml (embree_config, beside embree_packets: the packet "
                                "width the truth used) and in the store's runs.embree. For testing and for "
                                "machines that need it; the results are the same under every ISA (CI "
                                "checks it)."},
    {"SHADOWLAB_SCENES", "Colon-separated folders searched for scene names after the config's own folder and "
                         "before the installed share/shadowlab/scenes (or, not installed, the source tree's "
                         "scenes/)."},
    {"SHADOWLAB_TECHNIQUES", "Colon-separated folders searched for technique packages after a config's "
                             "'techniques:' folders and before the source tree's techniques/ and the installed "
                             "share/shadowlab/techniques; two different packages of one name along them are an error "
                             "naming both."},
    {"SHADOWLAB_THESES", "The folder report reads the theses' data files from (moderno-2011.csv, "
                         "moderno-2011-scenes.csv, moderno-2011-table15.csv, morais-2015.csv, "
                         "morais-2015-times.csv, hertel-2009.csv) instead of the installed "
                         "share/shadowlab/theses (or, not installed, the source tree's report/theses/); a "
                         "damaged file stops the report with its file, line and column (exit 2)."},
    {"SHADOWLAB_MODULE_DIR", "A folder searched first for the modules loaded on first use "
                             "(shadowlab-oiio.so, shadowlab-sheet.so); otherwise beside the binary, then "
                             "lib/shadowlab under its prefix."},
    {"OMP_WAIT_POLICY, GOMP_SPINCOUNT", "run and bench set OMP_WAIT_POLICY=passive for themselves when neither "
                                        "is set (idle OpenMP threads then do not spin); either one set keeps "
                                        "the user's choice."},
    {"LP_NUM_THREADS", "llvmpipe's threads; -j/--threads sets it."},
    {"NO_COLOR", "When set and not empty, check prints no colour."},
};

static const char man_description[] =
    "shadowlab renders shadow techniques with OpenGL (OSMesa or EGL, no window), compares every pixel with "
    "an exact ray-traced truth (Embree) and writes thesis-style tables, error overlays and a results store "
    "(SQLite). An experiment is a YAML config: scenes, viewports, map sizes, contours and method labels; it "
    "expands to a sweep of cells (scene x viewport x viewpoint x map size x label). Every output carries the "
    "git SHA, the config hash and the machine.\n"
    "\n"
    "Each command's reference below is its --help text (shadowlab help COMMAND prints the same).\n";

static const char man_config[] =
    "A config is a YAML file; every key is listed below (and in doc/config.md: both written by shadowlab "
    "help \\-\\-config from the parser's own schema), the Configs section of doc/guide.md explains them, and "
    "shadowlab validate CONFIG prints a config with every default filled in. In short:\n"
    "\n"
    "    name: study                  # output folder under the --out root\n"
    "    scenes: [{scene: primitives, viewpoints: [side]}]\n"
    "    viewports: [{width: 512, height: 512}]\n"
    "    map_sizes: [1024, 2048]      # powers of two, 64..16384\n"
    "    contours: [2, 4]\n"
    "    methods:\n"
    "      - {label: nsm, method: nsm}\n"
    "      - {label: bias-1, method: nsm, self_shadow: constant, bias: 1}\n"
    "\n"
    "Unknown keys are errors (in a research config they are typos), reported with file, line and key, exit "
    "2. -D KEY=VALUE replaces a key by its path for one run, checked as the file is; the config hash of the "
    "results covers the overrides. A method is a built-in (shadowlab list methods) or a technique package "
    "(shadowlab list techniques, doc/techniques.md). A scene file is YAML too (meshes, light, viewpoints; "
    "doc/guide.md, Scenes and models).\n";

static const char man_files[] =
    "PREFIX/share/shadowlab/configs/\n"
    "    The shipped experiments (default.yaml, ci.yaml, the theses' studies).\n"
    "PREFIX/share/shadowlab/scenes/\n"
    "    The shipped scenes.\n"
    "PREFIX/share/shadowlab/techniques/\n"
    "    The shipped technique packages.\n"
    "PREFIX/share/shadowlab/theses/\n"
    "    The theses' printed numbers that report puts beside a study's: one CSV file per thesis, "
    "README.md there gives their columns.\n"
    "DIR/shadowlab.db, DIR/shadowlab.db.lock\n"
    "    The results store of a run with --out DIR (doc/store.md), and the lock a writer holds on it while it "
    "writes (removed when it closes the store).\n"
    "DIR/cache/\n"
    "    The truth cache (--cache), shared between runs.\n";

static const char man_exit[] =
    "0 done; 1 a check failed (check, merge with a missing cell); 2 bad input or usage; 3 a system failure "
    "(output not writable, GL, Embree, memory); 130 or 143 interrupted by SIGINT or SIGTERM.\n";

static const char man_examples[] =
    "shadowlab run /usr/local/share/shadowlab/configs/default.yaml -o /tmp/r\n"
    "shadowlab run my.yaml -D map_sizes=[2048] -j 8 -q\n"
    "shadowlab run configs/morais-2015.yaml --jobs 4 --cache /scratch/cache\n"
    "shadowlab table /tmp/r/shadowlab.db --label nsm --format latex\n"
    "shadowlab check /tmp/r/shadowlab.db --baseline base.yaml --junit junit.xml\n";

static const char man_see_also[] =
    "README.md and doc/ in the source tree: guide.md (the user guide and the config reference), methods.md, "
    "techniques.md, store.md, testing.md, performance.md, glossary.md (PFL, PnFL and the other terms), "
    "references.md (the theses and papers).\n";

/* one character of plain text in roff: backslash and minus escaped, a
 * control character at the start of a line made text */
static void man_char(FILE *f, char c, int bol)
{
    if (bol && (c == '.' || c == '\''))
        fputs("\\&", f);
    if (c == '\\')
        fputs("\\e", f);
    else if (c == '-')
        fputs("\\-", f);
    else
        fputc(c, f);
}

static void man_line(FILE *f, const char *s, size_t n)
{
    for (size_t i = 0; i < n; i++)
        man_char(f, s[i], i == 0);
    fputc('\n', f);
}

/* paragraphs: a blank line is .PP; a line starting with a space, and the
 * lines after it up to a blank one, keep their layout (.nf) */
static void man_text(FILE *f, const char *s)
{
    int nf = 0;
    while (*s) {
        size_t n = strcspn(s, "\n");
        if (n == 0) {
            if (nf)
                fputs(".fi\n", f);
            nf = 0;
            fputs(".PP\n", f);
        } else {
            if (!nf && s[0] == ' ') {
                fputs(".nf\n", f);
                nf = 1;
            }
            man_line(f, s, n);
        }
        s += n + (s[n] == '\n');
    }
    if (nf)
        fputs(".fi\n", f);
}

/* the arguments of a verb's "usage: shadowlab VERB ..." lines (the first and
 * the indented ones that go on with '[' or '-'), spaces collapsed */
static void man_synopsis(FILE *f, const char *verb, const char *usage)
{
    const char *s = strchr(usage, ' ');   /* past "usage:" */
    s = s ? strchr(s + 1, ' ') : NULL;    /* past "shadowlab" */
    s = s ? strchr(s + 1, ' ') : NULL;    /* past the verb */
    char buf[1024];
    size_t len = 0;
    for (int first = 1; s && *s; first = 0) {
        size_t n = strcspn(s, "\n"), k = strspn(s, " ");
        /* a second form of the verb ("       shadowlab table DB --rows ..."): a synopsis line of its own */
        if (!first && k >= 7 && !strncmp(s + k, "shadowlab ", 10) && !strncmp(s + k + 10, verb, strlen(verb)) &&
            s[k + 10 + strlen(verb)] == ' ') {
            while (len && buf[len - 1] == ' ')
                len--;
            man_line(f, buf, len);
            fprintf(f, ".br\n.B shadowlab %s\n", verb);
            len = 0;
            k += 10 + strlen(verb);
            k += strspn(s + k, " ");
        } else if (!first && (k < 8 || (s[k] != '[' && s[k] != '-')))
            break;
        for (size_t i = k; i < n && len + 2 < sizeof buf; i++)
            if (s[i] != ' ' || (len && buf[len - 1] != ' '))
                buf[len++] = s[i];
        if (len && buf[len - 1] != ' ' && len + 2 < sizeof buf)
            buf[len++] = ' ';
        s += n + (s[n] == '\n');
    }
    while (len && buf[len - 1] == ' ')
        len--;
    man_line(f, buf, len);
}

/* a verb's help text as it prints, kept in its layout */
static void man_verbatim(FILE *f, const char *s)
{
    fputs(".nf\n", f);
    while (*s) {
        size_t n = strcspn(s, "\n");
        man_line(f, s, n);
        s += n + (s[n] == '\n');
    }
    fputs(".fi\n", f);
}

void cli_man(FILE *f)
{
    fputs(".\\\" shadowlab(1): generated by `shadowlab help --man` from harness/cli/usage.c (the table of verbs\n"
          ".\\\" and their --help texts); do not edit: edit usage.c, then build/shadowlab help --man > doc/shadowlab.1\n",
          f);
    fprintf(f, ".TH SHADOWLAB 1 \"\" \"shadowlab %s\" \"User Commands\"\n", SL_VERSION);
    fputs(".SH NAME\nshadowlab \\- measure how wrong shadow maps are, pixel by pixel, against a ray-traced "
          "truth\n.SH SYNOPSIS\n",
          f);
    for (const struct cli_verb *v = cli_verbs; v->name; v++) {
        fprintf(f, ".B shadowlab %s\n", v->name);
        man_synopsis(f, v->name, v->usage);
        fputs(".br\n", f);
    }
    fputs(".B shadowlab \\-V\\fR|\\fB\\-\\-version\n[\\-\\-verbose]\n.br\n"
          ".B shadowlab help\n.RI [ COMMAND \\fR|\\fB\\-\\-man\\fR|\\fB\\-\\-config\\fR|\\fB\\-\\-bash\\-completion ]\n",
          f);
    fputs(".SH DESCRIPTION\n", f);
    man_text(f, man_description);
    fputs(".SH COMMANDS\n", f);
    for (const struct cli_verb *v = cli_verbs; v->name; v++) {
        fprintf(f, ".SS %s\n", v->name);
        man_text(f, v->summary);
        fputs(".PP\n", f);
        man_verbatim(f, v->usage);
    }
    fputs(".SS help\nhelp prints the list of commands; help COMMAND the command's help (as COMMAND \\-\\-help); "
          "help \\-\\-man this page; help \\-\\-config the config reference (doc/config.md); "
          "help \\-\\-bash\\-completion the bash completion script.\n",
          f);
    fputs(".SH CONFIGURATION\n", f);
    man_text(f, man_config);
    fputs(".PP\nThe keys (a list's entries are key[]):\n", f);
    struct sl_diag d;
    if (sl_config_reference(f, 1, &d))   /* a key without its text: the man page says so, the test fails */
        fprintf(f, ".PP\nINCOMPLETE: %s\n", d.msg);
    fputs(".SH ENVIRONMENT\n", f);
    for (size_t i = 0; i < sizeof man_env / sizeof man_env[0]; i++) {
        fputs(".TP\n.B ", f);
        man_line(f, man_env[i].name, strlen(man_env[i].name));
        man_text(f, man_env[i].text);
    }
    fputs(".SH FILES\n", f);
    for (const char *s = man_files; *s;) {
        size_t n = strcspn(s, "\n");
        if (s[0] == ' ') {
            size_t k = strspn(s, " ");
            man_line(f, s + k, n - k);
        } else {
            fputs(".TP\n.I ", f);
            man_line(f, s, n);
        }
        s += n + (s[n] == '\n');
    }
    fputs(".SH EXIT STATUS\n", f);
    man_text(f, man_exit);
    fputs(".SH EXAMPLES\n", f);
    man_verbatim(f, man_examples);
    fputs(".SH SEE ALSO\n", f);
    man_text(f, man_see_also);
}

/* `shadowlab help --config`: doc/config.md, every key from the parser's own
 * schema (sl_config_reference); 1 when a key lacks its text. */
int cli_config_reference(FILE *f)
{
    struct sl_diag d;
    fputs("# Config reference\n\n"
          "Every key a config file may give, written by `shadowlab help --config` from the parser's own\n"
          "schema (harness/plan/config.c; do not edit: regenerate). A list's entries are `key[]`; a\n"
          "method entry also takes its method's parameters (listed below; a technique package's:\n"
          "`shadowlab show technique NAME`).\n"
          "The guide's [Configs](guide.md#configs) section explains them with examples.\n\n", f);
    if (sl_config_reference(f, 0, &d)) {
        fprintf(stderr, "shadowlab: %s\n", d.msg);
        return 1;
    }
    return 0;
}

/* ---- the bash completion -------------------------------------------------
 * `shadowlab help --bash-completion` writes scripts/shadowlab.bash-completion
 * from the same rows: the verbs, and each verb's options as its help text
 * names them (the "usage:" lines and the option lines "  -x, --long ARG"),
 * with the values a "a|b|c" argument lists; the bench's stages from bench.h's
 * list and the figure names from figrec.h/softfig.h. What depends on the
 * files at hand (scene names, a store's labels, a config's keys for -D,
 * technique names) the script asks the binary for as it completes.
 * doc::package_completion fails when the committed script differs, and when
 * an option a verb's parser accepts is missing from its help or here. */
struct comp_opt {
    char name[40];
    int  arg;            /* takes a value */
    char values[96];     /* the words of an "a|b|c" value, space-separated */
};

static int comp_is_word_char(char c) { return isalnum((unsigned char)c) || c == '-'; }

/* the option at s (a '-'): its name, and whether a value follows ("--x ARG") */
static const char *comp_scan(const char *s, struct comp_opt *o, int *n, int max)
{
    size_t k = 0;
    while (s[k] == '-')
        k++;
    size_t e = k;
    while (comp_is_word_char(s[e]))
        e++;
    if (e == k || k > 2 || e >= sizeof o[0].name)
        return s + (e ? e : 1);
    struct comp_opt *p = NULL;
    for (int i = 0; i < *n; i++)
        if (strlen(o[i].name) == e && !strncmp(o[i].name, s, e))
            p = &o[i];
    if (!p && *n < max) {
        p = &o[(*n)++];
        memset(p, 0, sizeof *p);
        memcpy(p->name, s, e);
    }
    if (p && s[e] == ' ' && s[e + 1] && !strchr(" [-|", s[e + 1])) {
        p->arg = 1;
        const char *a = s + e + 1;
        size_t an = strcspn(a, " ]\n");
        if (memchr(a, '|', an) && !p->values[0]) {
            /* the lowercase words of "a|b|c" (N|image|contours: image contours) */
            for (const char *w = a; w < a + an;) {
                size_t wn = strcspn(w, "|] \n");
                int lower = wn > 0;
                for (size_t i = 0; i < wn; i++)
                    lower &= islower((unsigned char)w[i]) != 0;
                size_t used = strlen(p->values);
                if (lower && used + wn + 2 < sizeof p->values)
                    snprintf(p->values + used, sizeof p->values - used, "%s%.*s", used ? " " : "", (int)wn, w);
                w += wn + (w[wn] == '|');
                if (w[-1] != '|')
                    break;
            }
        }
    }
    return s + e;
}

/* the options a verb's help text names; --help always */
static int comp_options(const char *usage, struct comp_opt *o, int max)
{
    int n = 0;
    int synopsis = 1;
    for (const char *s = usage; *s;) {
        size_t len = strcspn(s, "\n"), ind = strspn(s, " ");
        if (s != usage && !(synopsis && ind >= 8 && (s[ind] == '[' || s[ind] == '-')))
            synopsis = 0;
        if (synopsis) {
            for (size_t i = 0; i < len;)
                if (s[i] == '-' && i > 0 && strchr(" [|", s[i - 1]))
                    i = (size_t)(comp_scan(s + i, o, &n, max) - s);
                else
                    i++;
        } else if (ind == 2 && s[2] == '-') {
            /* "  -o, --out DIR   text": the leading options */
            const char *p = s + 2;
            while (*p == '-') {
                p = comp_scan(p, o, &n, max);
                if (p[0] == ',' && p[1] == ' ')
                    p += 2;
                else if (p[0] == ' ' && p[1] != ' ' && p[1] != '-')
                    break;
                else if (p[0] == ' ' && p[1] == '-')
                    p++;
                else
                    break;
            }
        }
        s += len + (s[len] == '\n');
    }
    struct comp_opt help = {"--help", 0, ""};
    int have = 0;
    for (int i = 0; i < n; i++)
        have |= !strcmp(o[i].name, "--help");
    if (!have && n < max)
        o[n++] = help;
    return n;
}

/* the first argument a verb's synopsis names: "CONFIG|SCENE", "DB", "methods|scenes" */
static void comp_first_arg(const char *usage, char *out, size_t n)
{
    const char *s = strchr(usage, ' ');
    s = s ? strchr(s + 1, ' ') : NULL;
    s = s ? strchr(s + 1, ' ') : NULL;
    out[0] = 0;
    if (s)
        snprintf(out, n, "%.*s", (int)strcspn(s + 1, " \n"), s + 1);
}

void cli_completion(FILE *f)
{
    fputs("# bash completion for shadowlab: generated by `shadowlab help --bash-completion` from\n"
          "# harness/cli/usage.c (the table of verbs and their --help texts); do not edit: edit usage.c,\n"
          "# then build/shadowlab help --bash-completion > scripts/shadowlab.bash-completion\n"
          "# Installed as share/bash-completion/completions/shadowlab.\n",
          f);
    /* a comma-separated list: complete its last item */
    fputs("_shadowlab_list()\n{\n"
          "    local pre=\"\" last=$cur\n"
          "    case $cur in *,*) pre=${cur%,*},; last=${cur##*,} ;; esac\n"
          "    COMPREPLY=($(compgen -P \"$pre\" -W \"$1\" -- \"$last\"))\n"
          "    compopt -o nospace 2>/dev/null\n}\n\n",
          f);
    fputs("_shadowlab()\n{\n"
          "    local cur prev verb i db cfg\n"
          "    cur=${COMP_WORDS[COMP_CWORD]}\n"
          "    prev=${COMP_WORDS[COMP_CWORD-1]}\n"
          "    verb=${COMP_WORDS[1]}\n",
          f);
    fputs("    if [ \"$COMP_CWORD\" -eq 1 ]; then\n        COMPREPLY=($(compgen -W \"", f);
    for (const struct cli_verb *v = cli_verbs; v->name; v++)
        fprintf(f, "%s ", v->name);
    fputs("help -V --version --help\" -- \"$cur\"))\n        return\n    fi\n", f);
    fputs("    # the store and the config named on the line\n"
          "    for ((i = 2; i < COMP_CWORD; i++)); do\n"
          "        case ${COMP_WORDS[i]} in *.db) db=${COMP_WORDS[i]} ;; *.yaml|*.yml) cfg=${COMP_WORDS[i]} ;; esac\n"
          "    done\n",
          f);
    /* values listed in a help text ("--format md|csv|latex"), per verb */
    fputs("    case \"$verb $prev\" in\n", f);
    for (const struct cli_verb *v = cli_verbs; v->name; v++) {
        struct comp_opt o[48];
        int n = comp_options(v->usage, o, 48);
        for (int i = 0; i < n; i++)
            if (o[i].values[0] && strcmp(o[i].name, "--figures"))
                fprintf(f, "        \"%s %s\") COMPREPLY=($(compgen -W \"%s\" -- \"$cur\")); return ;;\n", v->name,
                        o[i].name, o[i].values);
    }
    fputs("    esac\n", f);
    /* values that need a list of their own, whatever the verb */
    fputs("    case $prev in\n"
          "        -o|--out|--cache) COMPREPLY=($(compgen -d -- \"$cur\")); return ;;\n"
          "        --db|--stored-in) COMPREPLY=($(compgen -f -X '!*.db' -- \"$cur\") $(compgen -d -- \"$cur\")); "
          "return ;;\n"
          "        --baseline|--json|--junit|--csv|--markdown) COMPREPLY=($(compgen -f -- \"$cur\")); return ;;\n"
          "        --scene)\n"
          "            COMPREPLY=($(compgen -W \"$(shadowlab list scenes 2>/dev/null | awk '{ print $1 }')\" -- "
          "\"$cur\")); return ;;\n"
          "        --label)\n"
          "            # the labels the store named on the line holds (a,b: a list)\n"
          "            [ -n \"$db\" ] && _shadowlab_list \"$(shadowlab table \"$db\" --format csv 2>/dev/null |\n"
          "                awk -F, 'NR > 1 { print $6 }' | sort -u)\"\n"
          "            return ;;\n"
          "        -D|--define)\n"
          "            # the top-level keys of the config named on the line, as validate fills it in\n"
          "            [ -n \"$cfg\" ] && COMPREPLY=($(compgen -W \"$(shadowlab validate \"$cfg\" 2>/dev/null |\n"
          "                awk '/^[a-z_]+:/ { sub(/:.*/, \"=\"); print }')\" -- \"$cur\"))\n"
          "            compopt -o nospace 2>/dev/null\n"
          "            return ;;\n",
          f);
    fputs("        --only) _shadowlab_list \"", f);
    static const char *const stages[] = {
#define SL_COMP_STAGE(id, name) name,
        SL_BENCH_STAGES(SL_COMP_STAGE)
#undef SL_COMP_STAGE
    };
    for (size_t i = 0; i < sizeof stages / sizeof stages[0]; i++)
        fprintf(f, "%s%s", i ? " " : "", stages[i]);
    fputs("\"; return ;;\n        --summary) _shadowlab_list \"", f);
    for (int k = 0; k < SL_FIG_COUNT; k++)
        fprintf(f, "%s%s", k ? " " : "", sl_figure_name((enum sl_figure)k));
    fputs("\"; return ;;\n        --figures) _shadowlab_list \"all", f);
    for (int k = 0; k < SL_FIG_COUNT; k++)
        fprintf(f, " %s", sl_figure_name((enum sl_figure)k));
    for (int k = 0; k < SL_SFIG_COUNT; k++)
        fprintf(f, " %s", sl_soft_figure_name((enum sl_soft_figure)k));
    /* a pivot's one figure: any of those, or a counter or time of the cell */
    fputs("\"; return ;;\n        --figure) _shadowlab_list \"", f);
    for (int k = 0; k < SL_FIG_COUNT; k++)
        fprintf(f, "%s%s", k ? " " : "", sl_figure_name((enum sl_figure)k));
    for (int k = 0; k < SL_SFIG_COUNT; k++)
        fprintf(f, " %s", sl_soft_figure_name((enum sl_soft_figure)k));
    for (int k = 0; sl_pivot_counter_name(k); k++)
        fprintf(f, " %s", sl_pivot_counter_name(k));
    fputs("\"; return ;;\n", f);
    /* every other option that takes a value: nothing to offer */
    fputs("        ", f);
    int first = 1;
    char seen[2048] = " ";
    static const char *const listed[] = {"-o", "--out", "--cache", "--db", "--stored-in", "--baseline", "--json",
                                         "--junit", "--csv", "--markdown", "--scene", "--label", "-D", "--define",
                                         "--only", "--summary", "--figures", "--figure", "--gl", "--format"};
    for (const struct cli_verb *v = cli_verbs; v->name; v++) {
        struct comp_opt o[48];
        int n = comp_options(v->usage, o, 48);
        for (int i = 0; i < n; i++) {
            if (!o[i].arg || o[i].values[0])
                continue;
            int skip = 0;
            for (size_t j = 0; j < sizeof listed / sizeof listed[0]; j++)
                skip |= !strcmp(listed[j], o[i].name);
            char key[48];
            snprintf(key, sizeof key, " %s ", o[i].name);
            if (skip || strstr(seen, key) || strlen(seen) + strlen(key) >= sizeof seen)
                continue;
            strcat(seen, key + 1);
            fprintf(f, "%s%s", first ? "" : "|", o[i].name);
            first = 0;
        }
    }
    fputs(") return ;;\n    esac\n", f);
    /* options, then the verb's arguments */
    fputs("    case $verb in\n", f);
    for (const struct cli_verb *v = cli_verbs; v->name; v++) {
        struct comp_opt o[48];
        int n = comp_options(v->usage, o, 48);
        fprintf(f, "        %s)\n            case $cur in -*) COMPREPLY=($(compgen -W \"", v->name);
        for (int i = 0; i < n; i++)
            fprintf(f, "%s%s", i ? " " : "", o[i].name);
        fputs("\" -- \"$cur\")); return ;; esac\n", f);
        char a[64];
        comp_first_arg(v->usage, a, sizeof a);
        int lower = a[0] != 0;
        for (const char *c = a; *c; c++)
            lower &= islower((unsigned char)*c) || *c == '|';
        if (lower && strchr(a, '|') && !strstr(v->synopsis, " NAME")) {
            char w[64];
            snprintf(w, sizeof w, "%s", a);
            for (char *c = w; *c; c++)
                if (*c == '|')
                    *c = ' ';
            fprintf(f, "            [ \"$COMP_CWORD\" -eq 2 ] && COMPREPLY=($(compgen -W \"%s\" -- \"$cur\"))\n", w);
        } else if (lower) {
            for (char *c = a; *c; c++)   /* "show method|technique NAME": either word first */
                if (*c == '|')
                    *c = ' ';
            /* "show technique NAME": the word, then the names `list` gives for it */
            fprintf(f, "            if [ \"$COMP_CWORD\" -eq 2 ]; then COMPREPLY=($(compgen -W \"%s\" -- \"$cur\"))\n"
                       "            else COMPREPLY=($(compgen -W \"$(shadowlab list \"${COMP_WORDS[2]}s\" 2>/dev/null |"
                       " awk '{ print $1 }')\" -- \"$cur\")); fi\n",
                    a);
        } else if (strstr(a, "DB") || strstr(a, ".db")) {
            fputs("            COMPREPLY=($(compgen -f -X '!*.db' -- \"$cur\") $(compgen -d -- \"$cur\"))\n", f);
        } else if (!strcmp(a, "SCENE")) {
            /* a scene file, or a scene's name */
            fputs("            COMPREPLY=($(compgen -f -X '!*.yaml' -- \"$cur\") $(compgen -d -- \"$cur\")\n"
                  "                $(compgen -W \"$(shadowlab list scenes 2>/dev/null | awk '{ print $1 }')\" -- \"$cur\"))\n",
                  f);
        } else if (strstr(a, "CONFIG") || strstr(a, "FILE") || strstr(a, "SCENE")) {
            fputs("            COMPREPLY=($(compgen -f -X '!*.yaml' -- \"$cur\") $(compgen -d -- \"$cur\"))\n",
                  f);
        }
        fputs("            ;;\n", f);
    }
    fputs("        help) COMPREPLY=($(compgen -W \"", f);
    for (const struct cli_verb *v = cli_verbs; v->name; v++)
        fprintf(f, "%s ", v->name);
    fputs("--man --bash-completion --config\" -- \"$cur\")) ;;\n    esac\n}\ncomplete -F _shadowlab shadowlab\n", f);
}
