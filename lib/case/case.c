/*
 * td_case_load: read the case file, let libconfig 1.5 parse it (with @include relative to the
 * file's directory), apply the --set overrides, then read every section into a td_model and the
 * option structs. Each step stops at the first error with a "FILE:LINE: KEY: what" message.
 */
#include "case/case_schema.h"
#include "util/error_internal.h"

#include <stdlib.h>
#include <string.h>

static char *dup_string(const char *s, size_t n)
{
    char *p = malloc(n + 1);
    if (p) {
        memcpy(p, s, n);
        p[n] = '\0';
    }
    return p;
}

/* "dir/paper-a.cfg" -> "paper-a" */
static char *base_name(const char *path)
{
    const char *slash = strrchr(path, '/');
    const char *base = slash ? slash + 1 : path;
    size_t n = strlen(base);
    if (n > 4 && strcmp(base + n - 4, ".cfg") == 0)
        n -= 4;
    return dup_string(base, n);
}

/* The include directory: the case file's directory ("." when the path has none). */
static td_status set_dir(td_case_reader *r)
{
    const char *slash = strrchr(r->path, '/');
    r->has_dir = slash != NULL;
    r->dir = slash ? dup_string(r->path, slash == r->path ? 1 : (size_t)(slash - r->path)) : dup_string(".", 1);
    r->dir_shown = r->dir ? td_cr_printable_dup(r->dir) : NULL;
    return r->dir_shown ? TD_OK : td_cr_fail_file(r->err, TD_ERR_NOMEM, r->path_shown, 0, "out of memory");
}

static td_status syntax_error(td_case_reader *r)
{
    char shown[1024];
    const char *text = config_error_text(&r->cfg) ? config_error_text(&r->cfg) : "parse error";
    int line = config_error_line(&r->cfg);
    td_cr_file_shown(r, config_error_file(&r->cfg), shown, sizeof shown);
    if (strcmp(text, "cannot open include file") == 0)
        return td_cr_fail_file(r->err, TD_ERR_PARSE, shown, line, "%s (@include paths are relative to %s)", text,
                               r->dir_shown);
    return td_cr_fail_file(r->err, TD_ERR_PARSE, shown, line, "%s", text);
}

static int is_number(const config_setting_t *s)
{
    int t = config_setting_type(s);
    return t == CONFIG_TYPE_INT || t == CONFIG_TYPE_INT64 || t == CONFIG_TYPE_FLOAT;
}

static int same_file(const config_setting_t *s, const char *file)
{
    const char *f = config_setting_source_file(s);
    return (!f && !file) || (f && file && strcmp(f, file) == 0);
}

/* The number setting written as the (*ordinal)-th number (from 0) on file:line, searched under s in
 * the order of the text; *ordinal counts down the numbers of that line passed on the way. */
static const config_setting_t *find_number_at(const config_setting_t *s, const char *file, int line, int *ordinal)
{
    int i;
    if (is_number(s) && (int)config_setting_source_line(s) == line && same_file(s, file) && (*ordinal)-- == 0)
        return s;
    if (config_setting_is_aggregate(s))
        for (i = 0; i < config_setting_length(s); i++) {
            const config_setting_t *hit = find_number_at(config_setting_get_elem(s, (unsigned)i), file, line, ordinal);
            if (hit)
                return hit;
        }
    return NULL;
}

/* Report the first integer literal that libconfig wrapped to 32 bits. */
static td_status check_wraps(td_case_reader *r)
{
    const td_cr_wrap_site *w;
    const config_setting_t *s;
    char shown[1024];
    int ordinal;
    if (r->wrap_count == 0)
        return TD_OK;
    w = &r->wraps[0];
    ordinal = w->ordinal;
    s = find_number_at(config_root_setting(&r->cfg), w->file, w->line, &ordinal);
    if (s && config_setting_type(s) == CONFIG_TYPE_INT)
        return td_cr_fail(r, s, NULL, "integer %s is out of range (at most 2147483647; libconfig would read %d)",
                          w->literal, config_setting_get_int(s));
    td_cr_file_shown(r, w->file, shown, sizeof shown);
    return td_cr_fail_file(r->err, TD_ERR_PARSE, shown, w->line, "integer %s is out of range (at most 2147483647)",
                           w->literal);
}

static td_case *case_new(const char *path)
{
    td_case *c = calloc(1, sizeof *c);
    if (!c)
        return NULL;
    td_sim_options_default(&c->sim);
    td_output_options_default(&c->output);
    td_modal_options_default(&c->modal);
    c->path = dup_string(path, strlen(path));
    c->name = base_name(path);
    if (!c->path || !c->name || td_cr_record_file(c, path) != TD_OK || td_model_create(&c->model, NULL) != TD_OK)
        td_case_free(&c);
    return c;
}

/* Finish the case text: a final newline, then the overrides as comment lines; hands it to the case. */
static td_status finish_text(td_case_reader *r, td_text *buf, const char *const *ov, int n)
{
    int i;
    if (buf->len > 0 && buf->data[buf->len - 1] != '\n')
        td_text_append(buf, "\n", 1);
    if (n > 0)
        td_text_printf(buf, "%s\n", TD_CASE_TEXT_OVERRIDES);
    for (i = 0; i < n; i++) {
        td_text_append(buf, TD_CASE_TEXT_SET, strlen(TD_CASE_TEXT_SET));
        td_text_append(buf, ov[i], strlen(ov[i])); /* one line: checked by td_cr_apply_override */
        td_text_append(buf, "\n", 1);
    }
    if (!buf->data)
        td_text_append(buf, "", 0);
    if (buf->failed)
        return td_cr_fail_file(r->err, TD_ERR_NOMEM, r->path_shown, 0, "out of memory");
    r->c->text = buf->data;
    buf->data = NULL;
    return TD_OK;
}

/* shaft.refine: the model replaced by its refinement, the output nodes renumbered with it (every
 * node number in the case is one of the shaft as written, node i now being node refine * i). */
static td_status apply_refine(td_case_reader *r)
{
    td_model *fine = NULL;
    td_error merr;
    int i;
    if (r->refine == 1)
        return TD_OK;
    if (td_model_refine(r->c->model, r->refine, &fine, &merr) != TD_OK)
        return td_cr_fail_file(r->err, merr.code, r->path_shown, 0, "shaft.refine: %s", merr.message);
    td_model_free(&r->c->model);
    r->c->model = fine;
    for (i = 0; i < r->c->output.node_count; i++)
        r->c->output.nodes[i] *= r->refine;
    for (i = 0; i < r->c->modal.response_node_count; i++)
        r->c->modal.response_nodes[i] *= r->refine;
    return TD_OK;
}

/* Every section by the top level's table (its order: the shaft fixes the nodes, AMBs come before
 * retainers), then the model's cross checks and the refinement. */
static td_status read_case(td_case_reader *r)
{
    td_error merr;
    td_status st = td_cs_read(r, config_root_setting(&r->cfg), &td_cs_root, r->c);
    /* the model's cross checks (nodes on the shaft, one AMB and one retainer per node, retainers
     * tighter than the air gaps, schedule indices), reported at the settings they name */
    if (st == TD_OK && td_model_validate(r->c->model, &merr) != TD_OK)
        st = td_cr_validate_fail(r, &merr);
    if (st == TD_OK)
        st = apply_refine(r);
    return st;
}

/* libconfig 1.5 rejects a last line that is a comment without a final newline ("syntax error":
 * its comment pattern needs the newline), so the text it parses always ends with one. Line
 * numbers do not change. */
static td_status end_with_newline(td_case_reader *r, char **text)
{
    size_t n = strlen(*text);
    char *p;
    if (n == 0 || (*text)[n - 1] == '\n')
        return TD_OK;
    p = realloc(*text, n + 2);
    if (!p)
        return td_cr_fail_file(r->err, TD_ERR_NOMEM, r->path_shown, 0, "out of memory");
    p[n] = '\n';
    p[n + 1] = '\0';
    *text = p;
    return TD_OK;
}

/* Bytes libconfig 1.5 may allocate per setting, allocator overhead included: about 80 measured
 * (peak RSS of 'touchdown info' on a 199000-entry array), with room to spare. */
#define TD_CR_SETTING_BYTES 256

/* libconfig 1.5 does not check its allocations: out of memory inside config_read_string is a
 * crash, not an error. The shape counted by td_cr_expand bounds what it will allocate, so ask
 * for that much first (and give it back) to fail with a message while we still can. */
static td_status probe_memory(td_case_reader *r, size_t text_bytes)
{
    size_t need = (size_t)r->shape.settings * TD_CR_SETTING_BYTES + 2 * text_bytes;
    void *p = malloc(need);
    if (!p)
        return td_cr_fail_file(r->err, TD_ERR_NOMEM, r->path_shown, 0,
                               "out of memory: parsing %ld settings needs about %lu bytes", r->shape.settings,
                               (unsigned long)need);
    free(p);
    return TD_OK;
}

static td_status load(td_case_reader *r, const char *const *overrides, int n_overrides)
{
    char *main_text = NULL;
    td_text text = {NULL, 0, 0, 0, 0};
    int i;
    td_status st = set_dir(r);
    if (st == TD_OK)
        st = td_cr_read_file("case file", r->path_shown, r->path, &main_text, r->err);
    if (st == TD_OK) {
        r->bytes = strlen(main_text);
        st = td_cr_expand(r, main_text, NULL, 0, &text);
    }
    if (st == TD_OK)
        st = end_with_newline(r, &main_text);
    if (st != TD_OK) {
        free(main_text);
        free(text.data);
        return st;
    }
    if (st == TD_OK)
        st = probe_memory(r, strlen(main_text));
    if (st != TD_OK) {
        free(main_text);
        free(text.data);
        return st;
    }
    config_init(&r->cfg);
    config_set_include_dir(&r->cfg, r->dir);
    /* parse the text already read (no second open); settings of the main file have no file name */
    if (!config_read_string(&r->cfg, main_text))
        st = syntax_error(r);
    free(main_text);
    if (st == TD_OK)
        st = check_wraps(r);
    if (st == TD_OK && config_setting_length(config_root_setting(&r->cfg)) == 0)
        st = td_cr_fail_file(r->err, TD_ERR_PARSE, r->path_shown, 1, "the case file is empty (no settings)");
    if (st == TD_OK)
        st = td_cr_apply_file_overrides(r);
    for (i = 0; st == TD_OK && i < n_overrides; i++)
        st = td_cr_apply_override(r, overrides[i]);
    if (st == TD_OK)
        st = read_case(r);
    if (st == TD_OK)
        st = finish_text(r, &text, overrides, n_overrides);
    free(text.data);
    config_destroy(&r->cfg);
    return st;
}

td_status td_case_load(const char *path, const char *const *overrides, int n_overrides, td_case **out, td_error *err)
{
    td_case_reader r;
    td_status st;
    int i;
    if (!out)
        return td_error_set(err, TD_ERR_INVALID, "td_case_load: NULL output pointer");
    *out = NULL;
    if (!path || n_overrides < 0 || (n_overrides > 0 && !overrides))
        return td_error_set(err, TD_ERR_INVALID, "td_case_load: NULL path, or bad override array");
    if (!path[0])
        return td_error_set(err, TD_ERR_IO, "case file path is empty: cannot read the case file");
    memset(&r, 0, sizeof r);
    r.path = path;
    r.err = err;
    r.sets = overrides;
    r.n_sets = n_overrides;
    r.refine = 1;
    r.path_shown = td_cr_printable_dup(path);
    r.c = r.path_shown ? case_new(path) : NULL;
    if (!r.c) {
        free(r.path_shown);
        return td_error_set(err, TD_ERR_NOMEM, "case file: out of memory");
    }
    st = load(&r, overrides, n_overrides);
    for (i = 0; i < r.wrap_count; i++)
        free(r.wraps[i].file);
    free(r.wraps);
    free(r.dir);
    free(r.dir_shown);
    free(r.path_shown);
    if (st != TD_OK) {
        td_case_free(&r.c);
        return st;
    }
    td_error_clear(err);
    *out = r.c;
    return TD_OK;
}

void td_case_free(td_case **c)
{
    if (!c || !*c)
        return;
    td_model_free(&(*c)->model);
    free((*c)->text);
    free((*c)->path);
    free((*c)->name);
    free((*c)->description);
    while ((*c)->file_count > 0)
        free((*c)->files[--(*c)->file_count]);
    free((*c)->files);
    td_cr_free_sweep(*c);
    while ((*c)->controller_count > 0)
        free((char *)(*c)->controllers[--(*c)->controller_count].where);
    free((*c)->controllers);
    free((*c)->history_file); /* housing motion */
    free(*c);
    *c = NULL;
}

const td_model *td_case_model(const td_case *c)
{
    return c ? c->model : NULL;
}
const td_sim_options *td_case_sim_options(const td_case *c)
{
    return c ? &c->sim : NULL;
}
const td_output_options *td_case_output_options(const td_case *c)
{
    return c ? &c->output : NULL;
}
const td_modal_options *td_case_modal_options(const td_case *c)
{
    return c ? &c->modal : NULL;
}
double td_case_end_time(const td_case *c)
{
    return c ? c->end_time : 0.0;
}
const char *td_case_text(const td_case *c)
{
    return c ? c->text : NULL;
}
const char *td_case_path(const td_case *c)
{
    return c ? c->path : NULL;
}
const char *td_case_name(const td_case *c)
{
    return c ? c->name : NULL;
}
const char *const *td_case_files(const td_case *c, int *count)
{
    if (count)
        *count = c ? c->file_count : 0;
    return c ? (const char *const *)c->files : NULL;
}
const char *td_case_housing_history_file(const td_case *c)
{
    return c ? c->history_file : NULL;
}

const char *td_case_description(const td_case *c)
{
    return c && c->description ? c->description : "";
}
int td_case_sweep_specs(const td_case *c)
{
    return c ? c->sweep_count : 0;
}
const char *td_case_sweep_spec(const td_case *c, int i, int *with, const char **where)
{
    if (with)
        *with = c->sweep[i].with;
    if (where)
        *where = c->sweep[i].where;
    return c->sweep[i].spec;
}
td_status td_case_controller(const td_case *c, int i, td_case_controller_info *out)
{
    if (!c || !out || i < 0 || i >= c->controller_count)
        return TD_ERR_INVALID;
    *out = c->controllers[i];
    return TD_OK;
}
