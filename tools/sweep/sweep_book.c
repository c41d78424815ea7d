/*
 * touchdown sweep: the books of a sweep. Whoever writes the table (the one process, or rank 0 of
 * an MPI run) hands out the points here, one at a time and never one twice, keeps each row as it
 * arrives, and counts what the progress line and the summary say.
 */
#include "sweep/sweep_book.h"

#include <stdio.h>

long sweep_book_next(sweep_book *b)
{
    while (b->next < b->points && b->rows[b->next].state != TD_SWEEP_NOT_RUN) /* resumed */
        b->next++;
    if (b->next == b->points)
        return SWEEP_FEED_END;
    b->handed++;
    return b->next++;
}

void sweep_book_arrived(sweep_book *b, long point, const td_sweep_row *row)
{
    b->rows[point] = *row;
    b->ran++;
    if (row->wall_time == row->wall_time) /* NaN for a dead worker */
        b->wall_sum += row->wall_time;
    if (row->state == TD_SWEEP_FAILED) {
        b->failed++;
        sweep_progress_clear(&b->progress);
        sweep_report_failure(b->job, point, row);
    }
}

/* Seconds left: the points not yet handed out and the mean wall time of a point, spread over
 * every worker (the running points count as half done); < 0 before the first row. */
static double eta(const sweep_book *b)
{
    long running = b->handed - b->ran;
    double left = (double)(b->points - b->resumed - b->handed) + 0.5 * (double)running;
    if (b->ran == 0)
        return -1.0;
    return left * (b->wall_sum / (double)b->ran) / (double)(b->workers > 0 ? b->workers : 1);
}

void sweep_book_progress(sweep_book *b, int final)
{
    sweep_status s;
    s.points = b->points;
    s.done = b->resumed + b->ran;
    s.running = final ? 0 : b->handed - b->ran; /* at the end the running ones were stopped */
    s.failed = b->failed;
    s.eta = !final ? eta(b) : s.done == s.points ? 0.0 : -1.0;
    sweep_progress_show(&b->progress, &s, td_cli_now(), final);
}

static long local_next(void *ctx)
{
    return sweep_book_next(ctx);
}

static void local_finished(void *ctx, long point, const td_sweep_row *row, int ran)
{
    sweep_book *b = ctx;
    if (ran) /* a dead worker is not: a resume retries it */
        sweep_journal_record(b->journal, point, row);
    sweep_book_arrived(b, point, row);
}

static int local_service(void *ctx)
{
    sweep_book_progress(ctx, 0);
    return 0;
}

sweep_feed sweep_book_feed(sweep_book *b)
{
    sweep_feed f;
    f.next = local_next;
    f.finished = local_finished;
    f.service = local_service;
    f.ctx = b;
    f.wait_ms = 250;
    return f;
}
