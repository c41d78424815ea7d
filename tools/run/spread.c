/* touchdown run --spread N (tools/run/spread.h): the ensemble's other runs, with their progress line. */
#include "run/spread.h"

#include "common/cli.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int td_run_spread_parse(const char *text, int *n)
{
    char *end;
    long v = strtol(text, &end, 10);
    if (end == text || *end || v > TD_SPREAD_MAX_MEMBERS || !td_spread_members_valid((int)v)) {
        td_cli_error("run", "--spread: expected an odd number of runs from %d to %d, got '%s'", TD_SPREAD_MIN_MEMBERS,
                     TD_SPREAD_MAX_MEMBERS, text);
        return TD_EXIT_USAGE;
    }
    *n = (int)v;
    return 0;
}

/* The progress line of the ensemble: shown once it has taken about a second, refreshed a few
 * times a second, like the run's. */
typedef struct spread_progress {
    int runs; /* members run here: n - 1 */
    double started, last_shown;
    int shown;
} spread_progress;

static int show_spread_progress(double t, double fraction, long contacts, void *user)
{
    spread_progress *p = user;
    double now = td_cli_now(), elapsed = now - p->started;
    int k = (int)(fraction * p->runs) + 1;
    if (elapsed < 1.0 || now - p->last_shown < 0.25)
        return 0;
    p->last_shown = now;
    p->shown = 1;
    fprintf(stderr, "\r  spread: run %d of %d  t = %.4f s  contacts %ld  %5.1f %%  ETA %.0f s   ",
            k > p->runs ? p->runs : k, p->runs, t, contacts, 100.0 * fraction,
            fraction > 0.0 ? elapsed * (1.0 - fraction) / fraction : 0.0);
    fflush(stderr);
    return 0;
}

int td_run_spread(const td_job *job, const td_run_summary *run, int n, int progress, volatile sig_atomic_t *cancel,
                  td_spread *out)
{
    td_run_summary *members = calloc((size_t)n, sizeof *members);
    spread_progress prog = {0, 0.0, 0.0, 0};
    td_run_hooks hooks = {NULL, NULL, 0.0, NULL};
    td_error err;
    td_status st;
    if (!members) {
        fprintf(stderr, "touchdown: out of memory for the spread's %d runs\n", n);
        return TD_EXIT_FAILED;
    }
    td_error_clear(&err);
    memset(out, 0, sizeof *out); /* members 0: not gathered */
    members[0] = *run;
    prog.runs = n - 1;
    prog.started = td_cli_now();
    if (progress) {
        hooks.progress = show_spread_progress;
        hooks.user = &prog;
    }
    hooks.cancel = cancel;
    st = td_spread_run(job, n, &hooks, members, &err);
    if (prog.shown)
        fputs("\r\033[K", stderr);
    if (st != TD_OK)
        fprintf(stderr, "touchdown: %s: %s\n", td_case_path(td_job_case(job)),
                err.message[0] ? err.message : td_strerror(st));
    if (st == TD_OK || st == TD_ERR_INTERRUPTED) /* every member's summary filled, run or not */
        td_spread_collect(members, n, out, NULL);
    free(members);
    return td_cli_exit_code(st);
}
