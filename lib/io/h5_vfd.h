/*
 * A POSIX file driver for HDF5 whose writes never fail inside HDF5.
 *
 * Why: in HDF5 1.10 a file whose flush fails while it is being closed (disk full, file size
 * limit) is freed by H5Fclose although its identifier stays registered; the library's exit
 * handler (H5_term_library) then closes it again and crashes (fixed upstream only in 1.14.1).
 * This driver does the I/O itself and keeps the first I/O error in a slot owned by the writer
 * instead of reporting it to HDF5, so HDF5's own state stays consistent and H5Fclose succeeds;
 * the writer checks the slot after every HDF5 operation and treats the file as failed.
 * Files it writes carry no driver information: any HDF5 reader opens them with the default driver.
 */
#ifndef TD_IO_H5_VFD_H
#define TD_IO_H5_VFD_H

#include <hdf5.h>

/**
 * Register the driver (one registration per writer: no global state) and set it on `fapl`;
 * the first errno of a failed read, write or truncate goes to *io_errno (which must outlive the
 * file). Returns the driver id to pass to td_h5_vfd_release after the file is closed, or -1.
 */
hid_t td_h5_vfd_use(hid_t fapl, int *io_errno);

/** Drop the registration made by td_h5_vfd_use (accepts -1). */
void td_h5_vfd_release(hid_t driver);

#endif
