/*
 * touchdown sweep over the ranks of an MPI run: `mpirun -np N touchdown sweep ...`.
 *
 * Every rank parses the same command line; rank 0 checks every point's case, the outputs and the
 * journal, and tells the others to go or which exit code to end with. Rank 0 then hands out the
 * points one at a time, to its own workers and to any rank that asks (MPI_Iprobe in its pool's
 * turn, so that no core of rank 0 sits idle as a pure master); a rank asks whenever one of its
 * workers is free. Each rank records its rows in a part of its own (PREFIX.journal.rank-K) and
 * sends them to rank 0 too, for the progress line, the failed points' lines and the rows no part
 * holds (a dead worker's); rank 0 merges the parts into the table once every rank has closed its
 * part and said done. The worker processes are forked and never call MPI.
 *
 * Messages (all from or to rank 0): ASK (an int64, ignored) asks for a point; POINT (int64) is
 * the answer, -1 for none; ROW (point and row, bytes: the ranks run one build) a finished point;
 * DONE (int64) a rank has closed its part and will send nothing more but a receive of CODE;
 * STOP (int64) tells a rank to stop its workers; CODE (int64) the exit code, last.
 *
 * Started by an MPI launcher is read from the environment it sets for its processes: Open MPI's
 * mpirun (OMPI_COMM_WORLD_SIZE), PMIx launchers such as srun --mpi=pmix or Open MPI 5 (PMIX_RANK),
 * and PMI ones such as MPICH's hydra or srun --mpi=pmi2 (PMI_RANK with PMI_SIZE). Without any of
 * them the tool never calls MPI_Init and runs exactly as it does when built without MPI.
 */
#include "sweep/sweep_mpi.h"

#include "common/cli.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef TD_HAVE_MPI

#include <mpi.h>
#include <time.h>

enum { TAG_ASK = 1, TAG_POINT, TAG_ROW, TAG_DONE, TAG_STOP, TAG_CODE };

/* How long rank 0 waits for the ranks to say done after telling them to stop. */
#define STOP_GRACE_S 10.0

typedef struct row_msg {
    int64_t point;
    td_sweep_row row;
} row_msg;

static int launched(void)
{
    return getenv("OMPI_COMM_WORLD_SIZE") || getenv("PMIX_RANK") || (getenv("PMI_RANK") && getenv("PMI_SIZE"));
}

int sweep_mpi_init(sweep_world *w)
{
    w->rank = w->size = 0;
    if (!launched())
        return 0;
    if (MPI_Init(NULL, NULL) != MPI_SUCCESS) {
        td_cli_error("sweep", "MPI_Init failed");
        return TD_EXIT_FAILED;
    }
    MPI_Comm_rank(MPI_COMM_WORLD, &w->rank);
    MPI_Comm_size(MPI_COMM_WORLD, &w->size);
    return 0;
}

int sweep_mpi_finalize(const sweep_world *w, int code)
{
    if (w->size > 0)
        MPI_Finalize();
    return code;
}

void sweep_mpi_describe(char *buf, size_t n)
{
    char lib[MPI_MAX_LIBRARY_VERSION_STRING];
    int len = 0;
    char *nl;
    MPI_Get_library_version(lib, &len); /* allowed before MPI_Init */
    if ((nl = strpbrk(lib, ",\n")))
        *nl = '\0'; /* the first clause: "Open MPI v4.1.4" */
    snprintf(buf, n, "built with MPI (%s)", lib);
}

static void pause_ms(long ms)
{
    struct timespec ts;
    ts.tv_sec = 0;
    ts.tv_nsec = ms * 1000000L;
    nanosleep(&ts, NULL);
}

/* Wait for r to complete, asleep between tests: a blocking MPI call spins a core in most MPI
 * libraries, and a rank waiting for rank 0's check or merge would take that core from rank 0 or
 * from the workers on its node. */
static void wait_asleep(MPI_Request *r, MPI_Status *st)
{
    int done = 0;
    while (MPI_Test(r, &done, st) == MPI_SUCCESS && !done)
        pause_ms(2);
}

void sweep_mpi_go(const sweep_world *w, sweep_go *go)
{
    MPI_Request r;
    if (w->size == 0)
        return;
    MPI_Ibcast(go, (int)sizeof *go, MPI_BYTE, 0, MPI_COMM_WORLD, &r);
    wait_asleep(&r, MPI_STATUS_IGNORE);
}

static void send_int(int64_t v, int to, int tag)
{
    MPI_Send(&v, 1, MPI_INT64_T, to, tag, MPI_COMM_WORLD);
}

/* ---- rank 0 --------------------------------------------------------------------------------- */

/* Rank 0's state: its books, its own feed, which ranks are done, whether they were told to stop. */
typedef struct lead {
    const sweep_world *w;
    sweep_book *b;
    sweep_feed own;
    char *done; /* per rank */
    int waiting, stopped;
    volatile sig_atomic_t *cancel;
} lead;

static void answer_ask(lead *l, int from)
{
    int64_t ask, p = SWEEP_FEED_END;
    MPI_Recv(&ask, 1, MPI_INT64_T, from, TAG_ASK, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    if (!l->stopped && !*l->cancel)
        p = sweep_book_next(l->b);
    send_int(p < 0 ? -1 : p, from, TAG_POINT);
}

static void take_row(lead *l, int from)
{
    row_msg m;
    MPI_Recv(&m, (int)sizeof m, MPI_BYTE, from, TAG_ROW, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    if (m.point >= 0 && m.point < l->b->points)
        sweep_book_arrived(l->b, (long)m.point, &m.row);
}

static void take_done(lead *l, int from)
{
    int64_t v;
    MPI_Recv(&v, 1, MPI_INT64_T, from, TAG_DONE, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    if (!l->done[from]) {
        l->done[from] = 1;
        l->waiting--;
    }
}

/* Everything the other ranks have sent, in the order each sent it. */
static void serve(lead *l)
{
    MPI_Status st;
    int flag;
    while (MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &st) == MPI_SUCCESS && flag) {
        if (st.MPI_TAG == TAG_ASK)
            answer_ask(l, st.MPI_SOURCE);
        else if (st.MPI_TAG == TAG_ROW)
            take_row(l, st.MPI_SOURCE);
        else if (st.MPI_TAG == TAG_DONE)
            take_done(l, st.MPI_SOURCE);
        else { /* nothing else is sent to rank 0: take it off the queue */
            char sink[16];
            MPI_Recv(sink, (int)sizeof sink, MPI_BYTE, st.MPI_SOURCE, st.MPI_TAG, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        }
    }
}

static long lead_next(void *ctx)
{
    lead *l = ctx;
    return l->own.next(l->own.ctx);
}

static void lead_finished(void *ctx, long point, const td_sweep_row *row, int ran)
{
    lead *l = ctx;
    l->own.finished(l->own.ctx, point, row, ran);
}

static int lead_service(void *ctx)
{
    lead *l = ctx;
    serve(l);
    sweep_book_progress(l->b, 0);
    return 0;
}

static void tell_stop(lead *l)
{
    int r;
    for (r = 1; r < l->w->size; r++)
        if (!l->done[r])
            send_int(0, r, TAG_STOP);
    l->stopped = 1;
}

/* Serve the other ranks until every one is done; on a signal tell them to stop and wait at most
 * STOP_GRACE_S. Returns 1 if some rank was still not done then. */
static int lead_drain(lead *l)
{
    double deadline = 0.0;
    while (l->waiting > 0) {
        if (*l->cancel && !l->stopped) {
            tell_stop(l);
            deadline = td_cli_now() + STOP_GRACE_S;
        }
        serve(l);
        sweep_book_progress(l->b, 0);
        if (l->stopped && td_cli_now() > deadline)
            return 1;
        pause_ms(5);
    }
    return 0;
}

int sweep_mpi_lead(const sweep_world *w, sweep_book *b, int jobs, volatile sig_atomic_t *cancel)
{
    lead l;
    sweep_feed f;
    int lost;
    if (w->size == 0) { /* not under MPI: the points of this process alone */
        f = sweep_book_feed(b);
        sweep_pool_serve(b->job, jobs, &f, cancel);
        return 0;
    }
    memset(&l, 0, sizeof l);
    l.w = w;
    l.b = b;
    l.own = sweep_book_feed(b);
    l.cancel = cancel;
    l.waiting = w->size - 1;
    if (!(l.done = calloc((size_t)w->size, 1))) {
        td_cli_error("sweep", "out of memory");
        MPI_Abort(MPI_COMM_WORLD, TD_EXIT_FAILED);
    }
    f.next = lead_next;
    f.finished = lead_finished;
    f.service = lead_service;
    f.ctx = &l;
    f.wait_ms = 5; /* a rank that asks waits at most this long */
    sweep_pool_serve(b->job, jobs, &f, cancel);
    lost = lead_drain(&l);
    free(l.done);
    return lost;
}

void sweep_mpi_tell(const sweep_world *w, int code, int lost)
{
    int r;
    if (w->size == 0)
        return;
    if (lost) {
        td_cli_error("sweep", "some rank did not stop within %.0f s: aborting the MPI job", STOP_GRACE_S);
        MPI_Abort(MPI_COMM_WORLD, code ? code : TD_EXIT_FAILED);
    }
    for (r = 1; r < w->size; r++)
        send_int(code, r, TAG_CODE);
}

/* ---- the other ranks ------------------------------------------------------------------------- */

/* A rank's state: its part, its one question to rank 0 at a time and the answer. */
typedef struct follow {
    sweep_journal *part;
    MPI_Request req;
    int64_t answer;
    long got; /* a point received and not yet started, or -1 */
    int asking, ended, stop;
} follow;

static long follow_next(void *ctx)
{
    follow *f = ctx;
    long p = f->got;
    if (p >= 0) {
        f->got = -1;
        return p;
    }
    if (f->ended || f->stop)
        return SWEEP_FEED_END;
    if (!f->asking) { /* the receive posted first: rank 0's answer never waits for it */
        MPI_Irecv(&f->answer, 1, MPI_INT64_T, 0, TAG_POINT, MPI_COMM_WORLD, &f->req);
        send_int(0, 0, TAG_ASK);
        f->asking = 1;
    }
    return SWEEP_FEED_WAIT;
}

static void follow_finished(void *ctx, long point, const td_sweep_row *row, int ran)
{
    follow *f = ctx;
    row_msg m;
    if (ran)
        sweep_journal_record(f->part, point, row);
    memset(&m, 0, sizeof m);
    m.point = point;
    m.row = *row;
    MPI_Send(&m, (int)sizeof m, MPI_BYTE, 0, TAG_ROW, MPI_COMM_WORLD);
}

static int follow_service(void *ctx)
{
    follow *f = ctx;
    int flag = 0;
    int64_t v;
    if (f->asking) {
        MPI_Test(&f->req, &flag, MPI_STATUS_IGNORE);
        if (flag) {
            f->asking = 0;
            if (f->answer < 0)
                f->ended = 1;
            else
                f->got = (long)f->answer;
        }
    }
    MPI_Iprobe(0, TAG_STOP, MPI_COMM_WORLD, &flag, MPI_STATUS_IGNORE);
    if (flag) {
        MPI_Recv(&v, 1, MPI_INT64_T, 0, TAG_STOP, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        f->stop = 1;
    }
    return f->stop;
}

/* The exit code from rank 0, past any STOP it sent before it knew this rank was done. */
static int wait_code(void)
{
    MPI_Request r;
    MPI_Status st;
    int64_t v = TD_EXIT_FAILED;
    do {
        MPI_Irecv(&v, 1, MPI_INT64_T, 0, MPI_ANY_TAG, MPI_COMM_WORLD, &r);
        wait_asleep(&r, &st);
    } while (st.MPI_TAG != TAG_CODE);
    return (int)v;
}

int sweep_mpi_follow(const sweep_world *w, const sweep_job *job, int jobs, sweep_journal **part,
                     volatile sig_atomic_t *cancel)
{
    follow f;
    sweep_feed feed;
    (void)w;
    memset(&f, 0, sizeof f);
    f.part = *part;
    f.got = -1;
    feed.next = follow_next;
    feed.finished = follow_finished;
    feed.service = follow_service;
    feed.ctx = &f;
    feed.wait_ms = 5;
    if (jobs > 0)
        sweep_pool_serve(job, jobs, &feed, cancel);
    if (f.asking) /* rank 0 answers every question until every rank is done */
        wait_asleep(&f.req, MPI_STATUS_IGNORE);
    sweep_journal_close(part);
    send_int(0, 0, TAG_DONE);
    return wait_code();
}

#else /* built without MPI: one process, these are never reached past sweep_mpi_init */

int sweep_mpi_init(sweep_world *w)
{
    w->rank = w->size = 0;
    return 0;
}

int sweep_mpi_finalize(const sweep_world *w, int code)
{
    (void)w;
    return code;
}

void sweep_mpi_describe(char *buf, size_t n)
{
    snprintf(buf, n, "built without MPI");
}

void sweep_mpi_go(const sweep_world *w, sweep_go *go)
{
    (void)w;
    (void)go;
}

int sweep_mpi_lead(const sweep_world *w, sweep_book *b, int jobs, volatile sig_atomic_t *cancel)
{
    sweep_feed f = sweep_book_feed(b);
    (void)w;
    sweep_pool_serve(b->job, jobs, &f, cancel);
    return 0;
}

void sweep_mpi_tell(const sweep_world *w, int code, int lost)
{
    (void)w;
    (void)code;
    (void)lost;
}

int sweep_mpi_follow(const sweep_world *w, const sweep_job *job, int jobs, sweep_journal **part,
                     volatile sig_atomic_t *cancel)
{
    (void)w;
    (void)job;
    (void)jobs;
    (void)cancel;
    sweep_journal_close(part);
    return TD_EXIT_FAILED;
}

#endif
