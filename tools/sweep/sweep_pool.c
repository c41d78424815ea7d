/*
 * touchdown sweep: worker processes. Each point runs in a process of its own (fork), through the
 * library's run loop as `touchdown run` does but without output files, and sends its summary row
 * back through a pipe. A process per point keeps points apart: a crash, a leak or a hang in one
 * point cannot touch the others, and a dead worker is a failed point, never a failed sweep. Points
 * are handed out one at a time to whichever worker is free, because their costs differ by orders
 * of magnitude (a free orbit against a long rub).
 */
#include "sweep/sweep_pool.h"

#include <errno.h>
#include <poll.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>
#include <sys/wait.h>
#ifdef __linux__
#include <sys/prctl.h>
#else
#include <sys/time.h>
#endif
#include <unistd.h>

/* A running worker: its process, the read end of its pipe, its point and the bytes of its row. */
typedef struct worker {
    pid_t pid;
    int fd;
    long point;
    double started; /* wall clock, s */
    size_t got;
    td_sweep_row row;
} worker;

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

/* The name of point `point`'s result file with extension `ext` (".h5", ".csv") in `dir`. */
#define SWEEP_POINT_FILE "%s/point-%06ld%s"

/* dst (TD_OUTPUT_PATH_SIZE bytes) = the file of `point` with extension `ext`; -1 ("") if too long. */
static int point_path(char *dst, const char *dir, long point, const char *ext)
{
    if (snprintf(dst, TD_OUTPUT_PATH_SIZE, SWEEP_POINT_FILE, dir, point, ext) < TD_OUTPUT_PATH_SIZE)
        return 0;
    dst[0] = '\0';
    return -1;
}

int sweep_point_paths(const sweep_job *job, long point, td_output_options *out)
{
    int bad = 0;
    out->hdf5_path[0] = out->csv_path[0] = '\0';
    if (job->point_dir)
        bad |= point_path(out->hdf5_path, job->point_dir, point, ".h5");
    if (job->point_dir && job->point_csv)
        bad |= point_path(out->csv_path, job->point_dir, point, ".csv");
    return bad;
}

/* The whole run of one point, as `touchdown run` does it (touchdown/job.h), its files written only
 * when the sweep keeps them (DIR/point-NNNNNN.h5 and .csv, checked before the sweep). */
static void run_point(const sweep_job *job, long point, td_sweep_row *row)
{
    const char *items[TD_CLI_MAX_SETS + TD_SWEEP_MAX_KEYS];
    char store[TD_SWEEP_MAX_KEYS][TD_SWEEP_KEY_SIZE + TD_SWEEP_VALUE_SIZE];
    int n = sweep_point_overrides(job, point, items, store);
    td_job *j = NULL;
    td_job_settings set;
    td_run_summary s;
    td_error err;
    td_status st;
    td_error_clear(&err);
    if ((st = td_job_create(job->case_path, items, n, &j, &err)) != TD_OK) {
        td_sweep_row_unknown(row, TD_SWEEP_FAILED, td_strerror(st), err.message);
        return;
    }
    set = *td_job_settings_get(j);
    sweep_point_paths(job, point, &set.out); /* every point's checked before the sweep */
    td_job_set(j, &set, NULL);               /* cannot fail: the job has not started */
    td_job_run(j, NULL, &s, &err);           /* a failed set-up: the failed summary */
    td_sweep_row_from_summary(row, &s);
    td_job_free(&j);
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
    double t0 = td_cli_now();
    /* Ctrl-C reaches the whole process group: the parent alone decides, and stops workers with
     * SIGTERM, which ends them at once (held back until the handlers are reset: a SIGTERM
     * between fork and here would otherwise reach the parent's handler and be lost) */
    signal(SIGINT, SIG_IGN);
    signal(SIGHUP, SIG_IGN);
    signal(SIGTERM, SIG_DFL);
    sigprocmask(SIG_SETMASK, old_mask, NULL);
    run_point(job, point, &row);
    row.wall_time = td_cli_now() - t0;
    _exit(write_all(fd, &row, sizeof row) ? 3 : 0);
}

#ifndef __linux__
/* The sweep's process, for the parent watch of a worker (set in the worker before its handler). */
static volatile pid_t watched_parent;

static void on_parent_watch(int sig)
{
    (void)sig;
    if (getppid() != watched_parent) /* reparented: the sweep is gone */
        _exit(4);
}
#endif

/* A worker dies with its sweep, even one killed by SIGKILL, which no handler sees: on Linux the
 * kernel sends the worker SIGKILL when its parent dies (prctl PR_SET_PDEATHSIG, Linux-specific:
 * it fires when the thread that forked exits, and the pool forks from the sweep's main thread).
 * A parent that died before the request took effect left the worker reparented already, so its
 * parent is checked once the request is made. Elsewhere the worker polls its parent once a second
 * (an interval timer whose handler calls only getppid and _exit, both async-signal-safe). */
static void die_with_parent(pid_t parent)
{
#ifdef __linux__
    prctl(PR_SET_PDEATHSIG, SIGKILL);
#else
    struct sigaction sa;
    struct itimerval every = {{1, 0}, {1, 0}};
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_parent_watch;
    sa.sa_flags = SA_RESTART;
    sigemptyset(&sa.sa_mask);
    watched_parent = parent;
    sigaction(SIGALRM, &sa, NULL);
    setitimer(ITIMER_REAL, &every, NULL);
#endif
    if (getppid() != parent)
        _exit(4);
}

/* Start a worker for `point` in w; 0 on success, -1 if no process or pipe could be made. */
static int worker_start(worker *w, const sweep_job *job, long point)
{
    int fds[2];
    sigset_t stop, old_mask;
    pid_t parent = getpid();
    if (pipe(fds))
        return -1;
    fflush(NULL); /* a child must not print what the parent has buffered */
    sigemptyset(&stop);
    sigaddset(&stop, SIGTERM);
    sigprocmask(SIG_BLOCK, &stop, &old_mask);
    w->pid = fork();
    if (w->pid == 0) {
        die_with_parent(parent);
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
    w->started = td_cli_now();
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

void sweep_report_failure(const sweep_job *job, long point, const td_sweep_row *row)
{
    int a;
    fprintf(stderr, "touchdown sweep: point %ld (", point);
    for (a = 0; a < td_sweep_grid_keys(job->grid); a++)
        fprintf(stderr, "%s%s=%s", a ? " " : "", td_sweep_grid_key(job->grid, a),
                td_sweep_grid_value(job->grid, point, a));
    fprintf(stderr, "): %s: %s\n", row->status, row->message[0] ? row->message : "no message");
}

/* The pool: its workers, how many run, whether the feed has ended, what it feeds from. */
typedef struct pool {
    worker ws[TD_SWEEP_POOL_MAX];
    int n, running, ended;
    const sweep_job *job;
    const sweep_feed *feed;
    volatile sig_atomic_t *cancel;
} pool;

/* The worker's pipe is closed (EOF): collect its process and hand its point's row to the feed. A
 * worker killed by the signal that stops the sweep (mpirun sends SIGTERM to the whole job) leaves
 * its point without a row, as one the pool kills does. */
static void worker_finish(pool *pl, worker *w)
{
    int status = reap(w->pid);
    char why[96];
    td_sweep_row row;
    close(w->fd);
    w->pid = 0;
    if (WIFEXITED(status) && WEXITSTATUS(status) == 0 && w->got == sizeof w->row) {
        pl->feed->finished(pl->feed->ctx, w->point, &w->row, 1);
        return;
    }
    if (*pl->cancel)
        return;
    if (WIFSIGNALED(status))
        snprintf(why, sizeof why, "the worker was killed by signal %d (%s)", WTERMSIG(status),
                 strsignal(WTERMSIG(status)));
    else
        snprintf(why, sizeof why, "the worker ended with status %d before sending its result",
                 WIFEXITED(status) ? WEXITSTATUS(status) : -1);
    td_sweep_row_unknown(&row, TD_SWEEP_FAILED, "worker died", why);
    pl->feed->finished(pl->feed->ctx, w->point, &row, 0);
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

/* Wait (at most the feed's wait_ms, so that a signal or a request is seen soon) for workers to
 * send or end, and finish those that ended. */
static void pool_wait(pool *pl)
{
    struct pollfd pfd[TD_SWEEP_POOL_MAX];
    int i;
    for (i = 0; i < pl->n; i++) {
        pfd[i].fd = pl->ws[i].pid > 0 ? pl->ws[i].fd : -1;
        pfd[i].events = POLLIN;
        pfd[i].revents = 0;
    }
    if (poll(pfd, (nfds_t)pl->n, pl->feed->wait_ms) <= 0)
        return;
    for (i = 0; i < pl->n; i++)
        if (pl->ws[i].pid > 0 && pfd[i].revents && worker_read(&pl->ws[i])) {
            worker_finish(pl, &pl->ws[i]);
            pl->running--;
        }
}

/* Stop the workers that have run longer than the job's point_timeout. Their points fail with
 * status "timeout", a result of the sweep's own settings like any failure, so it is journaled:
 * a resume does not run them again (a finished sweep's journal is gone, a new one does). */
static void pool_expire(pool *pl)
{
    double now = td_cli_now(), limit = pl->job->point_timeout;
    td_sweep_row row;
    char why[TD_ERROR_MESSAGE_SIZE];
    int i;
    for (i = 0; i < pl->n && limit > 0.0; i++) {
        worker *w = &pl->ws[i];
        if (w->pid <= 0 || now - w->started <= limit)
            continue;
        kill(w->pid, SIGKILL);
        reap(w->pid);
        close(w->fd);
        w->pid = 0;
        pl->running--;
        snprintf(why, sizeof why, "stopped: ran longer than --point-timeout %g s of wall time", limit);
        td_sweep_row_unknown(&row, TD_SWEEP_FAILED, "timeout", why);
        row.wall_time = now - w->started;
        pl->feed->finished(pl->feed->ctx, w->point, &row, 1);
    }
}

/* Stop every running worker; their points get no row. */
static void pool_kill(pool *pl)
{
    int i;
    for (i = 0; i < pl->n; i++)
        if (pl->ws[i].pid > 0) {
            kill(pl->ws[i].pid, SIGTERM);
            reap(pl->ws[i].pid);
            close(pl->ws[i].fd);
            pl->ws[i].pid = 0;
        }
    pl->running = 0;
}

/* Give the feed's next point to every free worker; a point whose worker cannot start is failed. */
static void pool_fill(pool *pl)
{
    td_sweep_row row;
    long p;
    int i;
    for (i = 0; i < pl->n && !pl->ended; i++) {
        if (pl->ws[i].pid > 0)
            continue;
        p = pl->feed->next(pl->feed->ctx);
        if (p == SWEEP_FEED_WAIT)
            break;
        if (p == SWEEP_FEED_END) {
            pl->ended = 1;
            break;
        }
        if (worker_start(&pl->ws[i], pl->job, p)) {
            pl->ws[i].pid = 0;
            td_sweep_row_unknown(&row, TD_SWEEP_FAILED, "worker died", "cannot start a worker process");
            pl->feed->finished(pl->feed->ctx, p, &row, 0);
        } else
            pl->running++;
    }
}

void sweep_pool_serve(const sweep_job *job, int jobs, const sweep_feed *feed, volatile sig_atomic_t *cancel)
{
    pool *pl;
    if (jobs < 1)
        return;
    pl = calloc(1, sizeof *pl); /* 256 workers with their rows: too much for the stack */
    if (!pl) {
        td_cli_error("sweep", "out of memory for the worker pool");
        return;
    }
    pl->n = jobs > TD_SWEEP_POOL_MAX ? TD_SWEEP_POOL_MAX : jobs;
    pl->job = job;
    pl->feed = feed;
    pl->cancel = cancel;
    while (!*cancel) {
        pool_fill(pl);
        if (pl->ended && pl->running == 0)
            break;
        pool_wait(pl);
        pool_expire(pl);
        if (feed->service && feed->service(feed->ctx))
            break;
    }
    pool_kill(pl);
    free(pl);
}
