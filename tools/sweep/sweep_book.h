/* touchdown sweep: the books of a sweep kept by the process that writes its table (tools/sweep/sweep_book.c). */
#ifndef TD_TOOLS_SWEEP_BOOK_H
#define TD_TOOLS_SWEEP_BOOK_H

#include "sweep/sweep_journal.h"
#include "sweep/sweep_pool.h"
#include "sweep/sweep_progress.h"

/* Every point's row as it arrives, which point goes next, the counts and the progress line: one
 * per sweep, in the one process of a sweep or in rank 0 of an MPI run, which hands out the points
 * of every rank. */
typedef struct sweep_book {
    const sweep_job *job;
    td_sweep_row *rows;       /* one per point, "not run" until its row arrives */
    long points, next;        /* the next point to hand out: the first not run from here */
    long handed, ran, failed; /* points handed out and rows that arrived in this run; failed rows */
    long resumed;             /* rows found in the journal and parts before the run */
    double wall_sum;          /* the arrived rows' wall times */
    double check_time;        /* s, checking every point's case, the outputs and the journal */
    int workers;              /* worker processes of every rank, for the ETA */
    sweep_journal *journal;   /* where this process records its own points' rows (NULL: nowhere) */
    sweep_progress progress;
} sweep_book;

/* The next point not run yet, or SWEEP_FEED_END; counted as handed out. */
long sweep_book_next(sweep_book *b);

/* The row of `point` has arrived (from this process's worker or from another rank): keep it,
 * count it, report it if it failed. */
void sweep_book_arrived(sweep_book *b, long point, const td_sweep_row *row);

/* Print the progress line if due (final: whatever the time, with its newline). */
void sweep_book_progress(sweep_book *b, int final);

/* The feed of a sweep without MPI: points from the book, rows recorded in the journal and kept. */
sweep_feed sweep_book_feed(sweep_book *b);

#endif
