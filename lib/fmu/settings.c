/*
 * The FMU's settings file (resources/touchdown-fmu.cfg, fmu_internal.h) read back by its binary.
 */
#include "fmu/fmu_internal.h"
#include "util/error_internal.h"

#include <libconfig.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static char *join(const char *dir, const char *name)
{
    size_t n = strlen(dir) + strlen(name) + 2;
    char *p = malloc(n);
    if (p)
        snprintf(p, n, "%s/%s", dir, name);
    return p;
}

/* A required string setting into buf, TD_ERR_PARSE naming it when missing or too long. */
static td_status get_string(const config_t *cfg, const char *path, const char *key, char *buf, size_t n, td_error *err)
{
    const char *s;
    if (!config_lookup_string(cfg, key, &s) || strlen(s) >= n)
        return td_error_set(err, TD_ERR_PARSE, "%s: %s: missing, not a string or too long", path, key);
    snprintf(buf, n, "%s", s);
    return TD_OK;
}

static td_status read_overrides(const config_t *cfg, const char *path, td_fmu_settings *out, td_error *err)
{
    config_setting_t *ov = config_lookup(cfg, "overrides");
    int i, n = ov ? config_setting_length(ov) : 0;
    if (!ov || !config_setting_is_list(ov))
        return td_error_set(err, TD_ERR_PARSE, "%s: overrides: missing or not a list", path);
    if (n > 0 && !(out->overrides = calloc((size_t)n, sizeof *out->overrides)))
        return td_error_set(err, TD_ERR_NOMEM, "out of memory reading %s", path);
    for (i = 0; i < n; i++) {
        const char *s = config_setting_get_string_elem(ov, i);
        if (!s)
            return td_error_set(err, TD_ERR_PARSE, "%s: overrides[%d]: not a string", path, i);
        if (!(out->overrides[i] = malloc(strlen(s) + 1)))
            return td_error_set(err, TD_ERR_NOMEM, "out of memory reading %s", path);
        strcpy(out->overrides[i], s);
        out->n_overrides++;
    }
    return TD_OK;
}

static td_status read_settings(const config_t *cfg, const char *path, const char *dir, td_fmu_settings *out,
                               td_error *err)
{
    char name[TD_FMU_NAME_SIZE], inputs[16];
    int format;
    td_status st;
    if (!config_lookup_int(cfg, "format", &format) || format != TD_FMU_FORMAT)
        return td_error_set(err, TD_ERR_PARSE, "%s: format: not %d (staged by another version of touchdown)", path,
                            TD_FMU_FORMAT);
    if ((st = get_string(cfg, path, "guid", out->guid, sizeof out->guid, err)) != TD_OK ||
        (st = get_string(cfg, path, "model_identifier", out->model_identifier, sizeof out->model_identifier, err)) !=
            TD_OK ||
        (st = get_string(cfg, path, "case", name, sizeof name, err)) != TD_OK ||
        (st = get_string(cfg, path, "inputs", inputs, sizeof inputs, err)) != TD_OK)
        return st;
    for (out->inputs = TD_FMU_INPUTS_NONE; out->inputs <= TD_FMU_INPUTS_FORCE; out->inputs++)
        if (strcmp(inputs, td_fmu_inputs_name(out->inputs)) == 0)
            break;
    if (out->inputs > TD_FMU_INPUTS_FORCE)
        return td_error_set(err, TD_ERR_PARSE, "%s: inputs: \"%s\" is not none, current or force", path, inputs);
    if (strchr(name, '/') || !(out->case_path = join(dir, name)))
        return td_error_set(err, strchr(name, '/') ? TD_ERR_PARSE : TD_ERR_NOMEM, "%s: case: not a file of resources/",
                            path);
    return read_overrides(cfg, path, out, err);
}

td_status td_fmu_settings_read(const char *resources_dir, td_fmu_settings *out, td_error *err)
{
    config_t cfg;
    td_status st;
    char *path;
    FILE *f;
    memset(out, 0, sizeof *out);
    if (!(path = join(resources_dir, TD_FMU_SETTINGS_FILE)))
        return td_error_set(err, TD_ERR_NOMEM, "out of memory reading the FMU's settings");
    if (!(f = fopen(path, "r"))) {
        st = td_error_set(err, TD_ERR_IO, "%s: cannot read the FMU's settings", path);
        free(path);
        return st;
    }
    config_init(&cfg);
    if (!config_read(&cfg, f))
        st = td_error_set(err, TD_ERR_PARSE, "%s:%d: %s", path, config_error_line(&cfg), config_error_text(&cfg));
    else
        st = read_settings(&cfg, path, resources_dir, out, err);
    fclose(f);
    config_destroy(&cfg);
    free(path);
    return st;
}

void td_fmu_settings_free(td_fmu_settings *s)
{
    int i;
    for (i = 0; i < s->n_overrides; i++)
        free(s->overrides[i]);
    free(s->overrides);
    free(s->case_path);
    memset(s, 0, sizeof *s);
}

void td_fmu_config_string(td_text *t, const char *s)
{
    td_text_append(t, "\"", 1);
    for (; *s; s++) {
        unsigned char c = (unsigned char)*s;
        if (c == '\\' || c == '"')
            td_text_printf(t, "\\%c", c);
        else if (c < 0x20 || c == 0x7f)
            td_text_printf(t, "\\x%02x", c);
        else
            td_text_append(t, s, 1);
    }
    td_text_append(t, "\"", 1);
}
