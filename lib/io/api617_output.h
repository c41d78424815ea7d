/* The API 617 unbalance response report's parts of the modal files (touchdown/modal_output.h):
 * the CSV sections unbalance_response, response_peaks and static_reactions, the HDF5 groups of
 * the same names and the log decrement and part nodes in /modes; names from the schema (schema.c). */
#ifndef TD_IO_API617_OUTPUT_H
#define TD_IO_API617_OUTPUT_H

#include "touchdown/modal_output.h"

#include <hdf5.h>
#include <stdio.h>

/* The sections into f (a failed write shows in its error flag); each only when r holds its part. */
void td_api617_write_csv_sections(FILE *f, const td_modal_results *r);
/* The groups under `file` and the datasets in /modes (when r->modes is written); the name of the
 * part that failed, NULL when every call succeeded. */
const char *td_api617_write_h5(hid_t file, const td_modal_results *r);

#endif
