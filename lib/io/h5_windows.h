/*
 * long runs: the window summaries of the HDF5 back end (/windows, docs/output-format.md, "Window
 * summaries"), one extendible dataset per quantity, written a chunk of rows at a time so that a long
 * run holds at most one chunk of them.
 */
#ifndef TD_IO_H5_WINDOWS_H
#define TD_IO_H5_WINDOWS_H

#include "touchdown/output.h"

#include <hdf5.h>

typedef struct td_h5_windows td_h5_windows;

/** Create /windows in `file` for `n_ret` retainers (deflate `level` as the samples); NULL on failure
 *  (an HDF5 error, or no memory: *nomem set). */
td_h5_windows *td_h5_windows_create(hid_t file, int n_ret, int level, int *nomem);

/** Append one summary; -1 if a write failed. */
int td_h5_windows_add(td_h5_windows *t, const td_window_summary *win);

/** Write the buffered rows; -1 if a write failed. */
int td_h5_windows_flush(td_h5_windows *t);

/** Close the datasets and free (NULL accepted). */
void td_h5_windows_free(td_h5_windows *t);

#endif
