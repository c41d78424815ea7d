/* touchdown sweep: run a case over a grid of key values in parallel, one summary row per point. */
#include "cli.h"
#include "sweep_pool.h"
#include "touchdown/json.h"
#include "touchdown/sweep.h"

#include <getopt.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
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
    "  -j, --jobs N         worker processes, 1..256 (default: the number of online CPUs)\n"
    "  -o, --output PREFIX  write PREFIX.csv and PREFIX.h5 (default: CASENAME-sweep)\n"
    "  -q, --quiet          print no text summary (errors still go to stderr)\n"
    "      --json           print the sweep's counts and files as one JSON object on stdout\n"
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
    "\n"
    "exit codes: 0 every point ran to its end, 1 some point failed, the sweep was interrupted or\n"
    "the table could not be written, 2 bad input or usage (any point's case included).\n";

typedef struct sweep_options {
    td_cli_sets sets;
    td_sweep_grid *grid;
    const char *prefix;
    const char *case_path;
    const char *point_dir;
    int jobs, json, quiet, point_csv;
} sweep_options;

static double wall_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
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
    enum { OPT_JSON = 256, OPT_POINT_FILES, OPT_POINT_CSV };
    static const struct option longopts[] = {{"vary", required_argument, NULL, 'v'},
                                             {"with", required_argument, NULL, 'w'},
                                             {"set", required_argument, NULL, 's'},
                                             {"jobs", required_argument, NULL, 'j'},
                                             {"output", required_argument, NULL, 'o'},
                                             {"point-files", required_argument, NULL, OPT_POINT_FILES},
                                             {"point-csv", no_argument, NULL, OPT_POINT_CSV},
                                             {"quiet", no_argument, NULL, 'q'},
                                             {"json", no_argument, NULL, OPT_JSON},
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
        case 's': code = td_cli_add_set(&o->sets, optarg); break;
        case 'j': code = parse_jobs(optarg, &o->jobs); break;
        case 'o': o->prefix = optarg; break;
        case 'q': o->quiet = 1; break;
        case OPT_JSON: o->json = 1; break;
        case 'h': fputs(sweep_usage, stdout); return -1;
        default: fputs(sweep_usage, stderr); return TD_EXIT_USAGE;
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

/* The points' result files, checked by the rules of touchdown run before anything runs: the last
 * point's names (every name is as long) fit, and its files overwrite no input, the directory
 * exists and is writable. */
static int check_point_files(const sweep_options *o, const td_case *c)
{
    td_output_options out;
    const char *const *files;
    long last = td_sweep_grid_points(o->grid) - 1;
    int n = 0;
    td_error err;
    if (!o->point_dir)
        return 0;
    memset(&out, 0, sizeof out);
    if (snprintf(out.hdf5_path, sizeof out.hdf5_path, SWEEP_POINT_FILE, o->point_dir, last, ".h5") >=
            (int)sizeof out.hdf5_path ||
        snprintf(out.csv_path, sizeof out.csv_path, SWEEP_POINT_FILE, o->point_dir, last, ".csv") >=
            (int)sizeof out.csv_path) {
        td_cli_error("sweep", "--point-files: the directory name is too long (at most %d bytes a file name)",
                     TD_OUTPUT_PATH_SIZE - 1);
        return TD_EXIT_USAGE;
    }
    if (!o->point_csv)
        out.csv_path[0] = '\0';
    files = td_case_files(c, &n);
    td_error_clear(&err);
    if (td_output_check_paths(&out, files, n, &err) != TD_OK) {
        td_cli_error("sweep", "--point-files %s: %s", o->point_dir, err.message);
        return TD_EXIT_USAGE;
    }
    return 0;
}

/* "FILE:LINE: sweep.vary[i]: " when `message` is about the value of a key swept by the case
 * file's group, so that the error leads to the line that asked for it; else "". */
static const char *file_origin(const td_sweep_grid *g, const char *message, char *origin, size_t n)
{
    char probe[TD_SWEEP_KEY_SIZE + 16];
    int k;
    for (k = 0; k < td_sweep_grid_keys(g); k++) {
        snprintf(probe, sizeof probe, "--set '%s=", td_sweep_grid_key(g, k));
        if (strstr(message, probe) && strcmp(td_sweep_grid_origin(g, k), "command line") != 0) {
            snprintf(origin, n, "%s: ", td_sweep_grid_origin(g, k));
            return origin;
        }
    }
    return "";
}

/* Load every point's case once before anything runs, so that a bad key or value is found at
 * once and not after hours of other points. Returns 0 or TD_EXIT_USAGE (with the error line). */
static int check_points(const sweep_job *job)
{
    const char *items[TD_CLI_MAX_SETS + TD_SWEEP_MAX_KEYS];
    char store[TD_SWEEP_MAX_KEYS][TD_SWEEP_KEY_SIZE + TD_SWEEP_VALUE_SIZE];
    char origin[TD_ERROR_MESSAGE_SIZE];
    long p, n = td_sweep_grid_points(job->grid);
    td_case *c = NULL;
    td_error err;
    for (p = 0; p < n; p++) {
        int k = sweep_point_overrides(job, p, items, store);
        td_error_clear(&err);
        if (td_case_load(job->case_path, items, k, &c, &err) != TD_OK) {
            fprintf(stderr, "touchdown: %s%s\n", file_origin(job->grid, err.message, origin, sizeof origin),
                    err.message);
            return TD_EXIT_USAGE;
        }
        td_case_free(&c);
    }
    return 0;
}

/* PREFIX.csv and PREFIX.h5, refused before the sweep by the rules of touchdown run, and the
 * journal PREFIX.journal (journal: TD_OUTPUT_PATH_SIZE bytes). */
static int choose_outputs(td_output_options *out, char *journal, const sweep_options *o, const td_case *c)
{
    char stem[TD_OUTPUT_PATH_SIZE];
    const char *const *files;
    int n = 0, code;
    td_error err;
    memset(out, 0, sizeof *out);
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
        fprintf(stderr, "touchdown: %s\n", err.message);
        return TD_EXIT_USAGE;
    }
    return 0;
}

/* Counts of the rows by state. */
typedef struct sweep_counts {
    long points, done, failed, not_run, resumed;
} sweep_counts;

static sweep_counts count_rows(const td_sweep_row *rows, long n)
{
    sweep_counts k = {n, 0, 0, 0, 0};
    long p;
    for (p = 0; p < n; p++) {
        k.done += rows[p].state == TD_SWEEP_DONE;
        k.failed += rows[p].state == TD_SWEEP_FAILED;
        k.not_run += rows[p].state == TD_SWEEP_NOT_RUN;
    }
    return k;
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

static void print_result(const sweep_options *o, const sweep_counts *k, const td_output_options *out, double wall,
                         int jobs)
{
    if (o->json) {
        printf("{\"library_version\":\"%s\",\"points\":%ld,\"done\":%ld,\"failed\":%ld,\"not_run\":%ld,"
               "\"resumed\":%ld,\"complete\":%s,\"jobs\":%d,\"wall_time\":%.17g",
               td_version(), k->points, k->done, k->failed, k->not_run, k->resumed, k->not_run ? "false" : "true", jobs,
               wall);
        print_json_path("csv_path", out->csv_path);
        print_json_path("hdf5_path", out->hdf5_path);
        printf("}\n");
    } else if (!o->quiet)
        printf("sweep: %ld points: %ld ran to the end, %ld failed, %ld not run (%ld resumed from the journal); "
               "%d workers, wall time %.2f s\n"
               "table: %s, %s%s\n",
               k->points, k->done, k->failed, k->not_run, k->resumed, jobs, wall, out->csv_path, out->hdf5_path,
               k->not_run ? " (incomplete)" : "");
}

/* Run the points (those the journal holds already excepted), write the table, report. */
static int run_sweep(const sweep_options *o, const td_case *base, sweep_job *job, const td_output_options *out,
                     const char *journal)
{
    long n = td_sweep_grid_points(o->grid), p, resumed = 0;
    td_sweep_row *rows = malloc((size_t)n * sizeof *rows);
    td_sweep_table t;
    sweep_counts k;
    double t0 = wall_now();
    int jobs = o->jobs > n ? (int)n : o->jobs, code;
    char reason[128];
    if (!rows) {
        td_cli_error("sweep", "out of memory for %ld rows", n);
        return TD_EXIT_FAILED;
    }
    for (p = 0; p < n; p++)
        td_sweep_row_unknown(&rows[p], TD_SWEEP_NOT_RUN, "not run", "");
    code = sweep_journal_open(journal, sweep_fingerprint(base, o->grid), n, rows, &resumed, &job->journal);
    if (code) {
        free(rows);
        return code;
    }
    sweep_pool_run(job, jobs, rows, td_cli_catch_signals());
    k = count_rows(rows, n);
    k.resumed = resumed;
    snprintf(reason, sizeof reason, "interrupted: %ld of %ld points not run", k.not_run, n);
    memset(&t, 0, sizeof t);
    t.grid = o->grid;
    t.rows = rows;
    t.case_text = td_case_text(base);
    t.sets = o->sets.items;
    t.n_sets = o->sets.count;
    t.complete = k.not_run == 0;
    t.reason = k.not_run ? reason : NULL;
    code = write_table(out, &t);
    sweep_journal_close(&job->journal, !code && !k.not_run); /* kept until a finished table is written */
    if (k.not_run)
        td_cli_error("sweep", "%s", reason);
    print_result(o, &k, out, wall_now() - t0, jobs);
    free(rows);
    return code ? code : (k.failed || k.not_run ? TD_EXIT_FAILED : TD_EXIT_OK);
}

static int default_jobs(void)
{
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    return n < 1 ? 1 : (n > TD_SWEEP_POOL_MAX ? TD_SWEEP_POOL_MAX : (int)n);
}

int td_cmd_sweep(int argc, char **argv)
{
    sweep_options o;
    sweep_job job;
    td_output_options out;
    td_case *base = NULL;
    char journal[TD_OUTPUT_PATH_SIZE];
    int code;
    memset(&o, 0, sizeof o);
    o.jobs = default_jobs();
    if (td_sweep_grid_create(&o.grid, NULL) != TD_OK) {
        td_cli_error("sweep", "out of memory");
        return TD_EXIT_FAILED;
    }
    code = parse_options(argc, argv, &o);
    if (!code)
        code = td_cli_load_case(o.case_path, &o.sets, &base);
    if (!code)
        code = add_case_axes(o.grid, base);
    job.case_path = o.case_path;
    job.sets = &o.sets;
    job.grid = o.grid;
    job.journal = NULL;
    job.point_dir = o.point_dir;
    job.point_csv = o.point_csv;
    if (!code)
        code = choose_outputs(&out, journal, &o, base);
    if (!code)
        code = check_point_files(&o, base);
    if (!code)
        code = check_points(&job);
    if (!code)
        code = run_sweep(&o, base, &job, &out, journal);
    td_case_free(&base);
    td_sweep_grid_free(&o.grid);
    return code < 0 ? TD_EXIT_OK : code;
}
