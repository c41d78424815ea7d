/*
 * touchdown sweep: worker processes. Each point runs in a process of its own (fork), through the
 * library's run loop as `touchdown run` does but without output files, and sends its summary row
 * back through a pipe. A process per point keeps points apart: a crash, a leak or a hang in one
 * point cannot touch the others, and a dead worker is a failed point, never a failed sweep. Points
 * are handed out one at a time to whichever worker is free, because their costs differ by orders
 * of magnitude (a free orbit against a long rub).
 */
#include "sweep_pool.h"

#include <errno.h>
#include <poll.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

/* A running worker: its process, the read end of its pipe, its point and the bytes of its row. */
typedef struct worker {
    pid_t pid;
    int fd;
    long point;
    size_t got;
    td_sweep_row row;
} worker;

static double wall_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

int sweep_point_overrides(const sweep_job *job, long point, const char **items,
                          char store[][TD_SWEEP_KEY_SIZE + TD_SWEEP_VALUE_SIZE])
{
    int i, n = 0;
    for (i = 0; i < job->sets->count; i++)
        items[n++] = job->sets->items[i];
    /* after the fixed overrides: a swept key also given with --set takes the swept value */
    for (i = 0; i < td_sweep_grid_keys(job->grid); i++) {
        td_sweep_grid_override(job->grid, point, i, store[i], sizeof store[i]);
        items[n++] = store[i];
    }
    return n;
}

/* The whole run of one point, as `touchdown run` does it, its files written only when the sweep
 * keeps them (DIR/point-NNNNNN.h5 and .csv, their lengths checked before the sweep). */
static void run_point(const sweep_job *job, long point, td_sweep_row *row)
{
    const char *items[TD_CLI_MAX_SETS + TD_SWEEP_MAX_KEYS];
    char store[TD_SWEEP_MAX_KEYS][TD_SWEEP_KEY_SIZE + TD_SWEEP_VALUE_SIZE];
    int n = sweep_point_overrides(job, point, items, store);
    td_case *c = NULL;
    td_sim *sim = NULL;
    td_output_options out;
    td_run_summary s;
    td_error err;
    td_status st;
    td_error_clear(&err);
    if ((st = td_case_load(job->case_path, items, n, &c, &err)) != TD_OK) {
        td_sweep_row_unknown(row, TD_SWEEP_FAILED, td_strerror(st), err.message);
        return;
    }
    out = *td_case_output_options(c);
    out.hdf5_path[0] = out.csv_path[0] = '\0';
    if (job->point_dir)
        snprintf(out.hdf5_path, sizeof out.hdf5_path, SWEEP_POINT_FILE, job->point_dir, point, ".h5");
    if (job->point_dir && job->point_csv)
        snprintf(out.csv_path, sizeof out.csv_path, SWEEP_POINT_FILE, job->point_dir, point, ".csv");
    st = td_sim_create(td_case_model(c), td_case_sim_options(c), &sim, &err);
    if (st != TD_OK)
        td_run_summary_failed(&s, td_case_sim_options(c)->t0, td_case_end_time(c), td_model_speed(td_case_model(c)),
                              td_case_sim_options(c)->start, st, err.message);
    else /* the case text goes into the point's files, as touchdown run stores it */
        td_run(sim, td_case_end_time(c), &out, NULL, td_case_text(c), &s, &err);
    td_sweep_row_from_summary(row, &s);
    td_sim_free(&sim);
    td_case_free(&c);
}

static int write_all(int fd, const void *buf, size_t n)
{
    const char *p = buf;
    while (n > 0) {
        ssize_t k = write(fd, p, n);
        if (k < 0 && errno == EINTR)
            continue;
        if (k <= 0)
            return -1;
        p += k;
        n -= (size_t)k;
    }
    return 0;
}

/* The worker process: run the point, send the row, exit without the parent's stdio buffers. */
static void worker_main(const sweep_job *job, long point, int fd, const sigset_t *old_mask)
{
    td_sweep_row row;
    double t0 = wall_now();
    /* Ctrl-C reaches the whole process group: the parent alone decides, and stops workers with
     * SIGTERM, which ends them at once (held back until the handlers are reset: a SIGTERM
     * between fork and here would otherwise reach the parent's handler and be lost) */
    signal(SIGINT, SIG_IGN);
    signal(SIGHUP, SIG_IGN);
    signal(SIGTERM, SIG_DFL);
    sigprocmask(SIG_SETMASK, old_mask, NULL);
    run_point(job, point, &row);
    row.wall_time = wall_now() - t0;
    _exit(write_all(fd, &row, sizeof row) ? 3 : 0);
}

/* Start a worker for `point` in w; 0 on success, -1 if no process or pipe could be made. */
static int worker_start(worker *w, const sweep_job *job, long point)
{
    int fds[2];
    sigset_t stop, old_mask;
    if (pipe(fds))
        return -1;
    fflush(NULL); /* a child must not print what the parent has buffered */
    sigemptyset(&stop);
    sigaddset(&stop, SIGTERM);
    sigprocmask(SIG_BLOCK, &stop, &old_mask);
    w->pid = fork();
    if (w->pid == 0) {
        close(fds[0]);
        worker_main(job, point, fds[1], &old_mask);
    }
    sigprocmask(SIG_SETMASK, &old_mask, NULL);
    close(fds[1]);
    if (w->pid < 0) {
        close(fds[0]);
        return -1;
    }
    w->fd = fds[0];
    w->point = point;
    w->got = 0;
    return 0;
}

static int reap(pid_t pid)
{
    int status = 0;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR)
        ;
    return status;
}

static void report_failure(const sweep_job *job, long point, const td_sweep_row *row)
{
    int a;
    fprintf(stderr, "touchdown sweep: point %ld (", point);
    for (a = 0; a < td_sweep_grid_keys(job->grid); a++)
        fprintf(stderr, "%s%s=%s", a ? " " : "", td_sweep_grid_key(job->grid, a),
                td_sweep_grid_value(job->grid, point, a));
    fprintf(stderr, "): %s: %s\n", row->status, row->message[0] ? row->message : "no message");
}

/* The worker's pipe is closed (EOF): collect its process and record its point's row. */
static void worker_finish(worker *w, const sweep_job *job, td_sweep_row *rows)
{
    int status = reap(w->pid);
    char why[96];
    close(w->fd);
    w->pid = 0;
    if (WIFEXITED(status) && WEXITSTATUS(status) == 0 && w->got == sizeof w->row) {
        rows[w->point] = w->row;
        sweep_journal_record(job->journal, w->point, &w->row); /* a dead worker is not: a resume retries it */
    } else {
        if (WIFSIGNALED(status))
            snprintf(why, sizeof why, "the worker was killed by signal %d (%s)", WTERMSIG(status),
                     strsignal(WTERMSIG(status)));
        else
            snprintf(why, sizeof why, "the worker ended with status %d before sending its result",
                     WIFEXITED(status) ? WEXITSTATUS(status) : -1);
        td_sweep_row_unknown(&rows[w->point], TD_SWEEP_FAILED, "worker died", why);
    }
    if (rows[w->point].state == TD_SWEEP_FAILED)
        report_failure(job, w->point, &rows[w->point]);
}

/* Read what the worker has sent; 1 once its pipe is closed. */
static int worker_read(worker *w)
{
    char sink[256];
    ssize_t k;
    if (w->got < sizeof w->row)
        k = read(w->fd, (char *)&w->row + w->got, sizeof w->row - w->got);
    else
        k = read(w->fd, sink, sizeof sink); /* nothing more is expected: wait for the EOF */
    if (k < 0)
        return errno == EINTR || errno == EAGAIN ? 0 : 1;
    if (k == 0)
        return 1;
    if (w->got < sizeof w->row)
        w->got += (size_t)k;
    return 0;
}

/* Wait (at most a quarter of a second, so that a signal is seen soon) for workers to send or
 * end, and finish those that ended. Returns the number finished. */
static int pool_wait(worker *ws, int n, const sweep_job *job, td_sweep_row *rows)
{
    struct pollfd pfd[TD_SWEEP_POOL_MAX];
    int i, done = 0;
    for (i = 0; i < n; i++) {
        pfd[i].fd = ws[i].pid > 0 ? ws[i].fd : -1;
        pfd[i].events = POLLIN;
        pfd[i].revents = 0;
    }
    if (poll(pfd, (nfds_t)n, 250) <= 0)
        return 0;
    for (i = 0; i < n; i++)
        if (ws[i].pid > 0 && pfd[i].revents && worker_read(&ws[i])) {
            worker_finish(&ws[i], job, rows);
            done++;
        }
    return done;
}

/* Stop every running worker; their points stay "not run". */
static void pool_kill(worker *ws, int n)
{
    int i;
    for (i = 0; i < n; i++)
        if (ws[i].pid > 0) {
            kill(ws[i].pid, SIGTERM);
            reap(ws[i].pid);
            close(ws[i].fd);
            ws[i].pid = 0;
        }
}

/* Give the next point to every free worker; a point whose worker cannot start is failed. */
static int pool_fill(worker *ws, int n, const sweep_job *job, td_sweep_row *rows, long *next, long points)
{
    int i, started = 0;
    for (i = 0; i < n && *next < points; i++) {
        if (ws[i].pid > 0)
            continue;
        while (*next < points && rows[*next].state != TD_SWEEP_NOT_RUN) /* resumed from the journal */
            (*next)++;
        if (*next == points)
            break;
        if (worker_start(&ws[i], job, *next)) {
            td_sweep_row_unknown(&rows[*next], TD_SWEEP_FAILED, "worker died", "cannot start a worker process");
            report_failure(job, *next, &rows[*next]);
            ws[i].pid = 0;
        } else
            started++;
        (*next)++;
    }
    return started;
}

long sweep_pool_run(const sweep_job *job, int jobs, td_sweep_row *rows, volatile sig_atomic_t *cancel)
{
    worker ws[TD_SWEEP_POOL_MAX];
    long next = 0, points = td_sweep_grid_points(job->grid), not_run = 0, p;
    int running = 0;
    memset(ws, 0, sizeof ws);
    if (jobs > TD_SWEEP_POOL_MAX)
        jobs = TD_SWEEP_POOL_MAX;
    while (!*cancel && (next < points || running > 0)) {
        running += pool_fill(ws, jobs, job, rows, &next, points);
        running -= pool_wait(ws, jobs, job, rows);
    }
    pool_kill(ws, jobs);
    for (p = 0; p < points; p++)
        not_run += rows[p].state == TD_SWEEP_NOT_RUN;
    return not_run;
}
