/*
 * HDF5 helpers shared by the simulation writer (hdf5_writer.c) and the modal writer
 * (modal_writer.c): one way to create a file on the writers' driver, to write attributes and
 * fixed datasets, to attach dimension scales, and to turn a failure into a td_error.
 *
 * Conventions: text is variable-length UTF-8 (h5py reads it as str, fixed-length strings come
 * back as bytes; netCDF reads NC_STRING); every dataset carries a "units" text attribute; axes
 * are HDF5 dimension scales so netCDF-4 readers see named dimensions. Callers run these inside
 * H5E_BEGIN_TRY/H5E_END_TRY so that the library never prints.
 */
#ifndef TD_IO_H5_UTIL_H
#define TD_IO_H5_UTIL_H

#include "touchdown/error.h"
#include "touchdown/result.h"

#include <hdf5.h>

/**
 * Create (truncate) the file `path` with the writers' driver (h5_vfd.h: an I/O error goes to
 * *io_errno, never into a failed close), in the HDF5 1.8 format when `v18` is nonzero, else in
 * the library's default (earliest) format. *driver is set for td_h5_vfd_release after the close
 * (-1 on failure). Returns the file or -1.
 */
hid_t td_h5_create_file(const char *path, int v18, int *io_errno, hid_t *driver);

/** The variable-length UTF-8 string type (close it with H5Tclose), -1 on failure. */
hid_t td_h5_text_type(void);

/** Scalar text attribute `name` on `obj`, replacing one of that name. */
herr_t td_h5_attr_string(hid_t obj, const char *name, const char *value);

/** Numeric attribute: scalar when !is_array, else 1-D of n values; replaces one of that name. */
herr_t td_h5_attr_numeric(hid_t obj, const char *name, hid_t file_type, hid_t mem_type, const void *values, int n,
                          int is_array);

/** Scalar int32 and float64 attributes. */
herr_t td_h5_attr_int(hid_t obj, const char *name, int value);
herr_t td_h5_attr_double(hid_t obj, const char *name, double value);

/**
 * A fixed (contiguous) dataset `name` under `loc` of shape dims[0..rank-1], written from `data`
 * (not read when it has no elements). Returns the open dataset, -1 on failure.
 */
hid_t td_h5_fixed_dataset(hid_t loc, const char *name, hid_t file_type, hid_t mem_type, const void *data, int rank,
                          const hsize_t *dims);

/** td_h5_fixed_dataset plus its "units" attribute, closed; 0 on failure. */
int td_h5_dataset(hid_t loc, const char *name, hid_t file_type, hid_t mem_type, const void *data, int rank,
                  const hsize_t *dims, const char *units);

/** Output `id`'s dataset under g, named and with the units the schema declares: rows values (cols 0)
 *  or rows x cols (cols > 0) of memtype, int32 in the file for H5T_NATIVE_INT, else float64; 0 on
 *  failure. */
int td_h5_table(hid_t g, td_out_id id, hid_t memtype, const void *data, hsize_t rows, hsize_t cols);

/** A 1-D int32 dataset 0..n-1 with its "units" attribute, closed (the axis of rows that have no
 *  other coordinate); 0 on failure. */
int td_h5_index(hid_t loc, const char *name, int n, const char *units);

/**
 * Make loc/scale a dimension scale (named after itself) and attach it to axis `axis` of every
 * loc/NAME in `names` (NULL-ended; NULL: none, the scale is its own axis); 0 on failure.
 */
int td_h5_attach(hid_t loc, const char *scale, const char *const *names, unsigned axis);

/**
 * Fill err with TD_ERR_IO, "PATH: WHAT: CAUSE": the cause is the driver's I/O error when
 * io_errno != 0, else HDF5's innermost error message (the error stack is cleared).
 */
td_status td_h5_fail(td_error *err, const char *path, int io_errno, const char *what);

/** long runs: a dataset access property list without a raw chunk cache, for an extendible dataset
 *  written a whole chunk at a time, in order (the run's series, events and windows): HDF5's default
 *  keeps up to 1 MiB of written chunks of each dataset in memory, which grows with the run until it
 *  is full (about 20 MiB for the rig's datasets); nothing is ever read back. -1 on failure (close with
 *  H5Pclose). */
hid_t td_h5_stream_dapl(void);

/* ---- appendable tables: the run's series, events and windows ---------------------------------- */

/** Most axes of an appendable table: rows, then up to two fixed axes (a node's x and y). */
#define TD_H5_APPEND_MAX_RANK 3

/**
 * Create the appendable table `name` under `loc`: an extendible dataset of `file_type` with rows
 * along axis 0 (none at first, unlimited) and the fixed axes row_dims[0..rank-2] after it, chunked
 * `chunk_rows` rows at a time, shuffled and deflated at `level` > 0, without a chunk cache
 * (td_h5_stream_dapl). Returns the open dataset, -1 on failure.
 */
hid_t td_h5_append_create(hid_t loc, const char *name, hid_t file_type, int rank, const hsize_t *row_dims,
                          hsize_t chunk_rows, int level);

/**
 * Append `rows` rows of `mem_type` from `data` to the table `dset` created by td_h5_append_create
 * with the same rank and row_dims, `at` rows being there already: extends it to at + rows and
 * writes them. A row of no elements (a fixed axis of 0) writes nothing. Negative on failure.
 */
herr_t td_h5_append_rows(hid_t dset, hid_t mem_type, int rank, const hsize_t *row_dims, hsize_t at, hsize_t rows,
                         const void *data);

#endif
