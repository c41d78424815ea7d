/* touchdown run: a case file to HDF5/CSV plus a summary. */
#include "common/cli.h"
#include "run/spread.h"
#include "touchdown/job.h"

#include <getopt.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static const char run_usage[] =
    "usage: touchdown run [OPTIONS] CASE\n"
    "\n"
    "Simulate CASE from its start state to its end_time through retainer contact, write the\n"
    "samples and the event table to HDF5 and/or CSV, and print a summary.\n"
    "\n"
    "options:\n"
    "  -s, --set KEY=VALUE  override a case key, e.g. --set speed=190 --set contact.model=\"penalty\"\n"
    "                       (repeatable; keys as in docs/case-format.md)\n"
    "  -o, --output PREFIX  write PREFIX.h5 and PREFIX.csv (default: the case's output paths, else\n"
    "                       CASENAME.h5 and CASENAME.csv in the current directory)\n"
    "      --hdf5 PATH      HDF5 output path ('' for none)\n"
    "      --csv PATH       CSV output path ('' for none); events go to PATH minus .csv plus .events.csv\n"
    "                       (paths: at most 1023 characters)\n"
    "      --compress N     HDF5 deflate level 0 (none) .. 9, with shuffle; lossless (default: the case's\n"
    "                       output.compression, else 0)\n"
    "  -q, --quiet          print no text summary (errors still go to stderr, --json still prints)\n"
    "      --json           print the summary as one JSON object on stdout, also of a failed run\n"
    "      --no-progress    no progress line (it is shown only when stderr is a terminal)\n"
    "      --spread N       then run the case N - 1 more times without files, solver.atol scaled\n"
    "                       within +-1 % (N odd, 3..21), and print the spread of each leading\n"
    "                       answer over the N runs after the summary (--json: its member \"spread\")\n"
    "  -h, --help           this help\n"
    "\n"
    "The summary leads with the peak force into the housing, the total impulse, the friction work\n"
    "and the final speed (all converge in a steady rub; in a run that bounces the peak force, the\n"
    "contacts and the time in contact are chaotic: docs/validation.md; --spread N says which of this\n"
    "run's answers settle); then how the run ended (free,\n"
    "recovered, at rest, rolling or sliding on the retainers, backward whirl or forward rub at F Hz,\n"
    "bouncing), the AMBs' peak force against their capacity and each retainer's whirl, its sustained\n"
    "and brief (touch-and-go) contacts and its share of the run in contact. It also gives\n"
    "the start state used (start = \"auto\": the steady orbit, or rest when the\n"
    "orbit is unstable or outside a clearance, and why), whether the contact-free system is\n"
    "stable, the first contact time, the number of contacts, the peak normal force (when, which\n"
    "retainer), the fraction of time in contact, whether the rotor returned to a free orbit\n"
    "(n/a without contact), the wall time and the wall time per revolution after first contact\n"
    "(the paper's figure of merit), and the files written. A run that did not reach its end has\n"
    "no answers (n/a in the text, null in the JSON, NaN in the files).\n"
    "A result that may be suspect (an AMB past its force capacity with saturation off, a schedule\n"
    "entry at or after the end time, a clearance larger than the shaft radius, a section of fewer\n"
    "than 8 crossings) gives one line \"touchdown: CASE: warning: ...\" on stderr each, also with\n"
    "-q, and the same text in the JSON (warnings) and the files (attribute warnings).\n"
    "Files are written under a temporary name, PATH.XXXXXX.partial (XXXXXX: six letters or\n"
    "digits, unique to the run), and renamed to PATH when finished; an interrupted or failed run\n"
    "keeps what it computed, marked incomplete, and a run that cannot write (full disk) leaves\n"
    "no file at PATH. Two runs on the same PATH never mix: the last to finish leaves its file.\n"
    "Refused before the run (exit 2): two outputs (HDF5, CSV, events file) that are the same\n"
    "file, an output that is the case file or one of its @include files, an output named\n"
    "*.partial, an output that exists and is not a regular file, an output directory that does\n"
    "not exist or is not writable, an --output PREFIX that names no file ('', 'dir/', '.').\n";

/* The help's second part (ISO C bounds one string literal's length). */
static const char run_usage_more[] =
    "\n"
    "With --spread N the N runs are equally accurate (the same rtol, atol within +-1 %): each answer\n"
    "is given with its least, greatest and median value over them and its spread, (greatest -\n"
    "least) / |median|; it settles when the spread is at most 2 %, the range of atol (a converged\n"
    "answer moves by less than the tolerance that moves it), else it does not. A further run that\n"
    "fails is counted, never averaged in, and leaves the exit code as it was. The spread needs a\n"
    "run that reached its end: else \"spread\" is null. N runs take about N times as long; the\n"
    "progress line counts them.\n"
    "\n"
    "exit codes: 0 complete, 1 the simulation failed or was interrupted (SIGINT/SIGTERM/SIGHUP, also\n"
    "during the set-up or the spread's runs), 2 bad input or usage (an unusable start state included,\n"
    "and a plug-in controller that crashes in its init, refuses to start or fails during the run:\n"
    "one line naming the case file, line and key, docs/case-format.md \"controllers\").\n";

static void print_usage(FILE *f)
{
    fputs(run_usage, f);
    fputs(run_usage_more, f);
}

/* Progress line state: shown once a run has taken about a second, refreshed a few times a second. */
typedef struct progress {
    double started;
    double last_shown;
    int shown;
} progress;

static int show_progress(double t, double fraction, long contacts, void *user)
{
    progress *p = user;
    double now = td_cli_now(), elapsed = now - p->started;
    if (elapsed < 1.0 || now - p->last_shown < 0.25)
        return 0;
    p->last_shown = now;
    p->shown = 1;
    fprintf(stderr, "\r  t = %.4f s  %5.1f %%  contacts %ld  ETA %.0f s   ", t, 100.0 * fraction, contacts,
            fraction > 0.0 ? elapsed * (1.0 - fraction) / fraction : 0.0);
    fflush(stderr);
    return 0;
}

/* dst = stem + ext; a path too long for td_output_options is an error (exit 2), never cut short. */
static int set_path(char *dst, const char *stem, const char *ext, const char *from)
{
    return td_cli_path(dst, TD_OUTPUT_PATH_SIZE, stem, ext, "run", from);
}

/* Output paths: command line first, then the case, then CASENAME.h5/.csv. Returns 0 or an exit code. */
static int choose_outputs(td_output_options *out, const td_case *c, const char *prefix, const char *hdf5,
                          const char *csv)
{
    int code = 0;
    if (prefix) {
        if (!(code = td_cli_prefix(prefix, "run")) && !(code = set_path(out->hdf5_path, prefix, ".h5", "--output")))
            code = set_path(out->csv_path, prefix, ".csv", "--output");
    } else if (!out->hdf5_path[0] && !out->csv_path[0]) {
        if (!(code = set_path(out->hdf5_path, td_case_name(c), ".h5", td_case_path(c))))
            code = set_path(out->csv_path, td_case_name(c), ".csv", td_case_path(c));
    }
    if (!code && hdf5)
        code = set_path(out->hdf5_path, hdf5, "", "--hdf5");
    if (!code && csv)
        code = set_path(out->csv_path, csv, "", "--csv");
    return code;
}

/* Refuse, before the run, outputs that collide with each other or with the case's files, or that
 * cannot be written (td_job_check_outputs). Returns 0 or an exit code. */
static int check_outputs(const td_job *job)
{
    td_error err;
    td_status st;
    td_error_clear(&err);
    st = td_job_check_outputs(job, &err);
    if (st == TD_OK)
        return 0;
    fprintf(stderr, "touchdown: %s\n", err.message[0] ? err.message : td_strerror(st));
    return td_cli_exit_code(st);
}

/* --compress N: one digit 0..9 (a deflate level). */
static int parse_level(const char *text, int *level)
{
    if (text[0] < '0' || text[0] > '9' || text[1] != '\0') {
        td_cli_error("run", "--compress: expected a deflate level 0..9, got '%s'", text);
        return 1;
    }
    *level = text[0] - '0';
    return 0;
}

/* One of the library's writers of a summary, `spread` NULL or not (the text's spread follows it). */
static int write_summary(char *buf, size_t n, const td_run_summary *s, int json, int with_spread,
                         const td_spread *spread)
{
    if (json)
        return with_spread ? td_run_summary_json_spread(buf, n, s, spread) : td_run_summary_json(buf, n, s);
    if (!with_spread)
        return td_run_summary_format(buf, n, s);
    {
        int k = td_run_summary_format(buf, n, s);
        size_t used = (size_t)k < n ? (size_t)k : n;
        return k + td_spread_format(buf ? buf + used : NULL, n - used, spread);
    }
}

/* The summary, text or JSON; with --spread its spread too (NULL: not measured). */
static void print_summary(const td_run_summary *s, int json, int with_spread, const td_spread *spread)
{
    int n = write_summary(NULL, 0, s, json, with_spread, spread);
    char *buf = malloc((size_t)n + 1);
    if (!buf)
        return;
    write_summary(buf, (size_t)n + 1, s, json, with_spread, spread);
    fputs(buf, stdout);
    if (n > 0 && buf[n - 1] != '\n')
        fputc('\n', stdout);
    free(buf);
}

/* Each warning of the run, one line on stderr (also with -q: like the errors). */
static void print_warnings(const char *path, const td_run_summary *s)
{
    int i;
    for (i = 0; i < s->warning_count; i++)
        fprintf(stderr, "touchdown: %s: warning: %s\n", path, s->warnings[i]);
}

/* What the command line asks of the run. */
typedef struct run_args {
    td_cli_sets sets;
    const char *prefix, *hdf5, *csv, *case_path;
    int quiet, json, want_progress, compress;
    int spread; /* --spread N: runs in the ensemble, 0: none */
} run_args;

/* Parse the command line into a; -1 to go on, else the exit code (--help, a usage error). */
static int parse_args(int argc, char **argv, run_args *a)
{
    enum { OPT_HDF5 = 256, OPT_CSV, OPT_JSON, OPT_NO_PROGRESS, OPT_COMPRESS, OPT_SPREAD };
    static const struct option longopts[] = {{"set", required_argument, NULL, 's'},
                                             {"output", required_argument, NULL, 'o'},
                                             {"hdf5", required_argument, NULL, OPT_HDF5},
                                             {"csv", required_argument, NULL, OPT_CSV},
                                             {"compress", required_argument, NULL, OPT_COMPRESS},
                                             {"quiet", no_argument, NULL, 'q'},
                                             {"json", no_argument, NULL, OPT_JSON},
                                             {"no-progress", no_argument, NULL, OPT_NO_PROGRESS},
                                             {"spread", required_argument, NULL, OPT_SPREAD},
                                             {"help", no_argument, NULL, 'h'},
                                             {NULL, 0, NULL, 0}};
    int opt;
    memset(a, 0, sizeof *a);
    a->want_progress = 1;
    a->compress = -1;
    optind = 1;
    while ((opt = getopt_long(argc, argv, "s:o:qh", longopts, NULL)) != -1) {
        switch (opt) {
        case 's':
            if (td_cli_add_set(&a->sets, optarg))
                return TD_EXIT_USAGE;
            break;
        case 'o': a->prefix = optarg; break;
        case OPT_HDF5: a->hdf5 = optarg; break;
        case OPT_CSV: a->csv = optarg; break;
        case OPT_COMPRESS:
            if (parse_level(optarg, &a->compress))
                return TD_EXIT_USAGE;
            break;
        case 'q': a->quiet = 1; break;
        case OPT_JSON: a->json = 1; break;
        case OPT_NO_PROGRESS: a->want_progress = 0; break;
        case OPT_SPREAD:
            if (td_run_spread_parse(optarg, &a->spread))
                return TD_EXIT_USAGE;
            break;
        case 'h': print_usage(stdout); return TD_EXIT_OK;
        default: print_usage(stderr); return TD_EXIT_USAGE;
        }
    }
    if (optind != argc - 1) {
        td_cli_error("run", "expected exactly one case file (see touchdown run --help)");
        return TD_EXIT_USAGE;
    }
    a->case_path = argv[optind];
    return -1;
}

/* The job's outputs from the command line, checked before the run. Returns 0 or an exit code. */
static int set_outputs(td_job *job, const run_args *a)
{
    td_job_settings s = *td_job_settings_get(job);
    int code;
    if ((code = choose_outputs(&s.out, td_job_case(job), a->prefix, a->hdf5, a->csv)))
        return code;
    if (a->compress >= 0)
        s.out.compression = a->compress;
    td_job_set(job, &s, NULL); /* cannot fail: the job has not started */
    return check_outputs(job);
}

/* Where a failure of the run is: a plug-in controller's case key when the error is about one (its
 * failure mid-run is bad input, docs/case-format.md "Plug-ins"), else the case file. */
static const char *fault_where(const td_job *job, const td_error *err)
{
    const td_case *c = td_job_case(job);
    td_case_controller_info info;
    if (err->site.part && strcmp(err->site.part, "controller") == 0 &&
        td_case_controller(c, err->site.index, &info) == TD_OK && info.plugin && info.where)
        return info.where;
    return td_case_path(c);
}

/* Start and run the job, with the progress line when asked for and stderr is a terminal; print
 * what went wrong, the warnings and the summary. Returns the exit code. */
static int run_job(td_job *job, const run_args *a, volatile sig_atomic_t *cancel)
{
    const char *path = td_case_path(td_job_case(job));
    progress prog = {0.0, 0.0, 0};
    td_run_hooks hooks;
    td_run_summary summary;
    td_spread spread;
    td_error err;
    td_status st;
    int code, show = a->want_progress && !a->quiet && isatty(STDERR_FILENO);
    memset(&hooks, 0, sizeof hooks);
    spread.members = 0;
    td_error_clear(&err);
    /* the set-up first, reading the flag: its dense start solve may be long */
    st = td_job_start(job, cancel, NULL);
    prog.started = td_cli_now();
    if (st == TD_OK && show) {
        hooks.progress = show_progress;
        hooks.user = &prog;
    }
    hooks.cancel = cancel;
    st = td_job_run(job, &hooks, &summary, &err); /* a failed set-up: its status, the failed summary */
    if (prog.shown)
        fputs("\r\033[K", stderr);
    if (st != TD_OK)
        fprintf(stderr, "touchdown: %s: %s\n", fault_where(job, &err), err.message[0] ? err.message : td_strerror(st));
    print_warnings(path, &summary);
    code = td_cli_exit_code(st);
    /* the spread of a run that reached its end: its other members, after its own files */
    if (st == TD_OK && a->spread)
        code = td_run_spread(job, &summary, a->spread, show, cancel, &spread);
    /* JSON whenever asked (scripts read it, also of a failed run); -q silences only the text */
    if (a->json || (!a->quiet && summary.t_reached > summary.t_start))
        print_summary(&summary, a->json, a->spread > 0, spread.members > 0 ? &spread : NULL);
    return code;
}

int td_cmd_run(int argc, char **argv)
{
    run_args a;
    td_job *job = NULL;
    int code = parse_args(argc, argv, &a);
    if (code >= 0)
        return code;
    if ((code = td_cli_job_create(a.case_path, &a.sets, &job)))
        return code;
    if (!(code = set_outputs(job, &a)))
        /* catch signals before the set-up: a signal must not kill its long start solve */
        code = run_job(job, &a, td_cli_catch_signals());
    td_job_free(&job);
    return code;
}
