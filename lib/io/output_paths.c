/*
 * td_output_check_paths and td_modal_check_paths: the output files of a run or a modal analysis
 * checked against each other and against the inputs before anything is computed, so neither can
 * overwrite its own case file, write two results into one file, or find out only at the end that
 * it cannot write its results.
 *
 * Two paths name the same file when both exist and have the same device and inode (hard links,
 * symbolic links, "a/../b" all resolve), or when neither exists and they have the same base name
 * in the same directory (the directory compared by device and inode: a normalised path that also
 * sees through links). Every output's directory must exist, so it always has an identity.
 */
#include "io/writer_internal.h"
#include "touchdown/modal_output.h"
#include "touchdown/options.h"
#include "util/error_internal.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static const char reserved_suffix[] = TD_IO_TEMP_SUFFIX;

/* Where a path points: the file itself when it exists, else its directory and base name. */
typedef struct path_id {
    const char *path;
    const char *what; /* "the HDF5 output", "the case file", ... */
    int exists;
    dev_t dev; /* of the file, or of its directory when it does not exist */
    ino_t ino;
    const char *base; /* the base name (within path) */
    size_t base_len;
} path_id;

/* The directory part of `path` ("." when none, "/" for "/name"), malloc'ed; NULL: no memory. */
static char *dir_of(const char *path)
{
    const char *slash = strrchr(path, '/');
    size_t n = !slash ? 1 : slash == path ? 1 : (size_t)(slash - path);
    char *dir = malloc(n + 1);
    if (dir) {
        memcpy(dir, slash ? path : ".", n);
        dir[n] = '\0';
    }
    return dir;
}

/* An output's directory must exist and take new files (the temporary file, the rename). */
static td_status check_dir(const char *path, const char *what, const char *dir, td_error *err)
{
    struct stat sb;
    if (stat(dir, &sb) != 0 || !S_ISDIR(sb.st_mode))
        return td_error_set(err, TD_ERR_INVALID, "%s: the directory of the %s (%s) does not exist", path, what, dir);
    if (access(dir, W_OK | X_OK) != 0)
        return td_error_set(err, TD_ERR_INVALID, "%s: the directory of the %s (%s) is not writable: %s", path, what,
                            dir, strerror(errno));
    return TD_OK;
}

/* Fill `id` for `path`; an output must be a regular file or absent, in a writable directory,
 * and not be named like a temporary file. */
static td_status identify(const char *path, const char *what, int is_output, path_id *id, td_error *err)
{
    const char *slash = strrchr(path, '/');
    size_t len = strlen(path);
    struct stat sb;
    char *dir;
    td_status st = TD_OK;
    memset(id, 0, sizeof *id);
    id->path = path;
    id->what = what;
    id->base = slash ? slash + 1 : path;
    id->base_len = strlen(id->base);
    if (is_output && len >= sizeof reserved_suffix - 1 &&
        strcmp(path + len - (sizeof reserved_suffix - 1), reserved_suffix) == 0)
        return td_error_set(err, TD_ERR_INVALID, "%s: the %s may not end in \"%s\" (the name of temporary files)", path,
                            what, reserved_suffix);
    if (stat(path, &sb) == 0) {
        if (is_output && !S_ISREG(sb.st_mode))
            return td_error_set(err, TD_ERR_INVALID, "%s: the %s exists and is not a regular file", path, what);
        id->exists = 1;
        id->dev = sb.st_dev;
        id->ino = sb.st_ino;
    } else if (id->base_len == 0) {
        return td_error_set(err, TD_ERR_INVALID, "%s: the %s names a directory, not a file", path, what);
    }
    if (!is_output && id->exists)
        return TD_OK;
    if (!(dir = dir_of(path)))
        return td_error_set(err, TD_ERR_NOMEM, "out of memory checking %s", path);
    if (is_output)
        st = check_dir(path, what, dir, err);
    if (st == TD_OK && !id->exists) {
        if (stat(dir, &sb) == 0) {
            id->dev = sb.st_dev;
            id->ino = sb.st_ino;
        } else {
            id->base_len = 0; /* an input that is gone and has no directory matches nothing */
        }
    }
    free(dir);
    return st;
}

static int same_file(const path_id *a, const path_id *b)
{
    if (a->exists != b->exists || a->dev != b->dev || a->ino != b->ino)
        return 0;
    return a->exists || (a->base_len > 0 && a->base_len == b->base_len && memcmp(a->base, b->base, a->base_len) == 0);
}

/* ids[0 .. n_out-1] are outputs, the rest inputs: refuse any output that is another output or an
 * input. */
static td_status check_pairs(const path_id *ids, int n_out, int n, td_error *err)
{
    int i, j;
    for (i = 0; i < n_out; i++)
        for (j = i + 1; j < n; j++)
            if (same_file(&ids[i], &ids[j]))
                return td_error_set(err, TD_ERR_INVALID, "%s: the %s is the same file as the %s (%s)%s", ids[i].path,
                                    ids[i].what, ids[j].what, ids[j].path,
                                    j >= n_out ? ": an input is never overwritten" : "");
    return TD_OK;
}

/* Identify the n_out outputs `outs` (named `whats`) and the inputs, then refuse collisions. */
static td_status check_all(const char *const *outs, const char *const *whats, int n_out, const char *const *inputs,
                           int n_inputs, td_error *err)
{
    path_id *ids = malloc((size_t)(n_out + n_inputs > 0 ? n_out + n_inputs : 1) * sizeof *ids);
    td_status st = TD_OK;
    int i;
    if (!ids)
        return td_error_set(err, TD_ERR_NOMEM, "out of memory checking the output paths");
    for (i = 0; st == TD_OK && i < n_out; i++)
        st = identify(outs[i], whats[i], 1, &ids[i], err);
    for (i = 0; st == TD_OK && i < n_inputs; i++)
        st =
            identify(inputs[i], i == 0 ? "case file" : "input file of the case (an @include file or a record it reads)",
                     0, &ids[n_out + i], err);
    if (st == TD_OK)
        st = check_pairs(ids, n_out, n_out + n_inputs, err);
    free(ids);
    return st;
}

/* The file at `path` into files[n], `what` it is; returns n + 1. */
static int add_file(td_output_file *files, int n, const char *path, const char *what)
{
    snprintf(files[n].path, sizeof files[n].path, "%s", path);
    files[n].what = what;
    return n + 1;
}

int td_output_files(const td_output_options *out, td_output_file files[TD_OUTPUT_FILES])
{
    int n = 0;
    if (!out || !files || !memchr(out->hdf5_path, '\0', sizeof out->hdf5_path) ||
        !memchr(out->csv_path, '\0', sizeof out->csv_path))
        return -1;
    if (out->hdf5_path[0])
        n = add_file(files, n, out->hdf5_path, "HDF5 output");
    if (out->csv_path[0]) { /* the companions fit: the path is shorter than TD_OUTPUT_PATH_SIZE */
        n = add_file(files, n, out->csv_path, "CSV output");
        td_writer_events_path(out->csv_path, files[n].path, sizeof files[n].path);
        files[n++].what = "CSV events output";
        td_writer_windows_path(out->csv_path, files[n].path, sizeof files[n].path); /* long runs */
        files[n++].what = "CSV window output";
    }
    return n;
}

td_status td_output_check_paths(const td_output_options *out, const char *const *inputs, int n_inputs, td_error *err)
{
    td_output_file files[TD_OUTPUT_FILES];
    const char *outs[TD_OUTPUT_FILES], *whats[TD_OUTPUT_FILES];
    int i, n_out;
    if (!out || n_inputs < 0 || (n_inputs > 0 && !inputs))
        return td_error_set(err, TD_ERR_INVALID, "td_output_check_paths: NULL argument");
    if ((n_out = td_output_files(out, files)) < 0)
        return td_error_set(err, TD_ERR_INVALID, "td_output_check_paths: output path not NUL-terminated");
    for (i = 0; i < n_out; i++) {
        outs[i] = files[i].path;
        whats[i] = files[i].what;
    }
    return check_all(outs, whats, n_out, inputs, n_inputs, err);
}

int td_output_same_file(const char *a, const char *b)
{
    path_id ia, ib;
    td_error err;
    if (!a || !b || !a[0] || !b[0])
        return 0;
    td_error_clear(&err);
    if (identify(a, "file", 0, &ia, &err) != TD_OK || identify(b, "file", 0, &ib, &err) != TD_OK)
        return 0;
    return same_file(&ia, &ib);
}

td_status td_modal_check_paths(const char *csv_path, const char *hdf5_path, const char *const *inputs, int n_inputs,
                               td_error *err)
{
    const char *outs[2], *whats[2];
    int n_out = 0;
    if (n_inputs < 0 || (n_inputs > 0 && !inputs))
        return td_error_set(err, TD_ERR_INVALID, "td_modal_check_paths: NULL argument");
    if (hdf5_path && hdf5_path[0]) {
        outs[n_out] = hdf5_path;
        whats[n_out++] = "HDF5 output";
    }
    if (csv_path && csv_path[0]) {
        outs[n_out] = csv_path;
        whats[n_out++] = "CSV output";
    }
    return check_all(outs, whats, n_out, inputs, n_inputs, err);
}
