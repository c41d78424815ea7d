/* touchdown sweep: the journal that makes a sweep resumable (tools/sweep_journal.c). */
#ifndef TD_TOOLS_SWEEP_JOURNAL_H
#define TD_TOOLS_SWEEP_JOURNAL_H

#include "touchdown/case.h"
#include "touchdown/sweep.h"

#include <stdint.h>

typedef struct sweep_journal sweep_journal;

/* What identifies a sweep: the case as loaded with its --set overrides (its text), every point's
 * values, the row layout and the library version. A journal is resumed only by the same sweep. */
uint64_t sweep_fingerprint(const td_case *base, const td_sweep_grid *grid);

/* Open the journal at `path` for a sweep of `points` points with fingerprint `fp`. If a journal of
 * the same sweep is there, the rows it holds are put into rows[] and counted in *resumed; a journal
 * of another sweep is refused. Returns 0, or TD_EXIT_USAGE / TD_EXIT_FAILED after an error line. */
int sweep_journal_open(const char *path, uint64_t fp, long points, td_sweep_row *rows, long *resumed,
                       sweep_journal **out);

/* Record the row of `point` (a row the point's own run produced). A write that fails (disk full)
 * is reported once and ends the journal: the sweep goes on, a resume recomputes what is missing. */
void sweep_journal_record(sweep_journal *j, long point, const td_sweep_row *row);

/* Close the journal and set *j to NULL (accepts NULL); remove its file when `finished` (every
 * point is in the table written). */
void sweep_journal_close(sweep_journal **j, int finished);

#endif
