/* touchdown sweep: the journal that makes a sweep resumable (tools/sweep/sweep_journal.c). */
#ifndef TD_TOOLS_SWEEP_JOURNAL_H
#define TD_TOOLS_SWEEP_JOURNAL_H

#include "touchdown/case.h"
#include "touchdown/output.h"
#include "touchdown/sweep.h"

#include <stddef.h>
#include <stdint.h>

typedef struct sweep_journal sweep_journal;

/* What identifies a sweep: the case as loaded with its --set overrides (its text), every point's
 * values, the row layout and the library version. A journal is resumed only by the same sweep. */
uint64_t sweep_fingerprint(const td_case *base, const td_sweep_grid *grid);

/* The rows held by the journal at `journal` and by its parts (journal.rank-K, written by the ranks
 * of an MPI run) into rows[] (missing files are none), *found counting the rows that were "not
 * run" before. Only whole records are read (frame, CRC-32, point, state, text bounds); a torn tail
 * is dropped with a notice line. A journal or part of another sweep or format, not a journal, or
 * damaged before its end is refused: TD_EXIT_USAGE after an error line. */
int sweep_store_read(const char *journal, uint64_t fp, long points, td_sweep_row *rows, long *found);

/* Refuse a journal at `journal`, or a part of it on disk, that is one of the n inputs (the case
 * file first, then its @include files: td_case_files), compared by device and inode: the sweep
 * would overwrite it, then remove it. Returns 0, or TD_EXIT_USAGE after an error line. */
int sweep_store_check_inputs(const char *journal, const char *const *inputs, int n);

/* Remove the journal and its parts (once a finished table is written). */
void sweep_store_remove(const char *journal);

/* 1 if every text field of row r ends within its array (holds its terminating zero): the one list
 * of a row's text fields, checked before a row read from a file is trusted. */
int sweep_row_texts_end(const td_sweep_row *r);

/* Room for the path of a part: the journal's, ".rank-" and a rank. */
#define SWEEP_PART_PATH_SIZE (TD_OUTPUT_PATH_SIZE + 24)

/* dst (SWEEP_PART_PATH_SIZE bytes) = the part of `rank` of the journal at `journal` (shorter than
 * TD_OUTPUT_PATH_SIZE). */
void sweep_part_path(char *dst, const char *journal, int rank);

/* Open the journal (or part) at `path` of the sweep with fingerprint `fp` to append rows: created
 * when missing, else its torn tail is cut off. One of another sweep, or damaged, is refused. Returns 0,
 * or TD_EXIT_USAGE / TD_EXIT_FAILED after an error line. */
int sweep_journal_open(const char *path, uint64_t fp, long points, sweep_journal **out);

/* Record the row of `point` (a row the point's own run produced). A write that fails (disk full)
 * is reported once and ends the journal: the sweep goes on, a resume recomputes what is missing. */
void sweep_journal_record(sweep_journal *j, long point, const td_sweep_row *row);

/* Close the journal and set *j to NULL (accepts NULL). */
void sweep_journal_close(sweep_journal **j);

#endif
