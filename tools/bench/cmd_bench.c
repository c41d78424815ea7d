/*
 * touchdown bench: time the paper's cases with the constrained and penalty models.
 *
 * Every run goes through the library's own run loop (td_run with no output files), so the
 * numbers are those of `touchdown run` minus the file writing. Comparisons between two runs are
 * ratios measured inside one bench invocation, the two sides alternating (repeat r runs the list
 * forwards when r is even, backwards when odd), and the median over the repeats is quoted: on a
 * shared machine the load changes from one minute to the next, not between two neighbouring runs.
 * Method and results: docs/performance.md.
 */
#include "common/cli.h"
#include "touchdown/dofs.h"
#include "touchdown/job.h"
#include "touchdown/json.h"
#include "touchdown/run.h"

#include <getopt.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

static const char bench_usage[] =
    "usage: touchdown bench [OPTIONS]\n"
    "\n"
    "Time the paper's cases (cases/paper-*.cfg) with the constrained and the penalty contact\n"
    "models and print, per case, the median over the repeats of: wall time, CPU time, wall time\n"
    "per revolution after the first contact, real-time factor (simulated s per wall s), solver\n"
    "steps, residual and Jacobian evaluations, linear solves, events, contact onsets, worst\n"
    "constraint drift, the first contact time (its error against the exact value for the\n"
    "rotor of case A) and the simulated time carried by the closed-form free flight; then the\n"
    "penalty/constrained wall-time ratios C/A, D/B and D10/B, each\n"
    "measured in the same invocation with the two sides alternating.\n"
    "\n"
    "cases: A  paper-a.cfg             90 rad/s, constraint\n"
    "       C  paper-c.cfg             90 rad/s, penalty Kc = 1.25e12 N/m\n"
    "       B  paper-b.cfg             190 rad/s, constraint\n"
    "       D  paper-d-kc1.25e12.cfg   190 rad/s, penalty Kc = 1.25e12 N/m\n"
    "       D10 paper-d-kc1.25e10.cfg  190 rad/s, penalty Kc = 1.25e10 N/m\n"
    "\n"
    "options:\n"
    "  -n, --repeats N      repeats of every run (default 3; 1 with --quick)\n"
    "  -c, --cases LIST     comma-separated case keys (default A,C,B,D,D10)\n"
    "      --quick          short runs from t = 0.09 s to 0.15 s (first contact and ~45 ms of\n"
    "                       contact): a smoke test that takes seconds\n"
    "      --scaling        instead: case A refined to 13, 49, 97 and 193 nodes (same axial\n"
    "                       positions of discs, AMBs, retainers), KLU against the dense solver\n"
    "  -s, --set KEY=VALUE  override a key of every case (e.g. --set solver.rtol=1e-8)\n"
    "  -d, --dir DIR        directory of the case files (default: ./cases, then the cases beside\n"
    "                       the tool: the source tree's from a build directory, those in\n"
    "                       PREFIX/share/touchdown/cases when installed)\n"
    "      --json           print the results as one JSON object instead of the tables\n"
    "  -o, --output FILE    also write the JSON object to FILE\n"
    "  -h, --help           this help\n"
    "\n"
    "exit codes: 0 every run complete, 1 a run failed or was interrupted (SIGINT/SIGTERM/SIGHUP: no\n"
    "JSON file is written), 2 bad usage or missing case files.\n";

/* The benchmark's cases: key, file, contact model, the constrained case a penalty one is compared with. */
typedef struct bench_case {
    const char *key, *file, *model, *pair;
} bench_case;

static const bench_case bench_cases[] = {
    {"A", "paper-a.cfg", "constraint", NULL},
    {"C", "paper-c.cfg", "penalty 1.25e12", "A"},
    {"B", "paper-b.cfg", "constraint", NULL},
    {"D", "paper-d-kc1.25e12.cfg", "penalty 1.25e12", "B"},
    {"D10", "paper-d-kc1.25e10.cfg", "penalty 1.25e10", "B"},
};
#define N_CASES ((int)(sizeof bench_cases / sizeof bench_cases[0]))
#define MAX_REPEATS 99

/* The exact first contact of case A's rotor (shared by case C up to that instant), computed in
 * tests/validation/test_first_contact.c from the matrix exponential of the contact-free system. */
#define CASE_A_FIRST_CONTACT 0.105443450996315

/* --quick: the window of every run */
#define QUICK_T0 0.09
#define QUICK_T1 0.15

typedef struct bench_run {
    int ok;
    double cpu;         /* s of process CPU time inside td_run */
    td_run_summary sum; /* td_run's summary: wall times, revolutions, statistics */
} bench_run;

typedef struct bench_options {
    int repeats, quick, json, scaling;
    int selected[N_CASES];
    const char *dir;
    const char *output; /* also write the JSON here */
    td_cli_sets sets;
    volatile sig_atomic_t *cancel; /* set by SIGINT, SIGTERM, SIGHUP */
} bench_options;

/* ---- small utilities --------------------------------------------------------------------- */

static double cpu_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : (x > y ? 1 : 0);
}

/* Median of the defined values among n (copied); undefined when none is (touchdown/dofs.h). */
static double median(const double *v, int n)
{
    double tmp[MAX_REPEATS];
    int i, k = 0;
    for (i = 0; i < n; i++)
        if (!td_is_undefined(v[i]))
            tmp[k++] = v[i];
    if (k == 0)
        return TD_UNDEFINED;
    qsort(tmp, (size_t)k, sizeof(double), cmp_double);
    return k % 2 ? tmp[k / 2] : 0.5 * (tmp[k / 2 - 1] + tmp[k / 2]);
}

static int file_exists(const char *path)
{
    FILE *f = fopen(path, "r");
    if (f)
        fclose(f);
    return f != NULL;
}

/* The CPU model (first "model name" of /proc/cpuinfo) into buf; "unknown" when unavailable. */
static void cpu_model(char *buf, size_t n)
{
    char line[512];
    FILE *f = fopen("/proc/cpuinfo", "r");
    snprintf(buf, n, "unknown");
    if (!f)
        return;
    while (fgets(line, sizeof line, f)) {
        char *colon = strchr(line, ':');
        if (strncmp(line, "model name", 10) == 0 && colon) {
            size_t len;
            colon++;
            while (*colon == ' ' || *colon == '\t')
                colon++;
            len = strcspn(colon, "\n");
            snprintf(buf, n, "%.*s", (int)len, colon);
            break;
        }
    }
    fclose(f);
}

/* One-minute load average, -1 when unavailable. */
static double load_average(void)
{
    double l = -1.0;
    FILE *f = fopen("/proc/loadavg", "r");
    if (f) {
        if (fscanf(f, "%lf", &l) != 1)
            l = -1.0;
        fclose(f);
    }
    return l;
}

/* Where the install puts the cases, relative to the installed tool (CMakeLists.txt). */
#ifndef TD_CASES_FROM_BIN
#define TD_CASES_FROM_BIN "../share/touchdown/cases"
#endif

/* The directory holding paper-a.cfg: dir if given, ./cases, or cases/ beside the tool
 * (build tree: BUILD/touchdown -> BUILD/../cases; install: PREFIX/bin -> PREFIX/share/touchdown/cases).
 * 1 found, 0 not found, -1 --dir too long (said on stderr). */
static int find_case_dir(const char *dir, char *out, size_t n)
{
    char probe[TD_OUTPUT_PATH_SIZE + 32], exe[TD_OUTPUT_PATH_SIZE];
    const char *tries[3] = {"../cases", "../../cases", TD_CASES_FROM_BIN};
    ssize_t len;
    int i;
    if (dir) {
        if (td_cli_path(out, n, dir, "", "bench", "--dir") ||
            td_cli_path(probe, sizeof probe, dir, "/paper-a.cfg", "bench", "--dir"))
            return -1;
        return file_exists(probe);
    }
    snprintf(out, n, "cases"); /* fits: n is TD_OUTPUT_PATH_SIZE */
    if (file_exists("cases/paper-a.cfg"))
        return 1;
    len = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (len <= 0)
        return 0;
    exe[len] = '\0';
    if (strrchr(exe, '/'))
        *strrchr(exe, '/') = '\0';
    for (i = 0; i < 3; i++) {
        /* a candidate too long for the buffers cannot be used: skipped, never shortened */
        if (snprintf(out, n, "%s/%s", exe, tries[i]) >= (int)n ||
            snprintf(probe, sizeof probe, "%s/paper-a.cfg", out) >= (int)sizeof probe)
            continue;
        if (file_exists(probe))
            return 1;
    }
    return 0;
}

/* ---- one run ----------------------------------------------------------------------------- */

/* Run `job` with no files (touchdown/job.h), its CPU time taken over the run alone (not the set-up). */
static int run_job(volatile sig_atomic_t *cancel, td_job *job, bench_run *r, char *msg, size_t nmsg)
{
    td_job_settings set = *td_job_settings_get(job);
    td_run_hooks hooks;
    td_error err;
    td_status st;
    double c0;
    memset(r, 0, sizeof *r);
    set.out.hdf5_path[0] = set.out.csv_path[0] = '\0';
    td_job_set(job, &set, NULL); /* cannot fail: the job has not started */
    td_error_clear(&err);
    memset(&hooks, 0, sizeof hooks);
    hooks.cancel = cancel;
    st = td_job_start(job, cancel, &err);
    if (st != TD_OK) {
        snprintf(msg, nmsg, "%s", err.message[0] ? err.message : td_strerror(st));
        return 0;
    }
    c0 = cpu_now();
    st = td_job_run(job, &hooks, &r->sum, &err);
    r->cpu = cpu_now() - c0;
    if (st != TD_OK) {
        snprintf(msg, nmsg, "%s", err.message[0] ? err.message : td_strerror(st));
        return 0;
    }
    r->ok = 1;
    return 1;
}

/* Run `model` with `opt` from opt->t0 to t_end, no files (the case's sampling). */
static int run_model(volatile sig_atomic_t *cancel, const td_model *model, const td_sim_options *opt,
                     const td_output_options *case_out, double t_end, bench_run *r, char *msg, size_t nmsg)
{
    td_job_settings set;
    td_job *job = NULL;
    td_error err;
    int ok;
    set.sim = *opt;
    set.out = *case_out;
    set.t_end = t_end;
    if (td_job_create_model(model, &set, NULL, &job, &err) != TD_OK) {
        memset(r, 0, sizeof *r);
        snprintf(msg, nmsg, "%s", err.message);
        return 0;
    }
    ok = run_job(cancel, job, r, msg, nmsg);
    td_job_free(&job);
    return ok;
}

static int run_case(const bench_options *bo, const char *dir, int ci, bench_run *r)
{
    char path[TD_OUTPUT_PATH_SIZE + 64], msg[TD_ERROR_MESSAGE_SIZE];
    td_job *job = NULL;
    td_job_settings set;
    int ok;
    if (td_cli_path(path, sizeof path, dir, "/", "bench", "--dir") ||
        td_cli_path(path + strlen(path), sizeof path - strlen(path), bench_cases[ci].file, "", "bench", "--dir") ||
        td_cli_job_create(path, &bo->sets, &job))
        return 0;
    set = *td_job_settings_get(job);
    if (bo->quick) {
        set.sim.t0 = QUICK_T0;
        set.t_end = QUICK_T1;
    }
    td_job_set(job, &set, NULL); /* cannot fail: the job has not started */
    ok = run_job(bo->cancel, job, r, msg, sizeof msg);
    if (!ok)
        td_cli_error("bench", "case %s (%s): %s", bench_cases[ci].key, path, msg);
    td_job_free(&job);
    return ok;
}

/* ---- the paper's cases ------------------------------------------------------------------- */

typedef struct case_summary {
    double wall, cpu, rev, rtf; /* medians */
    const bench_run *first;     /* counts (the same in every repeat: the runs are deterministic) */
    int deterministic;
} case_summary;

static void summarise(bench_run runs[][MAX_REPEATS], int ci, int repeats, case_summary *cs)
{
    double w[MAX_REPEATS], c[MAX_REPEATS], v[MAX_REPEATS], f[MAX_REPEATS];
    int r;
    cs->deterministic = 1;
    for (r = 0; r < repeats; r++) {
        const td_run_summary *s = &runs[ci][r].sum;
        w[r] = s->wall_time;
        c[r] = runs[ci][r].cpu;
        v[r] = s->wall_time_per_revolution;
        f[r] = s->realtime_factor;
        if (s->stats.steps != runs[ci][0].sum.stats.steps || s->events != runs[ci][0].sum.events)
            cs->deterministic = 0;
    }
    cs->wall = median(w, repeats);
    cs->cpu = median(c, repeats);
    cs->rev = median(v, repeats);
    cs->rtf = median(f, repeats);
    cs->first = &runs[ci][0];
}

static int case_index(const char *key)
{
    int i;
    for (i = 0; i < N_CASES; i++)
        if (!strcmp(bench_cases[i].key, key))
            return i;
    return -1;
}

/* First contact error against the exact value, for the rotor of case A (A and C); undefined otherwise. */
static double first_contact_error(int ci, const td_run_summary *s)
{
    const char *k = bench_cases[ci].key;
    if ((strcmp(k, "A") && strcmp(k, "C")) || td_is_undefined(s->first_contact_time))
        return TD_UNDEFINED;
    return s->first_contact_time - CASE_A_FIRST_CONTACT;
}

static void print_machine_json(FILE *f, int nproc, const char *cpu, double l0, double l1)
{
    fprintf(f, "\"machine\":{\"nproc\":%d,\"cpu\":", nproc);
    td_cli_json_string(f, cpu);
    fprintf(f, ",\"loadavg_start\":%.2f,\"loadavg_end\":%.2f}", l0, l1);
}

static void json_number(FILE *f, const char *name, double v, int comma)
{
    if (isfinite(v))
        fprintf(f, "\"%s\":%.9g%s", name, v, comma ? "," : "");
    else
        fprintf(f, "\"%s\":null%s", name, comma ? "," : "");
}

static void print_run_json(FILE *f, int ci, int rep, const bench_run *r)
{
    const td_run_summary *s = &r->sum;
    fprintf(f, "{\"case\":");
    td_cli_json_string(f, bench_cases[ci].key);
    fprintf(f, ",\"file\":");
    td_cli_json_string(f, bench_cases[ci].file);
    fprintf(f, ",\"model\":");
    td_cli_json_string(f, bench_cases[ci].model);
    fprintf(f, ",\"repeat\":%d,", rep);
    json_number(f, "t_start", s->t_start, 1);
    json_number(f, "t_end", s->t_reached, 1);
    json_number(f, "wall_time", s->wall_time, 1);
    json_number(f, "solver_wall_time", s->solver_wall_time, 1);
    json_number(f, "cpu_time", r->cpu, 1);
    json_number(f, "wall_time_per_revolution", s->wall_time_per_revolution, 1); /* null when undefined */
    json_number(f, "realtime_factor", s->realtime_factor, 1);
    fprintf(f,
            "\"steps\":%ld,\"residual_evals\":%ld,\"jacobian_evals\":%ld,\"linear_setups\":%ld,"
            "\"linear_solves\":%ld,\"error_test_fails\":%ld,\"nonlinear_fails\":%ld,\"events\":%ld,"
            "\"contact_onsets\":%ld,",
            s->stats.steps, s->stats.residual_evals, s->stats.jacobian_evals, s->stats.linear_setups,
            s->stats.nonlinear_iters, s->stats.error_test_fails, s->stats.nonlinear_fails, s->events, s->contacts);
    json_number(f, "worst_drift", s->stats.worst_drift, 1);
    json_number(f, "first_contact_time", s->first_contact_time, 1);
    json_number(f, "first_contact_error", first_contact_error(ci, s), 1);
    json_number(f, "peak_normal_force", s->peak_normal_force, 1);
    json_number(f, "flight_time", s->stats.flight_time, 1);
    json_number(f, "contact_fraction", s->contact_fraction, 0);
    fprintf(f, "}");
}

static void print_table(const case_summary *cs, const int *sel, int repeats)
{
    int ci;
    printf("median of %d repeat%s (wall and CPU in s; counts are per run)\n", repeats, repeats > 1 ? "s" : "");
    printf("%-4s %-16s %8s %8s %9s %8s %9s %9s %7s %8s %7s %7s %9s %10s %8s\n", "case", "model", "wall", "cpu",
           "wall/rev", "RTF", "steps", "residual", "Jac", "solves", "events", "onsets", "drift m", "1st ct err",
           "flight s");
    for (ci = 0; ci < N_CASES; ci++) {
        const td_run_summary *s;
        double fe;
        char fes[32], drift[32];
        if (!sel[ci])
            continue;
        s = &cs[ci].first->sum;
        fe = first_contact_error(ci, s);
        if (isfinite(fe))
            snprintf(fes, sizeof fes, "%+.2e", fe);
        else
            snprintf(fes, sizeof fes, "-");
        if (bench_cases[ci].pair) /* penalty: no constraint to drift from */
            snprintf(drift, sizeof drift, "-");
        else
            snprintf(drift, sizeof drift, "%.2e", s->stats.worst_drift);
        printf("%-4s %-16s %8.3f %8.3f %9.4f %8.3f %9ld %9ld %7ld %8ld %7ld %7ld %9s %10s %8.4f%s\n",
               bench_cases[ci].key, bench_cases[ci].model, cs[ci].wall, cs[ci].cpu, cs[ci].rev, cs[ci].rtf,
               s->stats.steps, s->stats.residual_evals, s->stats.jacobian_evals, s->stats.nonlinear_iters, s->events,
               s->contacts, drift, fes, s->stats.flight_time,
               cs[ci].deterministic ? "" : "  (counts differ between repeats)");
    }
}

/* Wall-time (and CPU-time) ratios of penalty case ci to its constrained pair pi, per repeat. */
static void ratios(bench_run runs[][MAX_REPEATS], int ci, int pi, int repeats, double *q, double *qc)
{
    int r;
    for (r = 0; r < repeats; r++) {
        q[r] = runs[ci][r].sum.wall_time / runs[pi][r].sum.wall_time;
        qc[r] = runs[ci][r].cpu / runs[pi][r].cpu;
    }
}

static int pair_of(const bench_options *bo, int ci)
{
    int pi = bench_cases[ci].pair ? case_index(bench_cases[ci].pair) : -1;
    return pi >= 0 && bo->selected[ci] && bo->selected[pi] ? pi : -1;
}

typedef struct machine {
    int nproc;
    char cpu[256];
    double load0, load1;
} machine;

static void paper_json(FILE *f, const bench_options *bo, const machine *mc, bench_run runs[][MAX_REPEATS],
                       const case_summary *cs)
{
    int ci, r, i, first = 1;
    fprintf(f, "{");
    print_machine_json(f, mc->nproc, mc->cpu, mc->load0, mc->load1);
    fprintf(f, ",\"quick\":%s,\"repeats\":%d,\"sets\":[", bo->quick ? "true" : "false", bo->repeats);
    for (i = 0; i < bo->sets.count; i++) {
        fprintf(f, "%s", i ? "," : "");
        td_cli_json_string(f, bo->sets.items[i]);
    }
    fprintf(f, "],\"runs\":[");
    for (ci = 0; ci < N_CASES; ci++)
        for (r = 0; r < bo->repeats && bo->selected[ci]; r++) {
            fprintf(f, "%s", first ? "" : ",");
            first = 0;
            print_run_json(f, ci, r, &runs[ci][r]);
        }
    fprintf(f, "],\"medians\":[");
    first = 1;
    for (ci = 0; ci < N_CASES; ci++) {
        if (!bo->selected[ci])
            continue;
        fprintf(f, "%s{\"case\":", first ? "" : ",");
        td_cli_json_string(f, bench_cases[ci].key);
        fprintf(f, ",");
        json_number(f, "wall_time", cs[ci].wall, 1);
        json_number(f, "cpu_time", cs[ci].cpu, 1);
        json_number(f, "wall_time_per_revolution", cs[ci].rev, 1);
        json_number(f, "realtime_factor", cs[ci].rtf, 1);
        fprintf(f, "\"deterministic\":%s}", cs[ci].deterministic ? "true" : "false");
        first = 0;
    }
    fprintf(f, "],\"ratios\":[");
    first = 1;
    for (ci = 0; ci < N_CASES; ci++) {
        int pi = pair_of(bo, ci);
        double q[MAX_REPEATS], qc[MAX_REPEATS];
        if (pi < 0)
            continue;
        ratios(runs, ci, pi, bo->repeats, q, qc);
        fprintf(f, "%s{\"name\":\"%s/%s\",", first ? "" : ",", bench_cases[ci].key, bench_cases[pi].key);
        json_number(f, "wall_median", median(q, bo->repeats), 1);
        json_number(f, "cpu_median", median(qc, bo->repeats), 1);
        fprintf(f, "\"wall\":[");
        for (r = 0; r < bo->repeats; r++)
            fprintf(f, "%s%.6g", r ? "," : "", q[r]);
        fprintf(f, "],\"cpu\":[");
        for (r = 0; r < bo->repeats; r++)
            fprintf(f, "%s%.6g", r ? "," : "", qc[r]);
        fprintf(f, "]}");
        first = 0;
    }
    fprintf(f, "]}\n");
}

static void paper_text(const bench_options *bo, const machine *mc, bench_run runs[][MAX_REPEATS],
                       const case_summary *cs)
{
    int ci, r, i;
    printf("touchdown bench: %d CPU%s (%s), load average %.2f at the start, %.2f at the end%s\n", mc->nproc,
           mc->nproc > 1 ? "s" : "", mc->cpu, mc->load0, mc->load1, bo->quick ? "; --quick: t = 0.09 .. 0.15 s" : "");
    for (i = 0; i < bo->sets.count; i++)
        printf("  --set %s\n", bo->sets.items[i]);
    print_table(cs, bo->selected, bo->repeats);
    printf("penalty / constrained, same invocation, alternating: median [every repeat]\n");
    for (ci = 0; ci < N_CASES; ci++) {
        int pi = pair_of(bo, ci);
        double q[MAX_REPEATS], qc[MAX_REPEATS];
        if (pi < 0)
            continue;
        ratios(runs, ci, pi, bo->repeats, q, qc);
        printf("  %-5s wall %6.3f [", bench_cases[ci].key, median(q, bo->repeats));
        for (r = 0; r < bo->repeats; r++)
            printf("%s%.3f", r ? " " : "", q[r]);
        printf("]   cpu %6.3f [", median(qc, bo->repeats));
        for (r = 0; r < bo->repeats; r++)
            printf("%s%.3f", r ? " " : "", qc[r]);
        printf("]   (%s/%s)\n", bench_cases[ci].key, bench_cases[pi].key);
    }
}

static void machine_info(machine *mc)
{
    mc->nproc = (int)sysconf(_SC_NPROCESSORS_ONLN);
    cpu_model(mc->cpu, sizeof mc->cpu);
    mc->load0 = load_average();
    mc->load1 = mc->load0;
}

/* Write the JSON to bo->output as well (when given); 0 on failure. */
static int json_file(const bench_options *bo, void (*fn)(FILE *, const void *), const void *data)
{
    FILE *f;
    if (!bo->output)
        return 1;
    f = fopen(bo->output, "w");
    if (!f) {
        td_cli_error("bench", "cannot write %s", bo->output);
        return 0;
    }
    fn(f, data);
    if (fclose(f) != 0) {
        td_cli_error("bench", "cannot write %s", bo->output);
        return 0;
    }
    return 1;
}

typedef struct paper_results {
    const bench_options *bo;
    const machine *mc;
    bench_run (*runs)[MAX_REPEATS];
    const case_summary *cs;
} paper_results;

static void paper_json_cb(FILE *f, const void *data)
{
    const paper_results *p = data;
    paper_json(f, p->bo, p->mc, p->runs, p->cs);
}

static int bench_paper(const bench_options *bo, const char *dir)
{
    static bench_run runs[N_CASES][MAX_REPEATS];
    case_summary cs[N_CASES];
    machine mc;
    paper_results pr;
    int order[N_CASES], n = 0, r, i, ci, failed = 0;
    machine_info(&mc);
    for (ci = 0; ci < N_CASES; ci++)
        if (bo->selected[ci])
            order[n++] = ci;
    for (r = 0; r < bo->repeats && !failed; r++)
        for (i = 0; i < n && !failed; i++) {
            /* alternate: forwards on even repeats, backwards on odd ones */
            ci = order[r % 2 ? n - 1 - i : i];
            fprintf(stderr, "bench: repeat %d/%d, case %s ...\n", r + 1, bo->repeats, bench_cases[ci].key);
            if (!run_case(bo, dir, ci, &runs[ci][r]))
                failed = 1;
        }
    mc.load1 = load_average();
    if (failed)
        return TD_EXIT_FAILED;
    for (ci = 0; ci < N_CASES; ci++)
        if (bo->selected[ci])
            summarise(runs, ci, bo->repeats, &cs[ci]);
    if (bo->json)
        paper_json(stdout, bo, &mc, runs, cs);
    else
        paper_text(bo, &mc, runs, cs);
    pr.bo = bo;
    pr.mc = &mc;
    pr.runs = runs;
    pr.cs = cs;
    return json_file(bo, paper_json_cb, &pr) ? TD_EXIT_OK : TD_EXIT_FAILED;
}

/* ---- scaling: the rig refined ------------------------------------------------------------ */

#define SCALING_T0 0.09
#define SCALING_T_FREE 0.10 /* end of the free-flight window (the first contact is at 0.1054 s) */
#define SCALING_T_CONTACT 0.15

typedef struct scaling_row {
    int nodes, dofs;
    bench_run free_klu[MAX_REPEATS], free_dense[MAX_REPEATS], contact_klu[MAX_REPEATS];
} scaling_row;

static double med_wall(const bench_run *r, int n)
{
    double w[MAX_REPEATS];
    int i;
    for (i = 0; i < n; i++)
        w[i] = r[i].sum.wall_time;
    return median(w, n);
}

static double med_cpu(const bench_run *r, int n)
{
    double w[MAX_REPEATS];
    int i;
    for (i = 0; i < n; i++)
        w[i] = r[i].cpu;
    return median(w, n);
}

#define N_SIZES 4

typedef struct scaling_results {
    const bench_options *bo;
    const machine *mc;
    const scaling_row *rows;
} scaling_results;

static void scaling_json(FILE *f, const void *data)
{
    const scaling_results *sr = data;
    const bench_options *bo = sr->bo;
    double span_f = SCALING_T_FREE - SCALING_T0, span_c = SCALING_T_CONTACT - SCALING_T0;
    int i;
    fprintf(f, "{");
    print_machine_json(f, sr->mc->nproc, sr->mc->cpu, sr->mc->load0, sr->mc->load1);
    fprintf(f, ",\"repeats\":%d,\"t0\":%g,\"t_free\":%g,\"t_contact\":%g,\"scaling\":[", bo->repeats, SCALING_T0,
            SCALING_T_FREE, SCALING_T_CONTACT);
    for (i = 0; i < N_SIZES; i++) {
        const scaling_row *row = &sr->rows[i];
        fprintf(f, "%s{\"nodes\":%d,\"dofs\":%d,\"free_steps\":%ld,\"free_steps_dense\":%ld,", i ? "," : "", row->nodes,
                row->dofs, row->free_klu[0].sum.stats.steps, row->free_dense[0].sum.stats.steps);
        json_number(f, "free_klu_cpu_cost", med_cpu(row->free_klu, bo->repeats) / span_f, 1);
        json_number(f, "free_dense_cpu_cost", med_cpu(row->free_dense, bo->repeats) / span_f, 1);
        json_number(f, "free_klu_wall_cost", med_wall(row->free_klu, bo->repeats) / span_f, 1);
        json_number(f, "free_dense_wall_cost", med_wall(row->free_dense, bo->repeats) / span_f, 1);
        fprintf(f, "\"contact_steps\":%ld,\"contact_events\":%ld,\"contact_onsets\":%ld,",
                row->contact_klu[0].sum.stats.steps, row->contact_klu[0].sum.events, row->contact_klu[0].sum.contacts);
        json_number(f, "contact_klu_cpu_cost", med_cpu(row->contact_klu, bo->repeats) / span_c, 1);
        json_number(f, "contact_klu_wall_cost", med_wall(row->contact_klu, bo->repeats) / span_c, 0);
        fprintf(f, "}");
    }
    fprintf(f, "]}\n");
}

static void scaling_text(const scaling_results *sr)
{
    const bench_options *bo = sr->bo;
    double span_f = SCALING_T_FREE - SCALING_T0, span_c = SCALING_T_CONTACT - SCALING_T0;
    int i;
    printf("touchdown bench --scaling: case A refined, %d CPU%s (%s), load average %.2f .. %.2f\n", sr->mc->nproc,
           sr->mc->nproc > 1 ? "s" : "", sr->mc->cpu, sr->mc->load0, sr->mc->load1);
    printf("free flight t = %.2f .. %.2f s (KLU and dense); through the first contact to %.2f s (KLU).\n", SCALING_T0,
           SCALING_T_FREE, SCALING_T_CONTACT);
    printf("cost = CPU s per simulated s, median of %d repeat%s (CPU time: the machine's load disturbs it\n"
           "less than wall time); us/step = CPU microseconds per solver step\n",
           bo->repeats, bo->repeats > 1 ? "s" : "");
    printf("%6s %6s | %6s %9s %9s %9s %9s %8s | %7s %7s %9s %9s\n", "nodes", "DOFs", "steps", "KLU", "dense", "us/step",
           "us/step", "dense/", "steps", "onsets", "KLU", "us/step");
    printf("%6s %6s | %6s %9s %9s %9s %9s %8s | %7s %7s %9s %9s\n", "", "", "free", "cost", "cost", "KLU", "dense",
           "KLU", "contact", "", "cost", "KLU");
    for (i = 0; i < N_SIZES; i++) {
        const scaling_row *row = &sr->rows[i];
        double ck = med_cpu(row->free_klu, bo->repeats), cd = med_cpu(row->free_dense, bo->repeats);
        double cc = med_cpu(row->contact_klu, bo->repeats);
        long sf = row->free_klu[0].sum.stats.steps, sfd = row->free_dense[0].sum.stats.steps;
        long sc = row->contact_klu[0].sum.stats.steps;
        printf("%6d %6d | %6ld %9.3f %9.3f %9.2f %9.2f %8.1f | %7ld %7ld %9.3f %9.2f\n", row->nodes, row->dofs, sf,
               ck / span_f, cd / span_f, 1e6 * ck / (double)(sf > 0 ? sf : 1), 1e6 * cd / (double)(sfd > 0 ? sfd : 1),
               cd / ck, sc, row->contact_klu[0].sum.contacts, cc / span_c, 1e6 * cc / (double)(sc > 0 ? sc : 1));
    }
}

static int bench_scaling(const bench_options *bo, const char *dir)
{
    static const int ks[N_SIZES] = {1, 4, 8, 16};
    static scaling_row rows[N_SIZES];
    char path[TD_OUTPUT_PATH_SIZE + 64], msg[TD_ERROR_MESSAGE_SIZE];
    td_case *c = NULL;
    machine mc;
    scaling_results sr;
    int i, r, ok = 1;
    machine_info(&mc);
    if (td_cli_path(path, sizeof path, dir, "/", "bench", "--dir") ||
        td_cli_path(path + strlen(path), sizeof path - strlen(path), bench_cases[0].file, "", "bench", "--dir") ||
        td_cli_load_case(path, &bo->sets, &c))
        return TD_EXIT_USAGE;
    for (i = 0; i < N_SIZES && ok; i++) {
        const td_output_options *out = td_case_output_options(c);
        td_model *m = NULL;
        td_error err;
        td_sim_options o = *td_case_sim_options(c), od;
        if (td_model_refine(td_case_model(c), ks[i], &m, &err) != TD_OK) {
            td_cli_error("bench", "refining the rig: %s", err.message);
            td_case_free(&c);
            return TD_EXIT_FAILED;
        }
        rows[i].nodes = td_model_node_count(m);
        rows[i].dofs = td_model_dof_count(m);
        o.t0 = SCALING_T0;
        o.solver.linear_solver = TD_LINSOL_KLU;
        od = o;
        od.solver.linear_solver = TD_LINSOL_DENSE;
        for (r = 0; r < bo->repeats && ok; r++) {
            fprintf(stderr, "bench: %d nodes, repeat %d/%d ...\n", rows[i].nodes, r + 1, bo->repeats);
            /* free flight, KLU and dense alternating; then through the first contact, KLU */
            if (r % 2 == 0)
                ok = run_model(bo->cancel, m, &o, out, SCALING_T_FREE, &rows[i].free_klu[r], msg, sizeof msg) &&
                     run_model(bo->cancel, m, &od, out, SCALING_T_FREE, &rows[i].free_dense[r], msg, sizeof msg);
            else
                ok = run_model(bo->cancel, m, &od, out, SCALING_T_FREE, &rows[i].free_dense[r], msg, sizeof msg) &&
                     run_model(bo->cancel, m, &o, out, SCALING_T_FREE, &rows[i].free_klu[r], msg, sizeof msg);
            ok = ok && run_model(bo->cancel, m, &o, out, SCALING_T_CONTACT, &rows[i].contact_klu[r], msg, sizeof msg);
            if (!ok)
                td_cli_error("bench", "%d nodes: %s", rows[i].nodes, msg);
        }
        td_model_free(&m);
    }
    td_case_free(&c);
    mc.load1 = load_average();
    if (!ok)
        return TD_EXIT_FAILED;
    sr.bo = bo;
    sr.mc = &mc;
    sr.rows = rows;
    if (bo->json)
        scaling_json(stdout, &sr);
    else
        scaling_text(&sr);
    return json_file(bo, scaling_json, &sr) ? TD_EXIT_OK : TD_EXIT_FAILED;
}

/* ---- options ----------------------------------------------------------------------------- */

static int parse_cases(const char *list, int *sel)
{
    char buf[256], *tok, *save = NULL;
    int i;
    for (i = 0; i < N_CASES; i++)
        sel[i] = 0;
    if (snprintf(buf, sizeof buf, "%s", list) >= (int)sizeof buf) {
        td_cli_error("bench", "--cases: the list is longer than %d characters", (int)sizeof buf - 1);
        return 0;
    }
    for (tok = strtok_r(buf, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
        int ci = case_index(tok);
        if (ci < 0) {
            td_cli_error("bench", "unknown case '%s' (known: A, C, B, D, D10)", tok);
            return 0;
        }
        sel[ci] = 1;
    }
    return 1;
}

int td_cmd_bench(int argc, char **argv)
{
    enum { OPT_QUICK = 256, OPT_JSON, OPT_SCALING };
    static const struct option longopts[] = {
        {"repeats", required_argument, NULL, 'n'}, {"cases", required_argument, NULL, 'c'},
        {"quick", no_argument, NULL, OPT_QUICK},   {"scaling", no_argument, NULL, OPT_SCALING},
        {"set", required_argument, NULL, 's'},     {"dir", required_argument, NULL, 'd'},
        {"json", no_argument, NULL, OPT_JSON},     {"output", required_argument, NULL, 'o'},
        {"help", no_argument, NULL, 'h'},          {NULL, 0, NULL, 0}};
    bench_options bo;
    char dir[TD_OUTPUT_PATH_SIZE];
    const char *cases = NULL;
    int opt, i, repeats = -1;
    memset(&bo, 0, sizeof bo);
    optind = 1;
    while ((opt = getopt_long(argc, argv, "n:c:s:d:o:h", longopts, NULL)) != -1) {
        switch (opt) {
        case 'n': {
            char *end;
            long v = strtol(optarg, &end, 10);
            if (*end || v < 1 || v > MAX_REPEATS) {
                td_cli_error("bench", "--repeats must be an integer 1..%d", MAX_REPEATS);
                return TD_EXIT_USAGE;
            }
            repeats = (int)v;
            break;
        }
        case 'c': cases = optarg; break;
        case 's':
            if (td_cli_add_set(&bo.sets, optarg))
                return TD_EXIT_USAGE;
            break;
        case 'd': bo.dir = optarg; break;
        case 'o': bo.output = optarg; break;
        case OPT_QUICK: bo.quick = 1; break;
        case OPT_SCALING: bo.scaling = 1; break;
        case OPT_JSON: bo.json = 1; break;
        case 'h': fputs(bench_usage, stdout); return TD_EXIT_OK;
        default: fputs(bench_usage, stderr); return TD_EXIT_USAGE;
        }
    }
    if (optind != argc) {
        td_cli_error("bench", "unexpected argument '%s' (see touchdown bench --help)", argv[optind]);
        return TD_EXIT_USAGE;
    }
    bo.repeats = repeats > 0 ? repeats : (bo.quick ? 1 : 3);
    if (cases) {
        if (!parse_cases(cases, bo.selected))
            return TD_EXIT_USAGE;
    } else {
        for (i = 0; i < N_CASES; i++)
            bo.selected[i] = 1;
    }
    if ((i = find_case_dir(bo.dir, dir, sizeof dir)) < 0)
        return TD_EXIT_USAGE;
    if (!i) {
        td_cli_error("bench", "cannot find paper-a.cfg in %s (give the cases directory with --dir)",
                     bo.dir ? bo.dir : "./cases or beside the tool");
        return TD_EXIT_USAGE;
    }
    bo.cancel = td_cli_catch_signals(); /* a signal ends the current run as interrupted: exit 1, no file */
    return bo.scaling ? bench_scaling(&bo, dir) : bench_paper(&bo, dir);
}
