/*
 * HDF5 helpers shared by the writers (h5_util.h).
 */
#include "io/h5_util.h"
#include "io/h5_vfd.h"
#include "io/schema.h"
#include "util/error_internal.h"

#include <hdf5_hl.h> /* H5DS: dimension scales */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

hid_t td_h5_create_file(const char *path, int v18, int *io_errno, hid_t *driver)
{
    hid_t fapl = H5Pcreate(H5P_FILE_ACCESS), file = -1;
    *driver = -1;
    if (fapl < 0)
        return -1;
    if (!v18 || H5Pset_libver_bounds(fapl, H5F_LIBVER_V18, H5F_LIBVER_LATEST) >= 0)
        *driver = td_h5_vfd_use(fapl, io_errno);
    if (*driver >= 0)
        file = H5Fcreate(path, H5F_ACC_TRUNC, H5P_DEFAULT, fapl);
    H5Pclose(fapl);
    return file;
}

hid_t td_h5_text_type(void)
{
    hid_t type = H5Tcopy(H5T_C_S1);
    if (type >= 0 && (H5Tset_size(type, H5T_VARIABLE) < 0 || H5Tset_cset(type, H5T_CSET_UTF8) < 0 ||
                      H5Tset_strpad(type, H5T_STR_NULLTERM) < 0)) {
        H5Tclose(type);
        return -1;
    }
    return type;
}

herr_t td_h5_attr_string(hid_t obj, const char *name, const char *value)
{
    hid_t type = td_h5_text_type(), space = H5Screate(H5S_SCALAR), attr = -1;
    herr_t rc = -1;
    if (type >= 0 && space >= 0) {
        if (H5Aexists(obj, name) > 0)
            H5Adelete(obj, name);
        attr = H5Acreate2(obj, name, type, space, H5P_DEFAULT, H5P_DEFAULT);
        if (attr >= 0)
            rc = H5Awrite(attr, type, &value);
    }
    if (attr >= 0 && H5Aclose(attr) < 0)
        rc = -1;
    if (space >= 0)
        H5Sclose(space);
    if (type >= 0)
        H5Tclose(type);
    return rc;
}

herr_t td_h5_attr_numeric(hid_t obj, const char *name, hid_t file_type, hid_t mem_type, const void *values, int n,
                          int is_array)
{
    hsize_t dims[1];
    hid_t space, attr = -1;
    herr_t rc = -1;
    dims[0] = (hsize_t)n;
    space = is_array ? H5Screate_simple(1, dims, NULL) : H5Screate(H5S_SCALAR);
    if (space < 0)
        return -1;
    if (H5Aexists(obj, name) > 0)
        H5Adelete(obj, name);
    attr = H5Acreate2(obj, name, file_type, space, H5P_DEFAULT, H5P_DEFAULT);
    if (attr >= 0)
        rc = H5Awrite(attr, mem_type, values);
    if (attr >= 0 && H5Aclose(attr) < 0)
        rc = -1;
    H5Sclose(space);
    return rc;
}

herr_t td_h5_attr_int(hid_t obj, const char *name, int value)
{
    return td_h5_attr_numeric(obj, name, H5T_STD_I32LE, H5T_NATIVE_INT, &value, 1, 0);
}

herr_t td_h5_attr_double(hid_t obj, const char *name, double value)
{
    return td_h5_attr_numeric(obj, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &value, 1, 0);
}

hid_t td_h5_fixed_dataset(hid_t loc, const char *name, hid_t file_type, hid_t mem_type, const void *data, int rank,
                          const hsize_t *dims)
{
    hid_t space = H5Screate_simple(rank, dims, NULL), dset = -1;
    hsize_t n = 1;
    int i;
    for (i = 0; i < rank; i++)
        n *= dims[i];
    if (space >= 0)
        dset = H5Dcreate2(loc, name, file_type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    if (space >= 0)
        H5Sclose(space);
    if (dset >= 0 && n > 0 && H5Dwrite(dset, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0) {
        H5Dclose(dset);
        return -1;
    }
    return dset;
}

int td_h5_dataset(hid_t loc, const char *name, hid_t file_type, hid_t mem_type, const void *data, int rank,
                  const hsize_t *dims, const char *units)
{
    hid_t dset = td_h5_fixed_dataset(loc, name, file_type, mem_type, data, rank, dims);
    int ok = dset >= 0 && td_h5_attr_string(dset, td_out_name(TD_OUT_UNITS), units) >= 0;
    if (dset >= 0 && H5Dclose(dset) < 0)
        ok = 0;
    return ok;
}

int td_h5_table(hid_t g, td_out_id id, hid_t memtype, const void *data, hsize_t rows, hsize_t cols)
{
    hsize_t dims[2];
    dims[0] = rows;
    dims[1] = cols;
    return td_h5_dataset(g, td_out_name(id), memtype == H5T_NATIVE_INT ? H5T_STD_I32LE : H5T_IEEE_F64LE, memtype, data,
                         cols ? 2 : 1, dims, td_out_units(id));
}

int td_h5_index(hid_t loc, const char *name, int n, const char *units)
{
    int *v = malloc((size_t)(n > 0 ? n : 1) * sizeof *v), i, ok;
    hsize_t dims[1];
    dims[0] = (hsize_t)(n > 0 ? n : 0);
    for (i = 0; v && i < n; i++)
        v[i] = i;
    ok = v && td_h5_dataset(loc, name, H5T_STD_I32LE, H5T_NATIVE_INT, v, 1, dims, units);
    free(v);
    return ok;
}

int td_h5_attach(hid_t loc, const char *scale, const char *const *names, unsigned axis)
{
    hid_t s = H5Dopen2(loc, scale, H5P_DEFAULT);
    int ok = s >= 0 && (H5DSis_scale(s) > 0 || H5DSset_scale(s, scale) >= 0), i;
    for (i = 0; ok && names && names[i]; i++) {
        hid_t d = H5Dopen2(loc, names[i], H5P_DEFAULT);
        ok = d >= 0 && H5DSattach_scale(d, s, axis) >= 0;
        if (d >= 0)
            H5Dclose(d);
    }
    if (s >= 0)
        H5Dclose(s);
    return ok;
}

typedef struct h5_msg {
    char text[256];
} h5_msg;

/* H5Ewalk callback: keep the innermost entry (the first one walking upward). */
static herr_t keep_innermost(unsigned n, const H5E_error2_t *e, void *data)
{
    h5_msg *m = data;
    if (n == 0)
        snprintf(m->text, sizeof m->text, "%s: %s", e->func_name ? e->func_name : "?", e->desc ? e->desc : "?");
    return 0;
}

td_status td_h5_fail(td_error *err, const char *path, int io_errno, const char *what)
{
    h5_msg m;
    m.text[0] = '\0';
    H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, keep_innermost, &m);
    H5Eclear2(H5E_DEFAULT);
    if (io_errno)
        return td_error_set(err, TD_ERR_IO, "%s: %s: %s", path, what, strerror(io_errno));
    return td_error_set(err, TD_ERR_IO, "%s: %s%s%s%s", path, what, m.text[0] ? " (HDF5 " : "", m.text,
                        m.text[0] ? ")" : "");
}

/* long runs */
hid_t td_h5_stream_dapl(void)
{
    hid_t dapl = H5Pcreate(H5P_DATASET_ACCESS);
    if (dapl >= 0 && H5Pset_chunk_cache(dapl, H5D_CHUNK_CACHE_NSLOTS_DEFAULT, 0, H5D_CHUNK_CACHE_W0_DEFAULT) < 0) {
        H5Pclose(dapl);
        return -1;
    }
    return dapl;
}

/* The chunked creation properties of an appendable table; with level > 0 shuffle then deflate
 * (lossless: shuffle groups the bytes of equal significance, which deflate then compresses far
 * better for doubles). */
static hid_t append_dcpl(int rank, const hsize_t *chunk, int level)
{
    hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
    if (dcpl >= 0 && (H5Pset_chunk(dcpl, rank, chunk) < 0 ||
                      (level > 0 && (H5Pset_shuffle(dcpl) < 0 || H5Pset_deflate(dcpl, (unsigned)level) < 0)))) {
        H5Pclose(dcpl);
        return -1;
    }
    return dcpl;
}

hid_t td_h5_append_create(hid_t loc, const char *name, hid_t file_type, int rank, const hsize_t *row_dims,
                          hsize_t chunk_rows, int level)
{
    hsize_t dims[TD_H5_APPEND_MAX_RANK], maxdims[TD_H5_APPEND_MAX_RANK], chunk[TD_H5_APPEND_MAX_RANK];
    hid_t space, dcpl, dapl, dset = -1;
    int i;
    if (rank < 1 || rank > TD_H5_APPEND_MAX_RANK)
        return -1;
    dims[0] = 0;
    maxdims[0] = H5S_UNLIMITED;
    chunk[0] = chunk_rows;
    for (i = 1; i < rank; i++) { /* an empty axis (no retainer) still needs a chunk of 1 */
        dims[i] = maxdims[i] = row_dims[i - 1];
        chunk[i] = row_dims[i - 1] > 0 ? row_dims[i - 1] : 1;
    }
    space = H5Screate_simple(rank, dims, maxdims);
    dcpl = append_dcpl(rank, chunk, level);
    dapl = td_h5_stream_dapl(); /* long runs: no chunk cache */
    if (space >= 0 && dcpl >= 0 && dapl >= 0)
        dset = H5Dcreate2(loc, name, file_type, space, H5P_DEFAULT, dcpl, dapl);
    if (dapl >= 0)
        H5Pclose(dapl);
    if (dcpl >= 0)
        H5Pclose(dcpl);
    if (space >= 0)
        H5Sclose(space);
    return dset;
}

herr_t td_h5_append_rows(hid_t dset, hid_t mem_type, int rank, const hsize_t *row_dims, hsize_t at, hsize_t rows,
                         const void *data)
{
    hsize_t dims[TD_H5_APPEND_MAX_RANK], start[TD_H5_APPEND_MAX_RANK], count[TD_H5_APPEND_MAX_RANK];
    hid_t fspace = -1, mspace = -1;
    herr_t rc = -1;
    int i;
    if (rank < 1 || rank > TD_H5_APPEND_MAX_RANK)
        return -1;
    dims[0] = at + rows;
    start[0] = at;
    count[0] = rows;
    for (i = 1; i < rank; i++) {
        if (row_dims[i - 1] == 0)
            return 0; /* a row of no elements: nothing to extend into, the table stays (0, 0) */
        dims[i] = count[i] = row_dims[i - 1];
        start[i] = 0;
    }
    if (H5Dset_extent(dset, dims) >= 0 && (fspace = H5Dget_space(dset)) >= 0 &&
        H5Sselect_hyperslab(fspace, H5S_SELECT_SET, start, NULL, count, NULL) >= 0 &&
        (mspace = H5Screate_simple(rank, count, NULL)) >= 0)
        rc = H5Dwrite(dset, mem_type, mspace, fspace, H5P_DEFAULT, data);
    if (mspace >= 0)
        H5Sclose(mspace);
    if (fspace >= 0)
        H5Sclose(fspace);
    return rc;
}
