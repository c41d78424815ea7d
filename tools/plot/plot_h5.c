/* touchdown plot: reading datasets and attributes with the HDF5 C API (callers silence HDF5's
 * automatic error printing; every failure here is a return code). */
#include "plot.h"

#include <stdlib.h>
#include <string.h>

int plot_h5_exists(hid_t loc, const char *path)
{
    char part[512];
    const char *p = path;
    /* H5Lexists needs every intermediate link to exist: check "a", then "a/b", ... */
    for (;;) {
        const char *slash = strchr(p, '/');
        size_t len = slash ? (size_t)(slash - path) : strlen(path);
        if (len >= sizeof part)
            return 0;
        memcpy(part, path, len);
        part[len] = '\0';
        if (H5Lexists(loc, part, H5P_DEFAULT) <= 0)
            return 0;
        if (!slash)
            return 1;
        p = slash + 1;
    }
}

void plot_array_free(plot_array *a)
{
    free(a->v);
    memset(a, 0, sizeof *a);
}

int plot_h5_read(hid_t loc, const char *path, plot_array *out)
{
    hid_t d = -1, space = -1, type = -1;
    hsize_t dims[3] = {1, 1, 1};
    int rank, i, rc = -1;
    memset(out, 0, sizeof *out);
    if (!plot_h5_exists(loc, path) || (d = H5Dopen2(loc, path, H5P_DEFAULT)) < 0)
        return -1;
    space = H5Dget_space(d);
    type = H5Dget_type(d);
    rank = space >= 0 ? H5Sget_simple_extent_ndims(space) : -1;
    if (type < 0 || rank < 1 || rank > 3 || (H5Tget_class(type) != H5T_FLOAT && H5Tget_class(type) != H5T_INTEGER))
        goto done;
    H5Sget_simple_extent_dims(space, dims, NULL);
    out->rank = rank;
    out->n = 1;
    for (i = 0; i < 3; i++) {
        out->dims[i] = i < rank ? (size_t)dims[i] : 1;
        out->n *= out->dims[i];
    }
    out->v = malloc((out->n ? out->n : 1) * sizeof *out->v);
    if (out->v && (out->n == 0 || H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, out->v) >= 0))
        rc = 0;
done:
    if (type >= 0)
        H5Tclose(type);
    if (space >= 0)
        H5Sclose(space);
    H5Dclose(d);
    if (rc != 0)
        plot_array_free(out);
    return rc;
}

int plot_h5_attr_doubles(hid_t obj, const char *name, double **v, size_t *n)
{
    hid_t a, space = -1, type = -1;
    hssize_t count;
    int rc = -1;
    *v = NULL;
    *n = 0;
    if (H5Aexists(obj, name) <= 0 || (a = H5Aopen(obj, name, H5P_DEFAULT)) < 0)
        return -1;
    space = H5Aget_space(a);
    type = H5Aget_type(a);
    count = space >= 0 ? H5Sget_simple_extent_npoints(space) : -1;
    if (type >= 0 && count > 0 && (H5Tget_class(type) == H5T_FLOAT || H5Tget_class(type) == H5T_INTEGER)) {
        *v = malloc((size_t)count * sizeof **v);
        if (*v && H5Aread(a, H5T_NATIVE_DOUBLE, *v) >= 0) {
            *n = (size_t)count;
            rc = 0;
        }
    }
    if (rc != 0) {
        free(*v);
        *v = NULL;
    }
    if (type >= 0)
        H5Tclose(type);
    if (space >= 0)
        H5Sclose(space);
    H5Aclose(a);
    return rc;
}

int plot_h5_attr_double(hid_t obj, const char *name, double *v)
{
    double *d;
    size_t n;
    if (plot_h5_attr_doubles(obj, name, &d, &n) != 0)
        return -1;
    *v = d[0];
    free(d);
    return 0;
}

/* Strings are read with the attribute's own type: HDF5 will not convert UTF-8 to ASCII. */
char *plot_h5_attr_string(hid_t obj, const char *name)
{
    hid_t a, type = -1, space = -1;
    char *s = NULL;
    if (H5Aexists(obj, name) <= 0 || (a = H5Aopen(obj, name, H5P_DEFAULT)) < 0)
        return NULL;
    type = H5Aget_type(a);
    space = H5Aget_space(a);
    if (type >= 0 && space >= 0 && H5Tget_class(type) == H5T_STRING && H5Sget_simple_extent_npoints(space) == 1) {
        if (H5Tis_variable_str(type) > 0) {
            char *vs = NULL;
            if (H5Aread(a, type, &vs) >= 0 && vs) {
                s = malloc(strlen(vs) + 1);
                if (s)
                    strcpy(s, vs);
                H5free_memory(vs);
            }
        } else {
            size_t size = H5Tget_size(type);
            s = calloc(size + 1, 1);
            if (s && H5Aread(a, type, s) < 0) {
                free(s);
                s = NULL;
            }
        }
    }
    if (space >= 0)
        H5Sclose(space);
    if (type >= 0)
        H5Tclose(type);
    H5Aclose(a);
    return s;
}

/* A rank-1 dataset of variable-length strings, read with its own type (UTF-8 stays UTF-8). */
int plot_h5_read_strings(hid_t loc, const char *path, char ***out, size_t *n)
{
    hid_t d = H5Dopen2(loc, path, H5P_DEFAULT), type = -1, space = -1;
    char **raw = NULL, **copy = NULL;
    hssize_t count = -1;
    size_t i;
    int ok = 0;
    *out = NULL;
    *n = 0;
    if (d < 0)
        return -1;
    type = H5Dget_type(d);
    space = H5Dget_space(d);
    if (type >= 0 && space >= 0 && H5Tget_class(type) == H5T_STRING && H5Tis_variable_str(type) > 0)
        count = H5Sget_simple_extent_npoints(space);
    if (count >= 0 && (raw = calloc((size_t)count + 1, sizeof *raw)) &&
        (copy = calloc((size_t)count + 1, sizeof *copy)))
        ok = H5Dread(d, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, raw) >= 0;
    for (i = 0; ok && i < (size_t)count; i++) {
        const char *s = raw[i] ? raw[i] : "";
        ok = (copy[i] = malloc(strlen(s) + 1)) != NULL;
        if (ok)
            strcpy(copy[i], s);
    }
    for (i = 0; raw && count > 0 && i < (size_t)count; i++)
        H5free_memory(raw[i]);
    free(raw);
    if (ok) {
        *out = copy;
        *n = (size_t)count;
    } else {
        plot_strings_free(copy, count > 0 ? (size_t)count : 0);
    }
    H5Sclose(space);
    H5Tclose(type);
    H5Dclose(d);
    return ok ? 0 : -1;
}

void plot_strings_free(char **s, size_t n)
{
    size_t i;
    for (i = 0; s && i < n; i++)
        free(s[i]);
    free(s);
}
