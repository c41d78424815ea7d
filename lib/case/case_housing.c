/*
 * The case keys of the housing's prescribed motion (touchdown/housing.h): `housing.reference`, the
 * `housing.shocks` and `housing.rotation` pulses and the `housing.history` record, inline or from a
 * CSV file whose header gives each column's unit. The model checks the values (each rule once,
 * lib/model/housing.c) and names the field; a history point's fault is put back at its entry or at
 * its line of the CSV file here.
 */
#include "case/case_schema.h"
#include "touchdown/dofs.h"
#include "util/error_internal.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

/* TD_CS_ENUM stores an int (case_schema.c): the shape must be int-sized */
typedef char cr_shape_is_int[sizeof(td_pulse_shape) == sizeof(int) ? 1 : -1];

static const char *const shape_names[] = {"half-sine", "triangle", "sawtooth", "versine", "ramp"}; /* td_pulse_shape */

/* A pulse's direction or axis: two finite components (the model normalises them and refuses zero). */
static td_status read_direction(td_case_reader *r, const config_setting_t *g, const td_cs_key *k, void *rec)
{
    td_housing_pulse *p = rec;
    int n = 0;
    td_status st = td_cr_reals(r, g, k->key, 2, TD_CR_FINITE, p->direction, &n);
    if (st == TD_OK && n == 0)
        return td_cr_missing(r, g, k->key, k->what);
    if (st == TD_OK && n != 2)
        return td_cr_fail(r, config_setting_get_member(g, k->key), NULL, "expected two components [x, y], got %d", n);
    return st;
}

static td_status add_shock(td_case_reader *r, const config_setting_t *g, void *rec)
{
    td_error merr;
    td_status st = td_model_add_housing_shock(r->c->model, rec, &merr);
    return st == TD_OK ? TD_OK : td_cr_model_fail(r, g, st, &merr);
}

static td_status add_rotation(td_case_reader *r, const config_setting_t *g, void *rec)
{
    td_error merr;
    td_status st = td_model_add_housing_rotation(r->c->model, rec, &merr);
    /* the model calls the rate its amplitude and the axis its direction */
    if (st != TD_OK && merr.site.field && strcmp(merr.site.field, "amplitude") == 0)
        merr.site.field = "rate";
    else if (st != TD_OK && merr.site.field && strcmp(merr.site.field, "direction") == 0)
        merr.site.field = "axis";
    return st == TD_OK ? TD_OK : td_cr_model_fail(r, g, st, &merr);
}

static const td_cs_key shock_keys[] = {
    {.key = "shape",
     .type = TD_CS_ENUM,
     .offset = offsetof(td_housing_pulse, shape),
     .names = shape_names,
     .name_count = 5,
     .doc = "the pulse: `half-sine` A sin(pi tau/T), `triangle` (symmetric, peak at T/2), `sawtooth` (final peak: "
            "A tau/T, then 0), `versine` (haversine, A (1 - cos(2 pi tau/T))/2), as the shock standards define them; "
            "`ramp`: A tau/T, then held (a steady acceleration); tau = t - start"},
    {.key = "amplitude",
     .type = TD_CS_REAL,
     .offset = offsetof(td_housing_pulse, amplitude),
     .need = TD_CS_REQUIRED,
     .what = "the peak acceleration, m/s^2",
     .rule = TD_CR_POSITIVE,
     .unit = "m/s^2",
     .doc = "peak acceleration A of the housing (1 g = 9.80665 m/s^2)"},
    {.key = "duration",
     .type = TD_CS_REAL,
     .offset = offsetof(td_housing_pulse, duration),
     .need = TD_CS_REQUIRED,
     .what = "the pulse's duration, s",
     .rule = TD_CR_POSITIVE,
     .unit = "s",
     .doc = "duration T; the integrator stops at the pulse's start and end (and at a triangle's peak)"},
    {.key = "start",
     .type = TD_CS_REAL,
     .offset = offsetof(td_housing_pulse, start),
     .rule = TD_CR_NONNEGATIVE,
     .unit = "s",
     .doc = "time the pulse begins"},
    {.key = "direction",
     .type = TD_CS_CUSTOM,
     .read = read_direction,
     .need = TD_CS_REQUIRED,
     .what = "the acceleration's direction [x, y]",
     .doc_type = "array of 2 numbers",
     .doc_range = "not [0, 0]",
     .doc = "direction [x, y] of the housing's acceleration in the x-y plane (gravity's default is [0, -1]: [0, 1] "
            "lifts the housing), normalised to unit length"},
};
const td_cs_table td_cs_housing_shocks = {"housing.shocks[]",       NULL, shock_keys, TD_CS_COUNT(shock_keys),
                                          sizeof(td_housing_pulse), NULL, add_shock};

static const td_cs_key rotation_keys[] = {
    {.key = "shape",
     .type = TD_CS_ENUM,
     .offset = offsetof(td_housing_pulse, shape),
     .names = shape_names,
     .name_count = 5,
     .def = TD_PULSE_RAMP,
     .doc = "the rate's profile: the pulses of `housing.shocks[].shape` but `sawtooth` (a rate that drops at once is "
            "an angular impulse: use `triangle` or `versine`), or `ramp`: a linear rise over `duration`, then held"},
    {.key = "rate",
     .type = TD_CS_REAL,
     .offset = offsetof(td_housing_pulse, amplitude),
     .need = TD_CS_REQUIRED,
     .what = "the peak (or held) rotation rate, rad/s",
     .rule = TD_CR_POSITIVE,
     .unit = "rad/s",
     .doc = "peak (or held) rotation rate of the housing; it loads the spinning rotor through its gyroscopic moments "
            "Ip Omega rate"},
    {.key = "duration",
     .type = TD_CS_REAL,
     .offset = offsetof(td_housing_pulse, duration),
     .need = TD_CS_REQUIRED,
     .what = "the profile's duration, s",
     .rule = TD_CR_POSITIVE,
     .unit = "s",
     .doc = "duration of the pulse, or of the ramp's rise"},
    {.key = "start",
     .type = TD_CS_REAL,
     .offset = offsetof(td_housing_pulse, start),
     .rule = TD_CR_NONNEGATIVE,
     .unit = "s",
     .doc = "time the profile begins"},
    {.key = "axis",
     .type = TD_CS_CUSTOM,
     .read = read_direction,
     .need = TD_CS_REQUIRED,
     .what = "the rotation's axis [x, y]",
     .doc_type = "array of 2 numbers",
     .doc_range = "not [0, 0]",
     .doc = "axis of the rotation in the x-y plane: [1, 0] about x (theta), [0, 1] about y (phi), normalised; a "
            "rotation about the shaft's axis is not modelled"},
};
const td_cs_table td_cs_housing_rotation = {"housing.rotation[]",     NULL, rotation_keys, TD_CS_COUNT(rotation_keys),
                                            sizeof(td_housing_pulse), NULL, add_rotation};

/* ---- the history ------------------------------------------------------------------------------ */

/* `history` as read: the file (NULL: inline), the shift and the factor. */
typedef struct cr_history {
    const char *file;
    double start, scale;
} cr_history;

static void history_preset(void *rec)
{
    ((cr_history *)rec)->scale = 1.0;
}

/* The points read, inline or from the file (line: each point's line in it; NULL inline). */
typedef struct cr_points {
    int n, cap;
    double *t, *x, *y;
    int *line;
} cr_points;

static void points_free(cr_points *p)
{
    free(p->t), free(p->x), free(p->y), free(p->line);
}

/* Room for one more point; 0 when out of memory. */
static int points_grow(cr_points *p)
{
    int cap = p->cap ? 2 * p->cap : 64;
    double *t, *x, *y;
    int *line;
    if (p->n < p->cap)
        return 1;
    if (cap > (1 << 26)) /* far beyond what TD_CASE_MAX_FILE_SIZE can hold */
        return 0;
    t = realloc(p->t, (size_t)cap * sizeof *t);
    p->t = t ? t : p->t;
    x = realloc(p->x, (size_t)cap * sizeof *x);
    p->x = x ? x : p->x;
    y = realloc(p->y, (size_t)cap * sizeof *y);
    p->y = y ? y : p->y;
    line = realloc(p->line, (size_t)cap * sizeof *line);
    p->line = line ? line : p->line;
    if (!t || !x || !y || !line)
        return 0;
    p->cap = cap;
    return 1;
}

/* time, x and y written in the group: three arrays of numbers of one length. */
static td_status read_inline(td_case_reader *r, const config_setting_t *g, cr_points *p)
{
    static const char *const keys[] = {"time", "x", "y"};
    const config_setting_t *s[3];
    double **out[3];
    int k, n[3];
    out[0] = &p->t, out[1] = &p->x, out[2] = &p->y;
    for (k = 0; k < 3; k++) {
        td_status st;
        s[k] = config_setting_get_member(g, keys[k]);
        if (!s[k])
            return td_cr_missing(r, g, keys[k], k == 0 ? "the record's times, s" : "the record's acceleration, m/s^2");
        if (!config_setting_is_array(s[k]) && !config_setting_is_list(s[k]))
            return td_cr_fail(r, s[k], NULL, "expected an array of numbers");
        n[k] = config_setting_length(s[k]);
        *out[k] = malloc((size_t)(n[k] > 0 ? n[k] : 1) * sizeof **out[k]);
        if (!*out[k])
            return td_error_set(r->err, TD_ERR_NOMEM, "%s: out of memory reading housing.history", r->path_shown);
        st = td_cr_reals(r, g, keys[k], n[k], TD_CR_FINITE, *out[k], &n[k]);
        if (st != TD_OK)
            return st;
        if (k > 0 && n[k] != n[0])
            return td_cr_fail_vs(r, s[k], s[0], "has %d entries, `time` has %d", n[k], n[0]);
    }
    p->n = n[0];
    return TD_OK;
}

/* A CSV line split at its commas into at most `max` fields, each trimmed; returns the count (max + 1
 * when there are more). Writes into line. */
static int split_fields(char *line, char **field, int max)
{
    int n = 0;
    char *p = line;
    for (;;) {
        char *comma = strchr(p, ','), *end;
        if (n == max)
            return max + 1;
        if (comma)
            *comma = '\0';
        while (*p == ' ' || *p == '\t')
            p++;
        end = p + strlen(p);
        while (end > p && (end[-1] == ' ' || end[-1] == '\t' || end[-1] == '\r'))
            *--end = '\0';
        field[n++] = p;
        if (!comma)
            return n;
        p = comma + 1;
    }
}

/* The quantity header field f ("NAME [UNIT]") names, case-insensitive: 0 the time (`t`, `time`), 1 the
 * acceleration along x (`ax`, `x`), 2 along y (`ay`, `y`); -1 any other name. */
static int column_quantity(const char *f)
{
    static const char *const names[] = {"t", "time", "ax", "x", "ay", "y"};
    const char *open = strchr(f, '[');
    size_t n = open ? (size_t)(open - f) : strlen(f), k;
    while (n > 0 && (f[n - 1] == ' ' || f[n - 1] == '\t'))
        n--;
    for (k = 0; k < sizeof names / sizeof names[0]; k++)
        if (strlen(names[k]) == n && strncasecmp(f, names[k], n) == 0)
            return (int)k / 2;
    return -1;
}

/* The factor to SI of the unit in header field f ("NAME [UNIT]") of quantity q (column_quantity: time
 * s or ms, acceleration m/s^2 or g); 0 when it has none or an unknown one, the unit written into unit. */
static double column_unit(const char *f, int q, char *unit, size_t n)
{
    const char *open = strchr(f, '['), *close = open ? strchr(open, ']') : NULL;
    unit[0] = '\0';
    if (!open || !close)
        return 0.0;
    snprintf(unit, n, "%.*s", (int)(close - open - 1), open + 1);
    if (q == 0)
        return strcmp(unit, "s") == 0 ? 1.0 : strcmp(unit, "ms") == 0 ? 1e-3 : 0.0;
    return strcmp(unit, "m/s^2") == 0 ? 1.0 : strcmp(unit, "g") == 0 ? TD_STANDARD_GRAVITY : 0.0;
}

/* Where a CSV fault is: the `file` setting, the file as shown and the line; the header's columns: each
 * one's name as written, its quantity (column_quantity) and factor to SI, and each quantity's column. */
typedef struct cr_csv {
    const config_setting_t *at;
    char shown[256];
    int line;
    char names[3][64];
    int quantity[3], column[3];
    double factor[3];
} cr_csv;

#define CSV_FAIL(r, csv, ...) td_cr_fail((r), (csv)->at, NULL, __VA_ARGS__)

/* The header line: three columns in any order, the time, x and y, each named with its unit in brackets. */
static td_status csv_header(td_case_reader *r, cr_csv *csv, char *line)
{
    static const char *const want[] = {"a time: s or ms", "an acceleration: m/s^2 or g", "an acceleration: m/s^2 or g"};
    char *field[4], unit[64];
    int n = split_fields(line, field, 3), c, q;
    if (n != 3)
        return CSV_FAIL(r, csv, "%s:%d: the header must name 3 columns, e.g. 't [s], ax [m/s^2], ay [m/s^2]' (got %s)",
                        csv->shown, csv->line,
                        n > 3    ? "more"
                        : n == 2 ? "2"
                                 : "1");
    csv->column[0] = csv->column[1] = csv->column[2] = -1;
    for (c = 0; c < 3; c++) {
        snprintf(csv->names[c], sizeof csv->names[c], "%s", field[c]);
        q = csv->quantity[c] = column_quantity(field[c]);
        if (q < 0)
            return CSV_FAIL(r, csv,
                            "%s:%d: column %d '%.60s': name it t or time, ax or x, ay or y (each once, any order)",
                            csv->shown, csv->line, c + 1, field[c]);
        if (csv->column[q] >= 0)
            return CSV_FAIL(r, csv, "%s:%d: column %d '%.60s': the same quantity as column %d '%.60s'", csv->shown,
                            csv->line, c + 1, field[c], csv->column[q] + 1, csv->names[csv->column[q]]);
        csv->column[q] = c;
        csv->factor[c] = column_unit(field[c], q, unit, sizeof unit);
        if (csv->factor[c] == 0.0)
            return CSV_FAIL(r, csv, "%s:%d: column %d '%.60s': %s unit in brackets (%s)", csv->shown, csv->line, c + 1,
                            field[c], unit[0] ? "an unknown" : "no", want[q]);
    }
    return TD_OK;
}

/* A data line: three numbers, in SI after the columns' units. */
static td_status csv_row(td_case_reader *r, cr_csv *csv, char *line, cr_points *p)
{
    char *field[4];
    double v[3];
    int n = split_fields(line, field, 3), c;
    if (n != 3)
        return CSV_FAIL(r, csv, "%s:%d: expected 3 numbers (%s, %s, %s), got %s", csv->shown, csv->line, csv->names[0],
                        csv->names[1], csv->names[2],
                        n > 3    ? "more"
                        : n == 2 ? "2"
                                 : "1");
    for (c = 0; c < 3; c++) {
        char *end;
        double x;
        errno = 0;
        x = strtod(field[c], &end);
        if (end == field[c] || *end != '\0' || !isfinite(x) || errno == ERANGE)
            return CSV_FAIL(r, csv, "%s:%d: column %d '%s': '%.40s' is not a finite number", csv->shown, csv->line,
                            c + 1, csv->names[c], field[c]);
        v[csv->quantity[c]] = x * csv->factor[c]; /* v by quantity: the time, x, y */
    }
    if (!points_grow(p))
        return td_error_set(r->err, TD_ERR_NOMEM, "%s: out of memory reading %s", r->path_shown, csv->shown);
    p->t[p->n] = v[0], p->x[p->n] = v[1], p->y[p->n] = v[2], p->line[p->n] = csv->line;
    p->n++;
    return TD_OK;
}

/* The CSV text: '#' comments and blank lines skipped, the header, then the data. */
static td_status csv_parse(td_case_reader *r, cr_csv *csv, char *text, cr_points *p)
{
    char *line = text;
    int header = 0;
    td_status st = TD_OK;
    for (csv->line = 1; st == TD_OK && line; csv->line++) {
        char *nl = strchr(line, '\n'), *q = line;
        if (nl)
            *nl = '\0';
        while (*q == ' ' || *q == '\t' || *q == '\r')
            q++;
        if (*q != '\0' && *q != '#')
            st = header ? csv_row(r, csv, q, p) : csv_header(r, csv, q);
        header = header || (*q != '\0' && *q != '#');
        line = nl ? nl + 1 : NULL;
    }
    if (st == TD_OK && !header)
        return CSV_FAIL(r, csv, "%s: no header line 't [s], ax [m/s^2], ay [m/s^2]'", csv->shown);
    return st;
}

/* The history file named in group g (relative to the case file's directory unless absolute). */
static td_status read_csv(td_case_reader *r, const config_setting_t *g, const char *file, cr_points *p, cr_csv *csv)
{
    size_t n = strlen(r->dir) + strlen(file) + 2;
    char *path = malloc(n), *text;
    td_error ferr;
    td_status st;
    csv->at = config_setting_get_member(g, "file");
    td_cr_printable(file, csv->shown, sizeof csv->shown);
    if (!path)
        return td_error_set(r->err, TD_ERR_NOMEM, "%s: out of memory", r->path_shown);
    snprintf(path, n, "%s%s%s", file[0] == '/' ? "" : r->dir, file[0] == '/' ? "" : "/", file);
    st = td_cr_read_file("history file", csv->shown, path, &text, &ferr);
    if (st != TD_OK) {
        free(path);
        if (st == TD_ERR_NOMEM)
            return td_error_set(r->err, TD_ERR_NOMEM, "%s: %s", r->path_shown, ferr.message);
        return CSV_FAIL(r, csv, "%s%s", ferr.message,
                        st == TD_ERR_IO ? " (the path is relative to the case file's directory)" : "");
    }
    /* an input: the outputs must never overwrite it (td_case_files); an FMU carries it (lib/fmu) */
    st = td_cr_record_file(r->c, path) == TD_OK
             ? csv_parse(r, csv, text, p)
             : td_error_set(r->err, TD_ERR_NOMEM, "%s: out of memory", r->path_shown);
    free(text);
    free(r->c->history_file);
    r->c->history_file = path;
    return st;
}

/* A model fault about history point i: at that entry of the inline array, or at its line of the file
 * (csv->at set: the history is a file's). */
static td_status history_fail(td_case_reader *r, const config_setting_t *g, const cr_points *p, const cr_csv *csv,
                              td_status st, const td_error *merr)
{
    const char *f = merr->site.field ? merr->site.field : "time";
    int q = strcmp(f, "x") == 0 ? 1 : strcmp(f, "y") == 0 ? 2 : 0, i = merr->site.index, c = csv->column[q];
    const config_setting_t *s;
    if (st == TD_ERR_NOMEM || !merr->site.part || strcmp(merr->site.part, "history") != 0)
        return td_cr_model_fail(r, g, st, merr);
    if (csv->at && i >= 0 && i < p->n)
        return CSV_FAIL(r, csv, "%s:%d: column %d '%s': %s", csv->shown, p->line[i], c + 1, csv->names[c],
                        merr->message + merr->reason);
    if (csv->at) /* the record as a whole (too few points) */
        return CSV_FAIL(r, csv, "%s: %s", csv->shown, merr->message + merr->reason);
    s = config_setting_get_member(g, f);
    if (s && i >= 0 && i < config_setting_length(s))
        s = config_setting_get_elem(s, (unsigned)i);
    return td_cr_fail(r, s ? s : g, NULL, "%s", merr->message + merr->reason);
}

/* history { file | time, x, y; start; scale; }: the record shifted by start, scaled by scale, to the model. */
static td_status set_history(td_case_reader *r, const config_setting_t *g, void *rec)
{
    const cr_history *h = rec;
    int inline_ = td_cr_has(g, "time") || td_cr_has(g, "x") || td_cr_has(g, "y"), i;
    cr_points p;
    cr_csv csv;
    td_error merr;
    td_status st;
    memset(&p, 0, sizeof p);
    memset(&csv, 0, sizeof csv);
    if (h->file && inline_)
        return td_cr_fail(r, config_setting_get_member(g, "file"), NULL,
                          "give either `file` or `time`, `x` and `y`, not both");
    if (!h->file && !inline_)
        return td_cr_fail(r, g, NULL, "give `file` (a CSV record) or `time`, `x` and `y`");
    /* the factor exists only here (the model takes the scaled record): its rule too */
    if (h->scale == 0.0)
        return td_cr_fail(r, config_setting_get_member(g, "scale"), NULL,
                          "must not be 0 (it cancels the record; leave the history out for no motion)");
    st = h->file ? read_csv(r, g, h->file, &p, &csv) : read_inline(r, g, &p);
    /* the shift's fault, not the first point's: the model sees only the shifted times (t >= 0 once,
     * there; the later points' order is the record's own) */
    if (st == TD_OK && p.n > 0 && td_cr_has(g, "start") && !(p.t[0] + h->start >= 0.0))
        st = td_cr_fail(r, config_setting_get_member(g, "start"), NULL,
                        "shifts the record's first time %g s to %g s: the shifted times must be >= 0 (the run starts "
                        "at 0 with the housing at rest)",
                        p.t[0], p.t[0] + h->start);
    for (i = 0; st == TD_OK && i < p.n; i++) {
        p.t[i] += h->start;
        p.x[i] *= h->scale;
        p.y[i] *= h->scale;
        if (!isfinite(p.t[i]) || !isfinite(p.x[i]) || !isfinite(p.y[i]))
            st = td_cr_fail(r, config_setting_get_member(g, isfinite(p.t[i]) ? "scale" : "start"), NULL,
                            "shifts or scales point %d of the record beyond the largest number", i);
    }
    if (st == TD_OK) {
        st = td_model_set_housing_history(r->c->model, p.n, p.t, p.x, p.y, &merr);
        if (st != TD_OK)
            st = history_fail(r, g, &p, &csv, st, &merr);
    }
    points_free(&p);
    return st;
}

static const td_cs_key history_keys[] = {
    {.key = "file",
     .type = TD_CS_STRING,
     .offset = offsetof(cr_history, file),
     .doc_default = "none",
     .doc = "a CSV record of the housing's acceleration, relative to the case file's directory unless absolute: a "
            "header naming each column with its unit in brackets, `t [s], ax [m/s^2], ay [m/s^2]` (the names `t` or "
            "`time`, `ax` or `x`, `ay` or `y`, in any case and any order, the columns read by them; time in `s` or "
            "`ms`, acceleration in `m/s^2` or `g` = 9.80665 m/s^2), then one point a line; `#` comments and blank "
            "lines are skipped. A fault names the file, its line and column"},
    {.key = "time",
     .type = TD_CS_CUSTOM,
     .doc_type = "array of numbers",
     .doc_range = "increasing, >= 0",
     .unit = "s",
     .doc_default = "none",
     .doc = "the record inline (instead of `file`): its times"},
    {.key = "x",
     .type = TD_CS_CUSTOM,
     .doc_type = "array of numbers",
     .unit = "m/s^2",
     .doc_default = "none",
     .doc = "the acceleration along x at each time (as many as `time`)"},
    {.key = "y",
     .type = TD_CS_CUSTOM,
     .doc_type = "array of numbers",
     .unit = "m/s^2",
     .doc_default = "none",
     .doc = "the acceleration along y at each time"},
    {.key = "start",
     .type = TD_CS_REAL,
     .offset = offsetof(cr_history, start),
     .unit = "s",
     .doc = "shift of the record's times (the shifted first time must be >= 0)"},
    {.key = "scale",
     .type = TD_CS_REAL,
     .offset = offsetof(cr_history, scale),
     .def = 1.0,
     .doc_range = "not 0",
     .doc = "factor on the record's acceleration"},
};
const td_cs_table td_cs_housing_history = {"housing.history",  NULL,           history_keys, TD_CS_COUNT(history_keys),
                                           sizeof(cr_history), history_preset, set_history};

/* housing.reference: the model's z_ref when written (else the rotor's centre of mass, the model's default). */
static td_status read_reference(td_case_reader *r, const config_setting_t *g, const td_cs_key *k, void *rec)
{
    double z;
    td_error merr;
    td_status st;
    (void)rec;
    if (!td_cr_has(g, k->key))
        return TD_OK;
    st = td_cr_real(r, g, k->key, NULL, 0.0, TD_CR_FINITE, &z);
    if (st == TD_OK && (st = td_model_set_housing_reference(r->c->model, z, &merr)) != TD_OK)
        st = td_cr_model_fail(r, g, st, &merr);
    return st;
}

static const td_cs_key housing_keys[] = {
    {.key = "reference",
     .type = TD_CS_CUSTOM,
     .read = read_reference,
     .unit = "m",
     .doc_type = "number",
     .doc_default = "the rotor's centre of mass",
     .doc = "axial position z of the point the housing rotates about (`housing.rotation`)"},
    {.key = "shocks",
     .type = TD_CS_LIST,
     .sub = &td_cs_housing_shocks,
     .doc = "translational acceleration pulses of the housing, summed with the history"},
    {.key = "history",
     .type = TD_CS_GROUP,
     .sub = &td_cs_housing_history,
     .doc_default = "none",
     .doc = "a tabulated or measured acceleration of the housing, piecewise linear, zero before its first time and "
            "after its last; the integrator stops at those two"},
    {.key = "rotation",
     .type = TD_CS_LIST,
     .sub = &td_cs_housing_rotation,
     .doc = "rotation-rate profiles of the housing about x and y (pitch, yaw), summed"},
    /* housing body */
    {.key = "body",
     .type = TD_CS_GROUP,
     .sub = &td_cs_housing_body,
     .doc_default = "none (a rigid housing, moved by the base alone)",
     .doc = "the housing as a rigid body on resilient mounts, below; the base motion above then moves the mounts "
            "([theory](theory.md#compliant-housing))"},
};
const td_cs_table td_cs_housing = {"housing", "housing", housing_keys, TD_CS_COUNT(housing_keys), 0, NULL, NULL};
