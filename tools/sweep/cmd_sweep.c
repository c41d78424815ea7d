/* touchdown sweep: run a case over a grid of key values in parallel, one summary row per point. */
#include "common/cli.h"
#include "sweep/sweep_mpi.h"
#include "touchdown/json.h"
#include "touchdown/sweep.h"

#include <fcntl.h>
#include <getopt.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static const char sweep_usage[] =
    "usage: touchdown sweep [OPTIONS] CASE\n"
    "\n"
    "Run CASE at every point of a grid of case-key values, in parallel worker processes, and\n"
    "write one table with a row per point: the swept values, the point's status and message,\n"
    "and what its run summary leads with (peak housing force, impulse, friction work, time in\n"
    "contact, contacts, first contact, ending and its whirl frequency, return to a free orbit,\n"
    "final speed, peak AMB load), then its wall time.\n"
    "\n"
    "options:\n"
    "  -v, --vary KEY=START:STOP:N  sweep KEY over N >= 1 evenly spaced values, both ends included\n"
    "      --vary KEY=START:STOP:N:log  N values in geometric progression, START and STOP > 0\n"
    "      --vary KEY=V1,V2,...     sweep KEY over a list of values as --set takes them (numbers,\n"
    "                       true/false, \"quoted strings\"); each --vary is an axis of a full\n"
    "                       grid, the first varying slowest (at most 8 axes, 100000 points)\n"
    "  -w, --with KEY=SPEC  zip KEY (a range or list as for --vary) onto the axis of the --vary\n"
    "                       before it: its i-th value goes with that axis's i-th, so it needs as\n"
    "                       many values (at most 16 swept keys in all)\n"
    "  -s, --set KEY=VALUE  override a case key at every point (repeatable, as for touchdown run)\n"
    "      --point-files DIR  also keep each point's full result, DIR/point-NNNNNN.h5 (NNNNNN the\n"
    "                       point's index, as in the table), the file touchdown run writes\n"
    "      --point-csv      with --point-files, also DIR/point-NNNNNN.csv (and its events file)\n"
    "      --point-timeout S  stop a point whose worker has run S seconds of wall time: its row\n"
    "                       is failed with status \"timeout\" (default: no limit)\n"
    "  -j, --jobs N         worker processes, 1..256 (default: the number of online CPUs; under\n"
    "                       MPI: workers per rank, default 1)\n"
    "  -o, --output PREFIX  write PREFIX.csv and PREFIX.h5 (default: CASENAME-sweep)\n"
    "  -q, --quiet          print no text summary (errors still go to stderr)\n"
    "      --json           print the sweep's counts and files as one JSON object on stdout\n"
    "      --progress       print the progress line even with -q, --json or stderr not a terminal\n"
    "                       (then a whole line every 5 s and the last one)\n"
    "      --no-progress    never print it (default: on when stderr is a terminal, without -q\n"
    "                       and --json: one line rewritten at most 4 times a second)\n"
    "  -h, --help           this help\n"
    "\n"
    "The case file's own `sweep` group (docs/case-format.md) adds its axes after those of the\n"
    "command line; a file axis with a key that --vary or --with also sweeps is left out whole (the\n"
    "command line replaces it). The table records where each axis came from.\n"
    "\n"
    "Each point is CASE loaded with every --set, then KEY=VALUE for each swept key, so any key\n"
    "that --set accepts can be swept. Every point's case is loaded and checked before anything\n"
    "runs: a bad key or value is one error line naming it (exit 2). Each point runs in its own\n"
    "process, as touchdown run does but without output files (unless --point-files); a point that\n"
    "fails (solver, an impossible start state) or whose worker dies is a row with its status and\n"
    "message, and the sweep goes on. Rows are in point order whatever -j is. The table files are\n"
    "written at the end under temporary names and renamed, like those of touchdown run;\n"
    "SIGINT/SIGTERM/SIGHUP stop the workers and keep the table, its unfinished points marked\n"
    "\"not run\" and the files marked incomplete. Columns and units: docs/output-format.md,\n"
    "\"Sweep table\".\n"
    "\n"
    "Resume: each point's row goes to PREFIX.journal as the point ends; the same command run again\n"
    "after an interruption (Ctrl-C, a kill, a lost machine) runs only the points the journal lacks.\n"
    "The journal is removed once a finished table is written; one of another sweep (another case,\n"
    "--set, --vary, --with or version) is refused.\n"
    "\n";

/* The rest of the usage (one string would be longer than C99 promises to compile). */
static const char sweep_usage_more[] =
    "Progress: \"sweep: DONE/POINTS points, R running, F failed, ETA T\" on stderr, DONE counting the\n"
    "resumed points, T from the mean wall time of the points so far over every worker.\n"
    "\n"
    "MPI (if built in, see touchdown --version): mpirun -np N touchdown sweep ... runs the sweep\n"
    "over N ranks, each with -j workers (one rank per node and -j its cores). Rank 0 checks the\n"
    "points, hands them out one at a time to every rank's free workers (its own included), prints\n"
    "the progress, the failures and the summary, and writes the table. Each rank records its rows in\n"
    "PREFIX.journal.rank-K; rank 0 merges them into the table at the end and removes them with the\n"
    "journal. A resume, with any number of ranks or without MPI, reads the journal and every part.\n"
    "MPI is used only when an MPI launcher started the tool (OMPI_COMM_WORLD_SIZE, PMIX_RANK, or\n"
    "PMI_RANK and PMI_SIZE in the environment).\n"
    "\n"
    "exit codes: 0 every point ran to its end, 1 some point failed, the sweep was interrupted or\n"
    "the table could not be written, 2 bad input or usage (any point's case included).\n";

typedef struct sweep_options {
    td_cli_sets sets;
    td_sweep_grid *grid;
    const char *prefix;
    const char *case_path;
    const char *point_dir;
    double point_timeout;
    int jobs, json, quiet, point_csv, progress; /* progress: 1 --progress, 0 --no-progress, -1 neither */
} sweep_options;

static void print_usage(FILE *f)
{
    fputs(sweep_usage, f);
    fputs(sweep_usage_more, f);
}

static int parse_jobs(const char *text, int *jobs)
{
    char *end;
    long n = strtol(text, &end, 10);
    if (end == text || *end || n < 1 || n > TD_SWEEP_POOL_MAX) {
        td_cli_error("sweep", "--jobs: expected a whole number from 1 to %d, got '%s'", TD_SWEEP_POOL_MAX, text);
        return TD_EXIT_USAGE;
    }
    *jobs = (int)n;
    return 0;
}

/* The longest a point may run: a finite number of seconds > 0, at most a year. */
static int parse_timeout(const char *text, double *timeout)
{
    char *end;
    double v = strtod(text, &end);
    if (end == text || *end || !(v > 0.0) || v > TD_SWEEP_POOL_TIMEOUT_MAX) {
        td_cli_error("sweep", "--point-timeout: expected seconds > 0 and at most %g, got '%s'",
                     TD_SWEEP_POOL_TIMEOUT_MAX, text);
        return TD_EXIT_USAGE;
    }
    *timeout = v;
    return 0;
}

/* --vary (with = 0) or --with (with = 1): one more axis or key of the grid. */
static int add_key(td_sweep_grid *g, const char *spec, int with)
{
    td_error err;
    td_error_clear(&err);
    if ((with ? td_sweep_grid_with(g, spec, &err) : td_sweep_grid_vary(g, spec, &err)) == TD_OK)
        return 0;
    td_cli_error("sweep", "%s", err.message);
    return TD_EXIT_USAGE;
}

/* Options into o; returns 0, or an exit code (-1: --help was printed, exit 0). */
static int parse_options(int argc, char **argv, sweep_options *o)
{
    enum { OPT_JSON = 256, OPT_POINT_FILES, OPT_POINT_CSV, OPT_PROGRESS, OPT_NO_PROGRESS, OPT_POINT_TIMEOUT };
    static const struct option longopts[] = {{"vary", required_argument, NULL, 'v'},
                                             {"with", required_argument, NULL, 'w'},
                                             {"set", required_argument, NULL, 's'},
                                             {"jobs", required_argument, NULL, 'j'},
                                             {"output", required_argument, NULL, 'o'},
                                             {"point-files", required_argument, NULL, OPT_POINT_FILES},
                                             {"point-csv", no_argument, NULL, OPT_POINT_CSV},
                                             {"point-timeout", required_argument, NULL, OPT_POINT_TIMEOUT},
                                             {"quiet", no_argument, NULL, 'q'},
                                             {"json", no_argument, NULL, OPT_JSON},
                                             {"progress", no_argument, NULL, OPT_PROGRESS},
                                             {"no-progress", no_argument, NULL, OPT_NO_PROGRESS},
                                             {"help", no_argument, NULL, 'h'},
                                             {NULL, 0, NULL, 0}};
    int opt, code = 0;
    optind = 1;
    while (!code && (opt = getopt_long(argc, argv, "v:w:s:j:o:qh", longopts, NULL)) != -1) {
        switch (opt) {
        case 'v': code = add_key(o->grid, optarg, 0); break;
        case 'w': code = add_key(o->grid, optarg, 1); break;
        case OPT_POINT_FILES: o->point_dir = optarg; break;
        case OPT_POINT_CSV: o->point_csv = 1; break;
        case OPT_POINT_TIMEOUT: code = parse_timeout(optarg, &o->point_timeout); break;
        case 's': code = td_cli_add_set(&o->sets, optarg); break;
        case 'j': code = parse_jobs(optarg, &o->jobs); break;
        case 'o': o->prefix = optarg; break;
        case 'q': o->quiet = 1; break;
        case OPT_JSON: o->json = 1; break;
        case OPT_PROGRESS: o->progress = 1; break;
        case OPT_NO_PROGRESS: o->progress = 0; break;
        case 'h': print_usage(stdout); return -1;
        default: print_usage(stderr); return TD_EXIT_USAGE;
        }
    }
    if (!code && optind != argc - 1) {
        td_cli_error("sweep", "expected exactly one case file (see touchdown sweep --help)");
        code = TD_EXIT_USAGE;
    }
    if (!code && o->point_csv && !o->point_dir) {
        td_cli_error("sweep", "--point-csv needs --point-files DIR");
        code = TD_EXIT_USAGE;
    }
    if (!code)
        o->case_path = argv[optind];
    return code;
}

/* The case file's sweep group after the command line's axes (td_sweep_grid_from_case). */
static int add_case_axes(td_sweep_grid *g, const td_case *base)
{
    td_error err;
    td_error_clear(&err);
    if (td_sweep_grid_from_case(g, base, &err) == TD_OK)
        return 0;
    fprintf(stderr, "touchdown: %s\n", err.message);
    return TD_EXIT_USAGE;
}

/* 0, or TD_EXIT_USAGE after an error line when a file of point p (td_output_files of out: its .h5,
 * .csv, .events.csv and .windows.csv, the list the run's own check uses) is one of the sweep's own
 * files (the table's CSV and HDF5 files, the journal), by name or by device and inode
 * (td_output_same_file): the table, written last, would replace it. */
static int check_point_against_table(const sweep_job *job, long p, const td_output_options *out,
                                     const td_output_options *table, const char *journal)
{
    td_output_file mine[TD_OUTPUT_FILES];
    const char *theirs[3];
    int i, j, n = td_output_files(out, mine);
    theirs[0] = table->csv_path;
    theirs[1] = table->hdf5_path;
    theirs[2] = journal;
    for (i = 0; i < n; i++)
        for (j = 0; j < 3; j++)
            if (td_output_same_file(mine[i].path, theirs[j])) {
                td_cli_error("sweep",
                             "--point-files %s: %s, a file of point %ld, is the same file as the sweep's %s (%s): "
                             "choose another -o prefix or --point-files directory",
                             job->point_dir, mine[i].path, p, j == 2 ? "journal" : "table", theirs[j]);
                return TD_EXIT_USAGE;
            }
    return 0;
}

/* The points' result files, checked by the rules of touchdown run before anything runs, every
 * point's: the names fit, no file of a point (.h5, .csv, .events.csv, .windows.csv) is an input (the case file
 * or an @include, compared by device and inode) or another of its files, is anything but a
 * regular file, or lies in a directory that is missing or not writable; nor is it one of the
 * sweep's own files (the table's CSV and HDF5 files, the journal). */
static int check_point_files(const sweep_job *job, const td_case *c, const td_output_options *table,
                             const char *journal)
{
    td_output_options out;
    const char *const *files;
    long p, n = td_sweep_grid_points(job->grid);
    int k = 0, code;
    td_error err;
    if (!job->point_dir)
        return 0;
    files = td_case_files(c, &k);
    for (p = 0; p < n; p++) {
        memset(&out, 0, sizeof out);
        if (sweep_point_paths(job, p, &out)) {
            td_cli_error("sweep", "--point-files: the directory name is too long (at most %d bytes a file name)",
                         TD_OUTPUT_PATH_SIZE - 1);
            return TD_EXIT_USAGE;
        }
        td_error_clear(&err);
        if (td_output_check_paths(&out, files, k, &err) != TD_OK) {
            td_cli_error("sweep", "--point-files %s: %s", job->point_dir, err.message);
            return TD_EXIT_USAGE;
        }
        if ((code = check_point_against_table(job, p, &out, table, journal)) != 0)
            return code;
    }
    return 0;
}

/* The option that made key k: "--vary", or "--with" for a key zipped onto an earlier key's axis. */
static const char *key_option(const td_sweep_grid *g, int k)
{
    int j;
    for (j = 0; j < k; j++)
        if (td_sweep_grid_axis(g, j) == td_sweep_grid_axis(g, k))
            return "--with";
    return "--vary";
}

/* The error line of a point whose case did not load. The case reader names a swept value as the
 * override it was given as ("--set 'KEY=VALUE'"); the line names it as the user wrote it: the
 * case file's "FILE:LINE: sweep.vary[i]" first, or "--vary 'KEY=VALUE'" for the command line. */
static void report_point_error(const td_sweep_grid *g, const char *message)
{
    static const char set[] = "--set '";
    char probe[TD_SWEEP_KEY_SIZE + 16];
    const char *at;
    int k;
    for (k = 0; k < td_sweep_grid_keys(g); k++) {
        snprintf(probe, sizeof probe, "%s%s=", set, td_sweep_grid_key(g, k));
        if (!(at = strstr(message, probe)))
            continue;
        if (strcmp(td_sweep_grid_origin(g, k), "command line") != 0)
            fprintf(stderr, "touchdown: %s: %s\n", td_sweep_grid_origin(g, k), message);
        else
            fprintf(stderr, "touchdown: %.*s%s '%s\n", (int)(at - message), message, key_option(g, k),
                    at + strlen(set));
        return;
    }
    fprintf(stderr, "touchdown: %s\n", message);
}

/* Load every point's case once before anything runs, so that a bad key or value is found at
 * once and not after hours of other points. Returns 0 or TD_EXIT_USAGE (with the error line). */
static int check_points(const sweep_job *job)
{
    const char *items[TD_CLI_MAX_SETS + TD_SWEEP_MAX_KEYS];
    char store[TD_SWEEP_MAX_KEYS][TD_SWEEP_KEY_SIZE + TD_SWEEP_VALUE_SIZE];
    long p, n = td_sweep_grid_points(job->grid);
    td_case *c = NULL;
    td_error err;
    for (p = 0; p < n; p++) {
        int k = sweep_point_overrides(job, p, items, store);
        td_error_clear(&err);
        if (td_cli_case_checked(job->case_path, items, k, &c, &err) != TD_OK) {
            report_point_error(job->grid, err.message);
            return TD_EXIT_USAGE;
        }
        td_case_free(&c);
    }
    return 0;
}

/* PREFIX.csv and PREFIX.h5, refused before the sweep by the rules of touchdown run, and the
 * journal PREFIX.journal (journal: TD_OUTPUT_PATH_SIZE bytes), refused with its parts when one
 * is an input. */
static int choose_outputs(td_output_options *out, char *journal, const sweep_options *o, const td_case *c)
{
    char stem[TD_OUTPUT_PATH_SIZE];
    const char *const *files;
    int n = 0, code;
    td_error err;
    memset(out, 0, sizeof *out);
    if (o->prefix && (code = td_cli_prefix(o->prefix, "sweep")) != 0)
        return code;
    if (o->prefix)
        code = td_cli_path(stem, sizeof stem, o->prefix, "", "sweep", "--output");
    else
        code = td_cli_path(stem, sizeof stem, td_case_name(c), "-sweep", "sweep", td_case_path(c));
    if (!code)
        code = td_cli_path(out->csv_path, sizeof out->csv_path, stem, ".csv", "sweep", "--output");
    if (!code)
        code = td_cli_path(out->hdf5_path, sizeof out->hdf5_path, stem, ".h5", "sweep", "--output");
    if (!code)
        code = td_cli_path(journal, TD_OUTPUT_PATH_SIZE, stem, ".journal", "sweep", "--output");
    if (code)
        return code;
    files = td_case_files(c, &n);
    td_error_clear(&err);
    if (td_output_check_paths(out, files, n, &err) != TD_OK) {
        td_cli_error("sweep", "%s; choose another -o prefix", err.message);
        return TD_EXIT_USAGE;
    }
    return sweep_store_check_inputs(journal, files, n); /* the journal and its parts on disk */
}

/* Counts of the rows by state, what this run computed, and the seconds the merge of the parts and
 * the writing of the table took. */
typedef struct sweep_counts {
    long points, done, failed, not_run, resumed, ran, warned;
    double check_time, merge_time;
} sweep_counts;

static sweep_counts count_rows(const td_sweep_row *rows, long n)
{
    sweep_counts k;
    long p;
    memset(&k, 0, sizeof k);
    k.points = n;
    for (p = 0; p < n; p++) {
        k.done += rows[p].state == TD_SWEEP_DONE;
        k.failed += rows[p].state == TD_SWEEP_FAILED;
        k.not_run += rows[p].state == TD_SWEEP_NOT_RUN;
        k.warned += rows[p].warnings[0] != '\0';
    }
    return k;
}

/* One line on stderr when points have warnings (the table's `warnings` column): how many, and the
 * first point's. */
static void report_warnings(const td_sweep_grid *g, const td_sweep_row *rows, const sweep_counts *k)
{
    long p;
    int a;
    if (!k->warned)
        return;
    for (p = 0; p < k->points && !rows[p].warnings[0]; p++)
        ;
    fprintf(stderr,
            "touchdown sweep: warning: %ld of %ld points have warnings (the table's warnings column), first "
            "point %ld (",
            k->warned, k->points, p);
    for (a = 0; a < td_sweep_grid_keys(g); a++)
        fprintf(stderr, "%s%s=%s", a ? " " : "", td_sweep_grid_key(g, a), td_sweep_grid_value(g, p, a));
    fprintf(stderr, "): %s\n", rows[p].warnings);
}

/* Both table files; returns 0, or TD_EXIT_FAILED after an error line. */
static int write_table(const td_output_options *out, const td_sweep_table *t)
{
    td_error err;
    int code = 0;
    td_error_clear(&err);
    if (td_sweep_write_csv(out->csv_path, t, &err) != TD_OK) {
        fprintf(stderr, "touchdown: %s\n", err.message);
        code = TD_EXIT_FAILED;
    }
    td_error_clear(&err);
    if (td_sweep_write_hdf5(out->hdf5_path, t, &err) != TD_OK) {
        fprintf(stderr, "touchdown: %s\n", err.message);
        code = TD_EXIT_FAILED;
    }
    return code;
}

static void print_json_path(const char *name, const char *path)
{
    int n = td_json_string(NULL, 0, path);
    char *buf = malloc((size_t)n + 1);
    if (buf) {
        td_json_string(buf, (size_t)n + 1, path);
        printf(",\"%s\":%s", name, buf);
    }
    free(buf);
}

/* How the sweep ran: its ranks (1 without MPI), the workers of each, the wall time. */
typedef struct sweep_layout {
    int ranks, jobs;
    double wall;
} sweep_layout;

static void print_result(const sweep_options *o, const sweep_counts *k, const td_output_options *out,
                         const sweep_layout *l)
{
    if (o->json) {
        printf("{\"library_version\":\"%s\",\"points\":%ld,\"done\":%ld,\"failed\":%ld,\"not_run\":%ld,"
               "\"resumed\":%ld,\"ran\":%ld,\"warned\":%ld,\"complete\":%s,\"ranks\":%d,\"jobs\":%d,"
               "\"wall_time\":%.17g,\"check_time\":%.17g,\"merge_time\":%.17g",
               td_version(), k->points, k->done, k->failed, k->not_run, k->resumed, k->ran, k->warned,
               k->not_run ? "false" : "true", l->ranks, l->jobs, l->wall, k->check_time, k->merge_time);
        print_json_path("csv_path", out->csv_path);
        print_json_path("hdf5_path", out->hdf5_path);
        printf("}\n");
    } else if (!o->quiet) {
        printf("sweep: %ld points: %ld ran to the end, %ld failed, %ld not run (%ld resumed from the journal); "
               "%d workers",
               k->points, k->done, k->failed, k->not_run, k->resumed, l->ranks * l->jobs);
        if (l->ranks > 1)
            printf(" (%d ranks x %d)", l->ranks, l->jobs);
        printf(", wall time %.2f s\ntable: %s, %s%s\n", l->wall, out->csv_path, out->hdf5_path,
               k->not_run ? " (incomplete)" : "");
    }
}

/* Under MPI the rows come from the parts every rank wrote (read over the rows rank 0 holds
 * already: those it was sent, its own, the resumed ones). */
static void merge_parts(const sweep_world *w, const sweep_go *go, long n, td_sweep_row *rows)
{
    long found;
    if (w->size > 0 && sweep_store_read(go->journal, go->fp, n, rows, &found))
        td_cli_error("sweep", "the parts could not be merged: the table holds the rows sent to rank 0");
}

/* The table of rows[], written; the journal and parts removed once a finished one is. Returns
 * 0 or TD_EXIT_FAILED, and the counts in *k. */
static int finish_table(const sweep_options *o, const td_case *base, const td_output_options *out,
                        const td_sweep_row *rows, sweep_counts *k, const char *journal)
{
    long n = td_sweep_grid_points(o->grid);
    td_sweep_table t;
    char reason[128];
    int code;
    snprintf(reason, sizeof reason, "interrupted: %ld of %ld points not run", k->not_run, n);
    memset(&t, 0, sizeof t);
    t.grid = o->grid;
    t.rows = rows;
    t.case_text = td_case_text(base);
    t.sets = o->sets.items;
    t.n_sets = o->sets.count;
    t.complete = k->not_run == 0;
    t.reason = k->not_run ? reason : NULL;
    code = write_table(out, &t);
    if (!code && !k->not_run)
        sweep_store_remove(journal); /* kept until a finished table is written */
    if (k->not_run)
        td_cli_error("sweep", "%s", reason);
    return code;
}

/* Where rank 0 (or the one process) records its own rows: the journal, or its part under MPI. */
static int open_own_journal(const sweep_world *w, const sweep_go *go, long n, sweep_journal **j)
{
    char part[SWEEP_PART_PATH_SIZE];
    if (w->size == 0)
        return sweep_journal_open(go->journal, go->fp, n, j);
    sweep_part_path(part, go->journal, w->rank);
    return sweep_journal_open(part, go->fp, n, j);
}

/* Run the points not resumed (over every rank under MPI), merge, write the table, report. */
static int run_sweep(const sweep_options *o, const td_case *base, sweep_book *b, const td_output_options *out,
                     const sweep_world *w, const sweep_go *go)
{
    sweep_layout l;
    sweep_counts k;
    double t0 = td_cli_now(), t1;
    int code, lost;
    l.ranks = w->size > 0 ? w->size : 1;
    l.jobs = o->jobs > b->points ? (int)b->points : o->jobs;
    b->workers = l.ranks * l.jobs;
    b->progress.mode = sweep_progress_choose(o->progress, o->quiet || o->json);
    code = open_own_journal(w, go, b->points, &b->journal);
    if (code && w->size == 0)
        return code;
    /* under MPI the other ranks wait for points: rank 0 serves them all the same, without workers */
    lost = sweep_mpi_lead(w, b, code ? 0 : l.jobs, td_cli_catch_signals());
    code = 0;
    sweep_journal_close(&b->journal);
    sweep_book_progress(b, 1);
    t1 = td_cli_now();
    merge_parts(w, go, b->points, b->rows);
    k = count_rows(b->rows, b->points);
    k.resumed = b->resumed;
    k.ran = b->ran;
    k.check_time = b->check_time;
    code = finish_table(o, base, out, b->rows, &k, go->journal);
    k.merge_time = td_cli_now() - t1;
    l.wall = td_cli_now() - t0;
    report_warnings(o->grid, b->rows, &k);
    print_result(o, &k, out, &l);
    code = code ? code : (k.failed || k.not_run ? TD_EXIT_FAILED : TD_EXIT_OK);
    sweep_mpi_tell(w, code, lost);
    return code;
}

static int default_jobs(void)
{
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    return n < 1 ? 1 : (n > TD_SWEEP_POOL_MAX ? TD_SWEEP_POOL_MAX : (int)n);
}

/* Rank 0's checks before anything runs: the options, every point's case, the outputs, the
 * journal and parts (read into rows, which are allocated here). */
static int prepare(int argc, char **argv, sweep_options *o, sweep_job *job, td_case **base, td_output_options *out,
                   sweep_book *b, sweep_go *go)
{
    long p;
    int code = parse_options(argc, argv, o);
    job->case_path = o->case_path;
    job->point_dir = o->point_dir;
    job->point_csv = o->point_csv;
    job->point_timeout = o->point_timeout;
    if (!code)
        code = td_cli_load_case(o->case_path, &o->sets, base);
    if (!code)
        code = add_case_axes(o->grid, *base);
    if (!code)
        code = choose_outputs(out, go->journal, o, *base);
    if (!code)
        code = check_point_files(job, *base, out, go->journal);
    if (!code)
        code = check_points(job);
    if (code)
        return code;
    b->points = td_sweep_grid_points(o->grid);
    b->rows = malloc((size_t)b->points * sizeof *b->rows);
    if (!b->rows) {
        td_cli_error("sweep", "out of memory for %ld rows", b->points);
        return TD_EXIT_FAILED;
    }
    for (p = 0; p < b->points; p++)
        td_sweep_row_unknown(&b->rows[p], TD_SWEEP_NOT_RUN, "not run", "");
    go->fp = sweep_fingerprint(*base, o->grid);
    code = sweep_store_read(go->journal, go->fp, b->points, b->rows, &b->resumed);
    for (p = 0; p < b->points; p++) /* the progress line counts the resumed failures too */
        b->failed += b->rows[p].state == TD_SWEEP_FAILED;
    return code;
}

static void init_options(sweep_options *o, const sweep_world *w, sweep_job *job)
{
    memset(o, 0, sizeof *o);
    o->jobs = w->size > 0 ? 1 : default_jobs(); /* under MPI: workers per rank */
    o->progress = -1;
    job->case_path = NULL;
    job->sets = &o->sets;
    job->grid = NULL;
    job->point_dir = NULL;
    job->point_csv = 0;
    job->point_timeout = 0.0;
}

/* The one process of a sweep, or rank 0 of an MPI run. */
static int sweep_lead(int argc, char **argv, const sweep_world *w)
{
    sweep_options o;
    sweep_job job;
    sweep_book b;
    sweep_go go;
    td_output_options out;
    td_case *base = NULL;
    init_options(&o, w, &job);
    memset(&b, 0, sizeof b);
    memset(&go, 0, sizeof go);
    b.job = &job;
    if (td_sweep_grid_create(&o.grid, NULL) != TD_OK) {
        td_cli_error("sweep", "out of memory");
        go.code = TD_EXIT_FAILED;
    } else {
        double t0 = td_cli_now();
        job.grid = o.grid;
        go.code = prepare(argc, argv, &o, &job, &base, &out, &b, &go);
        b.check_time = td_cli_now() - t0;
    }
    sweep_mpi_go(w, &go);
    if (!go.code)
        go.code = run_sweep(&o, base, &b, &out, w, &go);
    free(b.rows);
    td_case_free(&base);
    td_sweep_grid_free(&o.grid);
    return go.code < 0 ? TD_EXIT_OK : go.code;
}

/* Point fd at /dev/null; returns a copy of what it was (-1 if none could be made). */
static int silence(int fd)
{
    int saved = dup(fd), null = open("/dev/null", O_WRONLY);
    if (null >= 0) {
        dup2(null, fd);
        close(null);
    }
    return saved;
}

static void unsilence(int fd, int saved)
{
    if (saved >= 0) {
        dup2(saved, fd);
        close(saved);
    }
}

/* A rank > 0's own copy of the sweep: the options and the grid, the case file's axes included,
 * and its fingerprint (0 if it could not be made). Returns 0 or an exit code (its message silent). */
static int follow_setup(int argc, char **argv, sweep_options *o, sweep_job *job, uint64_t *fp)
{
    td_case *base = NULL;
    int code = td_sweep_grid_create(&o->grid, NULL) != TD_OK ? TD_EXIT_FAILED : parse_options(argc, argv, o);
    if (!code)
        code = td_cli_load_case(o->case_path, &o->sets, &base);
    if (!code)
        code = add_case_axes(o->grid, base);
    *fp = code ? 0 : sweep_fingerprint(base, o->grid);
    td_case_free(&base);
    job->grid = o->grid;
    job->case_path = o->case_path;
    job->point_dir = o->point_dir;
    job->point_csv = o->point_csv;
    job->point_timeout = o->point_timeout;
    return code;
}

/* A rank > 0 of an MPI run: the same options, silent (rank 0 reports for the whole sweep), then
 * the points rank 0 hands out, recorded in this rank's part. A rank whose sweep is not rank 0's
 * (a case file that differs on its node) runs none: rank 0 and the others run them. */
static int sweep_follow(int argc, char **argv, const sweep_world *w)
{
    sweep_options o;
    sweep_job job;
    sweep_go go;
    sweep_journal *part = NULL;
    char path[SWEEP_PART_PATH_SIZE];
    uint64_t fp;
    int err = silence(STDERR_FILENO), out = silence(STDOUT_FILENO), code;
    if (out >= 0)
        close(out); /* stdout stays silent: only rank 0 prints results */
    init_options(&o, w, &job);
    code = follow_setup(argc, argv, &o, &job, &fp);
    sweep_mpi_go(w, &go);
    unsilence(STDERR_FILENO, err);
    if (!go.code) {
        if (!code && fp != go.fp) {
            td_cli_error("sweep", "rank %d: the case or the grid differs from rank 0's: this rank runs no point",
                         w->rank);
            code = TD_EXIT_USAGE;
        }
        sweep_part_path(path, go.journal, w->rank);
        if (code || sweep_journal_open(path, go.fp, td_sweep_grid_points(o.grid), &part))
            o.jobs = 0;
        go.code = sweep_mpi_follow(w, &job, o.jobs, &part, td_cli_catch_signals());
    }
    td_sweep_grid_free(&o.grid);
    return go.code < 0 ? TD_EXIT_OK : go.code;
}

int td_cmd_sweep(int argc, char **argv)
{
    sweep_world w;
    int code = sweep_mpi_init(&w);
    if (code)
        return code;
    code = w.rank > 0 ? sweep_follow(argc, argv, &w) : sweep_lead(argc, argv, &w);
    return sweep_mpi_finalize(&w, code);
}
