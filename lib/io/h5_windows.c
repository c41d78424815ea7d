/*
 * long runs: /windows of the HDF5 back end (h5_windows.h). Each quantity of td_window_summary is a
 * dataset (W) or (W, n_ret) under /windows with its `units`, its rows along /windows/time_end (a
 * dimension scale), buffered H5_WINDOW_CHUNK rows at a time: appendable tables (h5_util.h
 * td_h5_append_create, td_h5_append_rows) like the run's series and events.
 */
#include "io/h5_windows.h"

#include "io/h5_util.h"
#include "io/schema.h"

#include <hdf5_hl.h>
#include <stdlib.h>
#include <string.h>

#define H5_WINDOW_CHUNK 256 /* rows per chunk and per buffered write */

/* The datasets, in the order of td_window_summary: the run-wide ones, then those per retainer. */
static const td_out_id window_ids[] = {
    TD_OUT_WIN_TIME_START,       TD_OUT_WIN_TIME_END,          TD_OUT_WIN_SPEED,
    TD_OUT_WIN_ENERGY_KINETIC,   TD_OUT_WIN_ENERGY_RESIDUAL,   TD_OUT_WIN_CONTACTS,
    TD_OUT_WIN_CONTACT_FRACTION, TD_OUT_WIN_PEAK_NORMAL_FORCE, TD_OUT_WIN_FRICTION_WORK,
    TD_OUT_WIN_RACE_TEMPERATURE};
#define N_WINDOW_SETS ((int)(sizeof window_ids / sizeof window_ids[0]))
#define FIRST_PER_RETAINER 5 /* window_ids[5..]: (W, n_ret) */
#define CONTACTS_SET 5       /* int64; the others double */

struct td_h5_windows {
    hid_t dset[N_WINDOW_SETS];
    int n_ret;
    size_t buffered;
    hsize_t flushed;
    double *buf;       /* per set H5_WINDOW_CHUNK rows of row_len(set) doubles */
    long long *counts; /* the contacts set: H5_WINDOW_CHUNK x n_ret */
};

static size_t row_len(const td_h5_windows *t, int set)
{
    return set >= FIRST_PER_RETAINER ? (size_t)t->n_ret : 1;
}

/* Offset of set `set`'s buffer in t->buf. */
static size_t buf_at(const td_h5_windows *t, int set)
{
    size_t at = 0;
    int i;
    for (i = 0; i < set; i++)
        at += H5_WINDOW_CHUNK * row_len(t, i);
    return at;
}

static hid_t create_set(hid_t g, const td_h5_windows *t, int set, int level)
{
    const hsize_t row[1] = {(hsize_t)t->n_ret};
    hid_t dset =
        td_h5_append_create(g, td_out_name(window_ids[set]), set == CONTACTS_SET ? H5T_STD_I64LE : H5T_IEEE_F64LE,
                            set >= FIRST_PER_RETAINER ? 2 : 1, row, H5_WINDOW_CHUNK, level);
    if (dset >= 0 && td_h5_attr_string(dset, td_out_name(TD_OUT_UNITS), td_out_units(window_ids[set])) < 0) {
        H5Dclose(dset);
        dset = -1;
    }
    return dset;
}

/* /windows/time_end names the rows of every set; /retainers/retainer the columns of those per retainer. */
static int attach_scales(hid_t file, td_h5_windows *t)
{
    const int end = 1;
    int i, rc = H5DSset_scale(t->dset[end], td_out_name(TD_OUT_WIN_TIME_END)) < 0 ? -1 : 0;
    for (i = 0; rc == 0 && i < N_WINDOW_SETS; i++)
        if (i != end && H5DSattach_scale(t->dset[i], t->dset[end], 0) < 0)
            rc = -1;
    if (rc == 0 && t->n_ret > 0) {
        char path[64];
        hid_t ret;
        td_out_path(TD_OUT_RETAINER, NULL, path, sizeof path);
        ret = H5Dopen2(file, path, H5P_DEFAULT);
        for (i = FIRST_PER_RETAINER; ret >= 0 && rc == 0 && i < N_WINDOW_SETS; i++)
            if (H5DSattach_scale(t->dset[i], ret, 1) < 0)
                rc = -1;
        if (ret < 0)
            rc = -1;
        else
            H5Dclose(ret);
    }
    return rc;
}

td_h5_windows *td_h5_windows_create(hid_t file, int n_ret, int level, int *nomem)
{
    td_h5_windows *t = calloc(1, sizeof *t);
    hid_t g = -1;
    int i, ok;
    *nomem = 0;
    if (!t) {
        *nomem = 1;
        return NULL;
    }
    t->n_ret = n_ret;
    for (i = 0; i < N_WINDOW_SETS; i++)
        t->dset[i] = -1;
    t->buf = malloc(buf_at(t, N_WINDOW_SETS) * sizeof *t->buf);
    t->counts = malloc(H5_WINDOW_CHUNK * (size_t)(n_ret > 0 ? n_ret : 1) * sizeof *t->counts);
    if (!t->buf || !t->counts) {
        *nomem = 1;
        td_h5_windows_free(t);
        return NULL;
    }
    g = H5Gcreate2(file, td_out_name(TD_OUT_WINDOWS), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    ok = g >= 0 && td_h5_attr_int(g, td_out_name(TD_OUT_COUNT), n_ret) >= 0;
    for (i = 0; ok && i < N_WINDOW_SETS; i++)
        ok = (t->dset[i] = create_set(g, t, i, level)) >= 0;
    ok = ok && attach_scales(file, t) == 0;
    if (g >= 0)
        H5Gclose(g);
    if (!ok) {
        td_h5_windows_free(t);
        return NULL;
    }
    return t;
}

int td_h5_windows_flush(td_h5_windows *t)
{
    const hsize_t row[1] = {(hsize_t)t->n_ret};
    int i;
    if (t->buffered == 0)
        return 0;
    for (i = 0; i < N_WINDOW_SETS; i++) {
        const void *data = i == CONTACTS_SET ? (const void *)t->counts : (const void *)(t->buf + buf_at(t, i));
        if (td_h5_append_rows(t->dset[i], i == CONTACTS_SET ? H5T_NATIVE_LLONG : H5T_NATIVE_DOUBLE,
                              i >= FIRST_PER_RETAINER ? 2 : 1, row, t->flushed, t->buffered, data) < 0)
            return -1;
    }
    t->flushed += t->buffered;
    t->buffered = 0;
    return 0;
}

int td_h5_windows_add(td_h5_windows *t, const td_window_summary *win)
{
    const double run[FIRST_PER_RETAINER] = {win->t_start, win->t_end, win->speed, win->energy_kinetic,
                                            win->energy_residual};
    const double *per[] = {NULL, win->contact_fraction, win->peak_normal_force, win->friction_work,
                           win->race_temperature};
    size_t r = t->buffered, n = (size_t)t->n_ret, k;
    int i;
    for (i = 0; i < FIRST_PER_RETAINER; i++)
        t->buf[buf_at(t, i) + r] = run[i];
    for (k = 0; k < n; k++)
        t->counts[r * n + k] = win->contacts[k];
    for (i = CONTACTS_SET + 1; i < N_WINDOW_SETS; i++)
        if (n > 0)
            memcpy(t->buf + buf_at(t, i) + r * n, per[i - CONTACTS_SET], n * sizeof(double));
    t->buffered++;
    return t->buffered == H5_WINDOW_CHUNK ? td_h5_windows_flush(t) : 0;
}

void td_h5_windows_free(td_h5_windows *t)
{
    int i;
    if (!t)
        return;
    for (i = 0; i < N_WINDOW_SETS; i++)
        if (t->dset[i] >= 0)
            H5Dclose(t->dset[i]);
    free(t->buf);
    free(t->counts);
    free(t);
}
