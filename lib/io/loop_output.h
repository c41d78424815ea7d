/* The loop analysis's parts of the modal files (touchdown/modal_output.h): the CSV sections and
 * the HDF5 group /loop, names from the schema (schema.c). */
#ifndef TD_IO_LOOP_OUTPUT_H
#define TD_IO_LOOP_OUTPUT_H

#include "touchdown/modal.h"

#include <hdf5.h>
#include <stdio.h>

/* The sections loop, sensitivity_peaks and compliance into f (a failed write shows in its error flag). */
void td_loop_write_csv_sections(FILE *f, const td_loop *l);
/* The group /loop under `file`; 0 on failure. */
int td_loop_write_h5_group(hid_t file, const td_loop *l);

#endif
