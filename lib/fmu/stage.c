/*
 * td_fmu_stage (touchdown/fmu.h): the unpacked FMU of a case, everything but binaries/, written into
 * an empty directory: modelDescription.xml (FMI 2.0 co-simulation, fmi2ModelDescription.xsd) and
 * resources/ in the format of fmu_internal.h. The FMU's guid is a hash of what the binary reads
 * (make_guid), so the same case staged twice, from wherever, gives the same bytes, and the binary
 * refuses resources that are not the ones its modelDescription names.
 */
#include "fmu/fmu_internal.h"
#include "touchdown/version.h"
#include "util/error_internal.h"
#include "util/text.h"

#include <dirent.h>
#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* A C identifier (FMI 2.0, 2.2.1: modelIdentifier is the binary's file name and the prefix of its
 * functions) short enough for the settings. */
static int c_identifier(const char *s)
{
    size_t i;
    if (!s || !(s[0] == '_' || (s[0] >= 'a' && s[0] <= 'z') || (s[0] >= 'A' && s[0] <= 'Z')))
        return 0;
    for (i = 0; s[i]; i++)
        if (!(s[i] == '_' || (s[i] >= 'a' && s[i] <= 'z') || (s[i] >= 'A' && s[i] <= 'Z') ||
              (s[i] >= '0' && s[i] <= '9')))
            return 0;
    return i < TD_FMU_NAME_SIZE;
}

/* TD_OK when dir is an existing directory with nothing in it. */
static td_status empty_dir(const char *dir, td_error *err)
{
    struct dirent *e;
    td_status st = TD_OK;
    DIR *d = opendir(dir);
    if (!d)
        return td_error_set(err, TD_ERR_IO, "%s: cannot open the FMU's directory: %s", dir, strerror(errno));
    while (st == TD_OK && (e = readdir(d)))
        if (strcmp(e->d_name, ".") != 0 && strcmp(e->d_name, "..") != 0) /* the entry lives until closedir */
            st = td_error_set(err, TD_ERR_IO, "%s: the FMU's directory is not empty (%s)", dir, e->d_name);
    closedir(d);
    return st;
}

/* 64-bit FNV-1a of s, continued from h. */
static uint64_t fnv(uint64_t h, const char *s)
{
    for (; *s; s++) {
        h ^= (unsigned char)*s;
        h *= 1099511628211ULL;
    }
    return h ^ 0xff; /* a separator, so that "ab" + "c" and "a" + "bc" differ */
}

/* The guid, "{8-4-4-4-12}" hex digits, of what the binary will read: the staged case text (no path of
 * the machine that staged it), the overrides, the inputs, the identifier, the version and the
 * plug-in libraries' fingerprint fp (their bytes hashed, plugins.c; not their paths). */
static void make_guid(char *buf, size_t n, const char *text, const char *const *ov, int nov, td_fmu_inputs inputs,
                      const char *id, const char *fp)
{
    uint64_t h[2] = {14695981039346656037ULL, 0x6c62272e07bb0142ULL};
    int j, i;
    for (j = 0; j < 2; j++) {
        h[j] = fnv(fnv(fnv(fnv(h[j], TD_VERSION), td_fmu_inputs_name(inputs)), id), text);
        for (i = 0; i < nov; i++)
            h[j] = fnv(h[j], ov[i]);
        if (fp[0])
            h[j] = fnv(h[j], fp);
    }
    snprintf(buf, n, "{%08lx-%04lx-%04lx-%04lx-%012llx}", (unsigned long)(h[0] >> 32),
             (unsigned long)((h[0] >> 16) & 0xffff), (unsigned long)(h[0] & 0xffff), (unsigned long)(h[1] >> 48),
             (unsigned long long)(h[1] & 0xffffffffffffULL));
}

/* The case text (td_case_text) into t without the paths its @include markers name the files by as
 * opened ('# >>> @include "rig.cfg" (/where/it/was/rig.cfg)' keeps '# >>> @include "rig.cfg"'): the
 * FMU carries nothing of the machine it was staged on, and the same case staged from elsewhere gives
 * the same bytes. */
static void case_text(td_text *t, const char *text)
{
    static const char marker[] = "# >>> @include \"";
    const char *line = text;
    while (*line) {
        const char *end = strchr(line, '\n'), *q;
        size_t n = end ? (size_t)(end - line) : strlen(line);
        if (strncmp(line, marker, sizeof marker - 1) == 0) {
            for (q = line + sizeof marker - 1; q < line + n && *q != '"'; q++)
                if (*q == '\\' && q + 1 < line + n)
                    q++; /* an escaped character of the name */
            if (q < line + n)
                n = (size_t)(q + 1 - line);
        }
        td_text_append(t, line, n);
        td_text_append(t, "\n", 1);
        line = end ? end + 1 : line + n;
    }
}

/* Write `text` into the file `path`; TD_ERR_IO naming it. */
static td_status write_file(const char *path, const td_text *text, td_error *err)
{
    FILE *f;
    int ok;
    if (text->failed || !text->data)
        return td_error_set(err, TD_ERR_NOMEM, "out of memory writing %s", path);
    if (!(f = fopen(path, "wx")))
        return td_error_set(err, TD_ERR_IO, "%s: cannot create: %s", path, strerror(errno));
    ok = fwrite(text->data, 1, text->len, f) == text->len;
    ok = (fclose(f) == 0) && ok;
    return ok ? TD_OK : td_error_set(err, TD_ERR_IO, "%s: cannot write: %s", path, strerror(errno));
}

static void settings_text(td_text *t, const char *guid, const char *id, td_fmu_inputs inputs, const char *const *ov,
                          int nov)
{
    int i;
    td_text_printf(t, "# The settings of a touchdown FMU, read by its binary at instantiation.\n");
    td_text_printf(t, "format = %d;\ntouchdown = \"%s\";\nguid = \"%s\";\n", TD_FMU_FORMAT, TD_VERSION, guid);
    td_text_printf(t, "model_identifier = \"%s\";\ncase = \"%s\";\ninputs = \"%s\";\noverrides = (", id,
                   TD_FMU_CASE_FILE, td_fmu_inputs_name(inputs));
    for (i = 0; i < nov; i++) {
        td_text_printf(t, "%s\n    ", i ? "," : "");
        td_fmu_config_string(t, ov[i]);
    }
    td_text_printf(t, "%s);\n", nov ? "\n" : "");
}

/* Write into dir the case text, the settings and modelDescription.xml, with guid of those and the
 * plug-in libraries' fingerprint fp ("" for none: the guid of a case without plug-ins is unchanged). */
static td_status write_staged(const td_case *c, const char *const *ov, int nov, td_fmu_inputs inputs, const char *id,
                              const char *fp, const char *dir, td_error *err)
{
    td_text t = {NULL, 0, 0, 0, 0};
    char guid[64], *path = NULL;
    size_t n = strlen(dir) + 64;
    td_status st;
    case_text(&t, td_case_text(c));
    if (t.failed || !(path = malloc(n))) {
        free(t.data);
        return td_error_set(err, TD_ERR_NOMEM, "out of memory staging an FMU");
    }
    make_guid(guid, sizeof guid, t.data, ov, nov, inputs, id, fp);
    snprintf(path, n, "%s/resources/%s", dir, TD_FMU_CASE_FILE);
    st = write_file(path, &t, err);
    free(t.data);
    t = (td_text){NULL, 0, 0, 0, 0};
    if (st == TD_OK) {
        snprintf(path, n, "%s/resources/%s", dir, TD_FMU_SETTINGS_FILE);
        settings_text(&t, guid, id, inputs, ov, nov);
        st = write_file(path, &t, err);
        free(t.data);
        t = (td_text){NULL, 0, 0, 0, 0};
    }
    if (st == TD_OK) {
        snprintf(path, n, "%s/modelDescription.xml", dir);
        st = td_fmu_model_description(c, inputs, id, guid, &t, err);
        st = st == TD_OK ? write_file(path, &t, err) : st;
        free(t.data);
    }
    free(path);
    return st;
}

/* Write the FMU's resources/ (the plug-in libraries the case loads among them) and
 * modelDescription.xml from the loaded case; the binary gets the user's overrides, then those that
 * point its plug-in controllers at the copies. */
static td_status stage_case(const td_case *c, const char *const *ov, int nov, td_fmu_inputs inputs, const char *id,
                            const char *dir, td_error *err)
{
    td_fmu_plugins pl;
    const char **all = NULL;
    char *path;
    int i;
    td_status st;
    if (!(path = malloc(strlen(dir) + 16)))
        return td_error_set(err, TD_ERR_NOMEM, "out of memory staging an FMU");
    sprintf(path, "%s/resources", dir);
    if (mkdir(path, 0777) != 0) {
        st = td_error_set(err, TD_ERR_IO, "%s: cannot create: %s", path, strerror(errno));
        free(path);
        return st;
    }
    st = td_fmu_plugins_stage(c, path, &pl, err);
    if (st == TD_OK && !(all = malloc((size_t)(nov + pl.n + 1) * sizeof *all)))
        st = td_error_set(err, TD_ERR_NOMEM, "out of memory staging an FMU");
    if (st == TD_OK) {
        for (i = 0; i < nov; i++)
            all[i] = ov[i];
        for (i = 0; i < pl.n; i++)
            all[nov + i] = pl.overrides[i];
        st = write_staged(c, all, nov + pl.n, inputs, id, pl.fingerprint.data ? pl.fingerprint.data : "", dir, err);
    }
    free(all);
    td_fmu_plugins_free(&pl);
    free(path);
    return st;
}

td_status td_fmu_stage(const char *case_path, const char *const *overrides, int n_overrides, td_fmu_inputs inputs,
                       const char *model_identifier, const char *dir, td_error *err)
{
    td_case *c = NULL;
    td_status st;
    if (!case_path || !dir || n_overrides < 0 || (n_overrides > 0 && !overrides))
        return td_error_set(err, TD_ERR_INVALID, "td_fmu_stage: NULL argument");
    if (!td_fmu_inputs_name(inputs))
        return td_error_set(err, TD_ERR_INVALID, "td_fmu_stage: inputs %d is not none, current or force", (int)inputs);
    if (!c_identifier(model_identifier))
        return td_error_set(
            err, TD_ERR_INVALID,
            "the model identifier '%.100s' is no C identifier (a letter or '_', then letters, digits or "
            "'_', at most %d)",
            model_identifier ? model_identifier : "", TD_FMU_NAME_SIZE - 1);
    if ((st = empty_dir(dir, err)) != TD_OK)
        return st;
    if ((st = td_case_load(case_path, overrides, n_overrides, &c, err)) != TD_OK)
        return st;
    if ((st = td_fmu_check_start(c, inputs, err)) == TD_OK)
        st = stage_case(c, overrides, n_overrides, inputs, model_identifier, dir, err);
    td_case_free(&c);
    return st;
}
