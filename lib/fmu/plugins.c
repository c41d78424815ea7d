/*
 * The plug-in libraries of a staged case (fmu_internal.h): each library a controller of the case
 * loads is copied into resources/plugins/ and the FMU's binary is pointed at the copy by one more
 * td_case_load override, `controllers[i].plugin.library="plugins/NAME"`. An override's relative
 * library path resolves under the case file's directory (lib/case/case_plugin.c), which in the
 * FMU is resources/, so the FMU needs nothing of the machine that staged it. A library keeps its
 * file name; a second, different library of the same name goes into plugins/2/ (then 3/, ...), one
 * used by several controllers is copied once. The fingerprint (the libraries' bytes, hashed, with
 * the names they are staged under) goes into the guid: the same libraries give the same guid
 * wherever they were read from. A housing history file (`housing.history.file`, a CSV the case
 * reads) travels the same way, as resources/history/NAME with `housing.history.file="history/NAME"`.
 */
#include "fmu/fmu_internal.h"
#include "util/error_internal.h"
#include "util/text.h"

#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* One library as staged: its name under resources/ and the hash of its bytes. */
typedef struct staged_lib {
    char name[TD_FMU_PLUGIN_NAME_SIZE];
    uint64_t hash[2];
    long size;
} staged_lib;

/* 64-bit FNV-1a of n bytes, continued from h (two seeds make a 128-bit fingerprint). */
static uint64_t fnv_bytes(uint64_t h, const unsigned char *p, size_t n)
{
    size_t i;
    for (i = 0; i < n; i++) {
        h ^= p[i];
        h *= 1099511628211ULL;
    }
    return h;
}

/* The 128-bit fingerprint of n bytes: FNV-1a from two seeds. */
static void fingerprint_bytes(const unsigned char *data, long n, uint64_t h[2])
{
    h[0] = fnv_bytes(14695981039346656037ULL, data, (size_t)n);
    h[1] = fnv_bytes(0x6c62272e07bb0142ULL, data, (size_t)n);
}

/* The whole file `path` (a `what`: "plug-in library", ...) into *data (free()) and *size; TD_ERR_IO naming it. */
static td_status read_library(const char *path, const char *what, unsigned char **data, long *size, td_error *err)
{
    FILE *f;
    long n = -1;
    *data = NULL;
    errno = 0;
    f = fopen(path, "rb");
    if (f && fseek(f, 0, SEEK_END) == 0 && (n = ftell(f)) >= 0 && fseek(f, 0, SEEK_SET) == 0 &&
        (*data = malloc(n > 0 ? (size_t)n : 1)) != NULL && fread(*data, 1, (size_t)n, f) == (size_t)n) {
        fclose(f);
        *size = n;
        return TD_OK;
    }
    free(*data);
    *data = NULL;
    if (f)
        fclose(f);
    return td_error_set(err, TD_ERR_IO, "%s: cannot read the %s to put it into the FMU: %s", path, what,
                        errno ? strerror(errno) : "short read");
}

/* n bytes into the new file `path` (never over an existing one). */
static td_status write_library(const char *path, const unsigned char *data, long n, td_error *err)
{
    FILE *f = fopen(path, "wbx");
    int ok;
    if (!f)
        return td_error_set(err, TD_ERR_IO, "%s: cannot create: %s", path, strerror(errno));
    ok = fwrite(data, 1, (size_t)n, f) == (size_t)n;
    ok = (fclose(f) == 0) && ok;
    return ok ? TD_OK : td_error_set(err, TD_ERR_IO, "%s: cannot write: %s", path, strerror(errno));
}

/* The name under resources/ of a library with file name `base` and hash h, among the `n` staged:
 * the staged one with the same bytes, else the first free of plugins/BASE, plugins/2/BASE, ...
 * *fresh says whether it is a new one (to be written). */
static void choose_name(const staged_lib *libs, int n, const char *base, const uint64_t h[2], long size,
                        staged_lib *out, int *fresh)
{
    int i, k, taken = 1;
    *fresh = 1;
    for (i = 0; i < n; i++)
        if (libs[i].size == size && libs[i].hash[0] == h[0] && libs[i].hash[1] == h[1]) {
            *out = libs[i];
            *fresh = 0;
            return;
        }
    for (k = 1; taken; k++) {
        if (k == 1)
            snprintf(out->name, sizeof out->name, "plugins/%s", base);
        else
            snprintf(out->name, sizeof out->name, "plugins/%d/%s", k, base);
        for (taken = 0, i = 0; i < n && !taken; i++)
            taken = strcmp(libs[i].name, out->name) == 0;
    }
    out->hash[0] = h[0], out->hash[1] = h[1], out->size = size;
}

/* mkdir of `path` unless it is there already. */
static td_status make_dir(const char *path, td_error *err)
{
    struct stat sb;
    if (mkdir(path, 0777) == 0 || (errno == EEXIST && stat(path, &sb) == 0 && S_ISDIR(sb.st_mode)))
        return TD_OK;
    return td_error_set(err, TD_ERR_IO, "%s: cannot create: %s", path, strerror(errno));
}

/* Write lib (fresh) under resources_dir, with the directories its name needs. */
static td_status put_library(const char *resources_dir, const staged_lib *lib, const unsigned char *data, td_error *err)
{
    char path[4096], *slash;
    td_status st = TD_OK;
    size_t at = (size_t)snprintf(path, sizeof path, "%s/", resources_dir);
    if (snprintf(path, sizeof path, "%s/%s", resources_dir, lib->name) >= (int)sizeof path)
        return td_error_set(err, TD_ERR_IO, "%s: path too long", resources_dir);
    for (slash = strchr(path + at, '/'); st == TD_OK && slash; slash = strchr(slash + 1, '/')) {
        *slash = '\0';
        st = make_dir(path, err);
        *slash = '/';
    }
    return st == TD_OK ? write_library(path, data, lib->size, err) : st;
}

/* The file `path` to stage (a `what`: "plug-in library", "housing history") read into *data and *size,
 * its fingerprint into h and its file name (in path) into *base; TD_ERR_INVALID when that name is too
 * long for its place under resources/. */
static td_status read_staged(const char *path, const char *what, const char **base, unsigned char **data, long *size,
                             uint64_t h[2], td_error *err)
{
    td_status st;
    *base = strrchr(path, '/') ? strrchr(path, '/') + 1 : path;
    if (strlen(*base) + 16 >= TD_FMU_PLUGIN_NAME_SIZE)
        return td_error_set(err, TD_ERR_INVALID, "%s: the %s's file name is too long for an FMU (at most %d)", path,
                            what, TD_FMU_PLUGIN_NAME_SIZE - 17);
    if ((st = read_library(path, what, data, size, err)) != TD_OK)
        return st;
    fingerprint_bytes(*data, *size, h);
    return TD_OK;
}

/* The staged file `name`'s line of the fingerprint: its name, its bytes' hash and its size. */
static void note_fingerprint(td_fmu_plugins *out, const char *name, const uint64_t h[2], long size)
{
    td_text_printf(&out->fingerprint, "%s %016llx%016llx %ld\n", name, (unsigned long long)h[0],
                   (unsigned long long)h[1], size);
}

/* The override `ov` (its key written) completed with the staged file's `name` and kept in out when
 * staging went well (st), else dropped; the status. */
static td_status keep_override(td_fmu_plugins *out, td_text *ov, const char *name, td_status st, td_error *err)
{
    td_fmu_config_string(ov, name);
    if (st == TD_OK && (ov->failed || out->fingerprint.failed))
        st = td_error_set(err, TD_ERR_NOMEM, "out of memory staging an FMU");
    if (st == TD_OK)
        out->overrides[out->n++] = ov->data;
    else
        free(ov->data);
    return st;
}

/* Stage the library of plug-in controller i (path) among the `n` staged so far into libs[n]. */
static td_status stage_one(const char *resources_dir, int i, const char *path, staged_lib *libs, int *n,
                           td_fmu_plugins *out, td_error *err)
{
    unsigned char *data;
    uint64_t h[2];
    long size = 0;
    int fresh;
    char name[TD_FMU_PLUGIN_NAME_SIZE];
    const char *base;
    td_text ov = {NULL, 0, 0, 0, 0};
    td_status st;
    if ((st = read_staged(path, "plug-in library", &base, &data, &size, h, err)) != TD_OK)
        return st;
    choose_name(libs, *n, base, h, size, &libs[*n], &fresh);
    snprintf(name, sizeof name, "%s", libs[*n].name);
    if (fresh && (st = put_library(resources_dir, &libs[*n], data, err)) == TD_OK) {
        note_fingerprint(out, name, h, size);
        (*n)++;
    }
    free(data);
    td_text_printf(&ov, "controllers[%d].plugin.library=", i);
    return keep_override(out, &ov, name, st, err);
}

/* housing motion: the case's housing history file `path` copied to history/NAME (NAME its file name),
 * hashed into the fingerprint as a library is, and the override `housing.history.file="history/NAME"`:
 * a relative history file resolves under the case file's directory (lib/case/case_housing.c),
 * which in the FMU is resources/. */
static td_status stage_history(const char *resources_dir, const char *path, td_fmu_plugins *out, td_error *err)
{
    unsigned char *data;
    staged_lib lib;
    const char *base;
    td_text ov = {NULL, 0, 0, 0, 0};
    td_status st;
    if ((st = read_staged(path, "housing history", &base, &data, &lib.size, lib.hash, err)) != TD_OK)
        return st;
    snprintf(lib.name, sizeof lib.name, "history/%s", base);
    st = put_library(resources_dir, &lib, data, err);
    free(data);
    note_fingerprint(out, lib.name, lib.hash, lib.size);
    td_text_printf(&ov, "housing.history.file=");
    return keep_override(out, &ov, lib.name, st, err);
}

td_status td_fmu_plugins_stage(const td_case *c, const char *resources_dir, td_fmu_plugins *out, td_error *err)
{
    const td_model *m = td_case_model(c);
    const char *history = td_case_housing_history_file(c);
    int i, n_libs = 0, count = td_model_controller_count(m);
    staged_lib *libs;
    td_status st = TD_OK;
    memset(out, 0, sizeof *out);
    if (count < 0)
        count = 0;
    if (count == 0 && !history)
        return TD_OK;
    libs = calloc((size_t)count + 1, sizeof *libs);
    out->overrides = calloc((size_t)count + 1, sizeof *out->overrides); /* one more: the history's */
    if (!libs || !out->overrides) {
        free(libs);
        return td_error_set(err, TD_ERR_NOMEM, "out of memory staging an FMU");
    }
    for (i = 0; st == TD_OK && i < count; i++) {
        const td_plugin_spec *spec = td_model_get_plugin(m, i);
        td_case_controller_info info;
        /* the case's controllers[i] is the model's controller i (td_case_controller) */
        if (spec && spec->library && td_case_controller(c, i, &info) == TD_OK && info.plugin)
            st = stage_one(resources_dir, i, spec->library, libs, &n_libs, out, err);
    }
    free(libs);
    if (st == TD_OK && history) /* housing motion */
        st = stage_history(resources_dir, history, out, err);
    return st;
}

void td_fmu_plugins_free(td_fmu_plugins *p)
{
    int i;
    for (i = 0; i < p->n; i++)
        free(p->overrides[i]);
    free(p->overrides);
    free(p->fingerprint.data);
    memset(p, 0, sizeof *p);
}
