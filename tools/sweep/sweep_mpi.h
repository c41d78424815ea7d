/* touchdown sweep over the ranks of an MPI run (tools/sweep/sweep_mpi.c). */
#ifndef TD_TOOLS_SWEEP_MPI_H
#define TD_TOOLS_SWEEP_MPI_H

#include "sweep/sweep_book.h"
#include "touchdown/output.h"

#include <signal.h>
#include <stddef.h>
#include <stdint.h>

/* The ranks: size 0 when the tool was not started by an MPI launcher (or was built without MPI),
 * and then everything below is a no-op. */
typedef struct sweep_world {
    int rank, size;
} sweep_world;

/* If an MPI launcher started this process (its environment says so), MPI_Init and the rank and
 * size; otherwise size 0. Returns 0, or TD_EXIT_FAILED after an error line. */
int sweep_mpi_init(sweep_world *w);

/* MPI_Finalize if MPI_Init was called; returns code. */
int sweep_mpi_finalize(const sweep_world *w, int code);

/* "built with MPI (LIBRARY VERSION)" or "built without MPI", into buf (n bytes). */
void sweep_mpi_describe(char *buf, size_t n);

/* What rank 0 tells every rank once it has checked the points, the outputs and the journal. */
typedef struct sweep_go {
    int code;    /* 0: run; else every rank's exit code (-1: --help was printed, exit 0) */
    uint64_t fp; /* the sweep's fingerprint, for the headers of the parts */
    char journal[TD_OUTPUT_PATH_SIZE];
} sweep_go;

/* Rank 0's *go to every rank (collective: every rank calls it once). */
void sweep_mpi_go(const sweep_world *w, sweep_go *go);

/* Rank 0: run points in `jobs` workers of its own and hand out points to the other ranks as
 * they ask, until every rank has said it is done. On a signal every rank is told to stop.
 * Returns 0, or 1 if some rank did not answer within 10 s of the stop. */
int sweep_mpi_lead(const sweep_world *w, sweep_book *b, int jobs, volatile sig_atomic_t *cancel);

/* Rank 0, at the end: every rank's exit code (lost: abort the job with it instead). */
void sweep_mpi_tell(const sweep_world *w, int code, int lost);

/* A rank > 0: ask rank 0 for a point whenever one of its `jobs` workers is free, run it and record
 * its row in *part (and send it to rank 0, for the progress line and failed points) until rank 0
 * has no more or says stop; then close the part, say done and return the exit code rank 0 sends. */
int sweep_mpi_follow(const sweep_world *w, const sweep_job *job, int jobs, sweep_journal **part,
                     volatile sig_atomic_t *cancel);

#endif
