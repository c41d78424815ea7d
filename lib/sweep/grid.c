/*
 * The grid of a sweep (touchdown/sweep.h): axes parsed from "KEY=START:STOP:N[:SPACING]" or
 * "KEY=V1,V2,..." specs, each key holding its values as the text of a --set override, so that a
 * point is nothing but the case loaded with one more override per swept key. An axis has one key,
 * or several zipped keys with as many values each that move together.
 */
#include "case/case_message.h" /* td_cr_printable: user text in messages */
#include "sweep/sweep_internal.h"
#include "util/error_internal.h"
#include "util/text.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef char td_sweep_value[TD_SWEEP_VALUE_SIZE];

typedef struct sweep_key {
    char key[TD_SWEEP_KEY_SIZE];
    char *spec;
    int axis;
    int numeric;
    long count;
    td_sweep_value *values; /* NULL in a dry grid */
} sweep_key;

typedef struct sweep_axis {
    long count;
    char *origin;
} sweep_axis;

struct td_sweep_grid {
    int dry;
    int axes, keys;
    sweep_axis axis[TD_SWEEP_MAX_AXES];
    sweep_key key[TD_SWEEP_MAX_KEYS];
};

/* Where a failed rule leaves its part and reason. */
typedef struct add_error {
    td_sweep_part part;
    char *reason;
    size_t n;
} add_error;

static td_status reject(add_error *e, td_sweep_part part, const char *fmt, ...) TD_PRINTF(3, 4);
static td_status reject(add_error *e, td_sweep_part part, const char *fmt, ...)
{
    va_list ap;
    e->part = part;
    va_start(ap, fmt);
    vsnprintf(e->reason, e->n, fmt, ap);
    va_end(ap);
    return TD_ERR_PARSE;
}

td_status td_sweep_grid_create(td_sweep_grid **out, td_error *err)
{
    if (!out)
        return td_error_set(err, TD_ERR_INVALID, "td_sweep_grid_create: NULL argument");
    *out = calloc(1, sizeof **out);
    return *out ? TD_OK : td_error_set(err, TD_ERR_NOMEM, "td_sweep_grid_create: out of memory");
}

td_status td_sweep_grid_create_dry(td_sweep_grid **out, td_error *err)
{
    td_status st = td_sweep_grid_create(out, err);
    if (st == TD_OK)
        (*out)->dry = 1;
    return st;
}

static void key_release(sweep_key *k)
{
    free(k->spec);
    free(k->values);
    memset(k, 0, sizeof *k);
}

void td_sweep_grid_free(td_sweep_grid **g)
{
    int i;
    if (!g || !*g)
        return;
    for (i = 0; i < (*g)->keys; i++)
        key_release(&(*g)->key[i]);
    for (i = 0; i < (*g)->axes; i++)
        free((*g)->axis[i].origin);
    free(*g);
    *g = NULL;
}

/* A whole string that strtod reads as a finite number. */
static int parse_number(const char *s, double *v)
{
    char *end;
    if (!*s)
        return 0;
    *v = strtod(s, &end);
    return *end == '\0' && isfinite(*v);
}

/* Point i of n from start to stop, both ends exact: evenly spaced, or geometric (log). */
static double range_value(double start, double stop, long n, long i, int log_spacing)
{
    double t;
    if (i == 0 || n == 1)
        return start;
    if (i == n - 1) /* STOP itself, not START plus rounded steps */
        return stop;
    t = (double)i / (double)(n - 1);
    return log_spacing ? start * pow(stop / start, t) : start + (stop - start) * t;
}

/* body split at its colons into f[]; the number of fields, or -1 past `max` or a field too long. */
static int split_fields(const char *body, td_sweep_value *f, int max)
{
    int nf = 0;
    for (;;) {
        const char *c = strchr(body, ':');
        size_t len = c ? (size_t)(c - body) : strlen(body);
        if (nf == max || len >= TD_SWEEP_VALUE_SIZE)
            return -1;
        memcpy(f[nf], body, len);
        f[nf++][len] = '\0';
        if (!c)
            return nf;
        body = c + 1;
    }
}

/* The spacing field of a range: 0 linear, 1 log, -1 neither. */
static int parse_spacing(const char *s)
{
    return !strcmp(s, "linear") ? 0 : (!strcmp(s, "log") ? 1 : -1);
}

static td_status fill_range(sweep_key *k, double start, double stop, long n, int log_spacing, add_error *e)
{
    long i;
    if (!(k->values = malloc((size_t)n * sizeof *k->values)))
        return reject(e, TD_SWEEP_PART_SPEC, "out of memory");
    for (i = 0; i < n; i++)
        td_text_shortest_number(k->values[i], TD_SWEEP_VALUE_SIZE, range_value(start, stop, n, i, log_spacing));
    return TD_OK;
}

/* START:STOP:N[:SPACING] into k (its values unless the grid is dry). */
static td_status parse_range(sweep_key *k, const char *body, int dry, add_error *e)
{
    td_sweep_value f[4];
    double start, stop;
    char *end;
    long n;
    int nf = split_fields(body, f, 4), log_spacing = 0;
    if (nf < 3)
        return reject(e, TD_SWEEP_PART_SPEC, "expected KEY=START:STOP:N[:linear|log] or KEY=V1,V2,...");
    if (!parse_number(f[0], &start))
        return reject(e, TD_SWEEP_PART_START, "the range's first value '%s' is not a number", f[0]);
    if (!parse_number(f[1], &stop))
        return reject(e, TD_SWEEP_PART_STOP, "the range's last value '%s' is not a number", f[1]);
    n = strtol(f[2], &end, 10);
    if (end == f[2] || *end || n < 1 || n > TD_SWEEP_MAX_POINTS)
        return reject(e, TD_SWEEP_PART_N, "the number of points must be a whole number from 1 to %ld, got '%s'",
                      TD_SWEEP_MAX_POINTS, f[2]);
    if (nf == 4 && (log_spacing = parse_spacing(f[3])) < 0)
        return reject(e, TD_SWEEP_PART_SPACING, "the spacing must be linear or log, got '%s'", f[3]);
    if (log_spacing && !(start > 0.0 && stop > 0.0))
        return reject(e, start > 0.0 ? TD_SWEEP_PART_STOP : TD_SWEEP_PART_START,
                      "a log range needs both ends > 0 (got %s and %s)", f[0], f[1]);
    /* range_value interpolates through STOP/START (log) or STOP-START (linear): when that is beyond a
     * double, the inner points would be inf or 0, values nobody wrote */
    if (n > 2 && log_spacing && !isnormal(stop / start))
        return reject(e, TD_SWEEP_PART_STOP,
                      "the log range from %s to %s has a ratio (%s/%s) beyond a double's range: split it or "
                      "list the values",
                      f[0], f[1], f[1], f[0]);
    if (n > 2 && !log_spacing && !isfinite(stop - start))
        return reject(e, TD_SWEEP_PART_STOP,
                      "the range from %s to %s is wider than a double holds (%s - %s overflows): split it or "
                      "list the values",
                      f[0], f[1], f[1], f[0]);
    k->count = n;
    k->numeric = 1;
    return dry ? TD_OK : fill_range(k, start, stop, n, log_spacing, e);
}

/* End of the list item starting at s: the next comma outside quotes and brackets, or the end. */
static const char *item_end(const char *s)
{
    int depth = 0, quoted = 0;
    for (; *s; s++) {
        if (quoted) {
            if (*s == '\\' && s[1])
                s++;
            else if (*s == '"')
                quoted = 0;
        } else if (*s == '"')
            quoted = 1;
        else if (*s == '[' || *s == '(' || *s == '{')
            depth++;
        else if ((*s == ']' || *s == ')' || *s == '}') && depth > 0)
            depth--;
        else if (*s == ',' && depth == 0)
            break;
    }
    return s;
}

static long count_items(const char *body)
{
    long n = 1;
    const char *s = body;
    while (*(s = item_end(s)) == ',') {
        n++;
        s++;
    }
    return n;
}

/* V1,V2,... into k: every value checked, kept unless the grid is dry. */
static td_status parse_list(sweep_key *k, const char *body, int dry, add_error *e)
{
    long n = count_items(body), i;
    const char *s = body;
    double v;
    if (n > TD_SWEEP_MAX_POINTS)
        return reject(e, TD_SWEEP_PART_VALUES, "more than %ld values", TD_SWEEP_MAX_POINTS);
    if (!dry && !(k->values = malloc((size_t)n * sizeof *k->values)))
        return reject(e, TD_SWEEP_PART_SPEC, "out of memory");
    k->numeric = 1;
    for (i = 0; i < n; i++) {
        const char *end = item_end(s);
        size_t len = (size_t)(end - s);
        char value[TD_SWEEP_VALUE_SIZE];
        if (len == 0 || len >= TD_SWEEP_VALUE_SIZE)
            return reject(e, TD_SWEEP_PART_VALUES, "value %ld is %s", i + 1,
                          len ? "too long (at most 127 characters)" : "empty");
        memcpy(value, s, len);
        value[len] = '\0';
        if (!dry)
            memcpy(k->values[i], value, len + 1);
        k->numeric = k->numeric && parse_number(value, &v);
        s = end + 1;
    }
    k->count = n;
    return TD_OK;
}

static int key_index(const td_sweep_grid *g, const char *key)
{
    int i;
    for (i = 0; i < g->keys; i++)
        if (!strcmp(g->key[i].key, key))
            return i;
    return -1;
}

/* The key before '=' into k->key, checked for size and against the grid's other keys. */
static td_status parse_key(const td_sweep_grid *g, sweep_key *k, const char *spec, const char **body, add_error *e)
{
    const char *eq = strchr(spec, '=');
    size_t len = eq ? (size_t)(eq - spec) : 0;
    if (!eq || len == 0 || !eq[1])
        return reject(e, TD_SWEEP_PART_SPEC, "expected KEY=START:STOP:N[:linear|log] or KEY=V1,V2,...");
    if (len >= sizeof k->key)
        return reject(e, TD_SWEEP_PART_KEY, "the key is too long (at most %d characters)", TD_SWEEP_KEY_SIZE - 1);
    memcpy(k->key, spec, len);
    k->key[len] = '\0';
    if (key_index(g, k->key) >= 0)
        return reject(e, TD_SWEEP_PART_KEY, "%s is swept twice", k->key);
    *body = eq + 1;
    return TD_OK;
}

/* A list has a comma outside quotes; a range has a colon and no quote; anything else is a
 * list of one value. */
static int looks_like_range(const char *body)
{
    return *item_end(body) == '\0' && strchr(body, ':') && !strchr(body, '"');
}

/* Room for one more key, and for a new axis unless it is zipped onto the last one. */
static td_status check_room(const td_sweep_grid *g, int with, add_error *e)
{
    if (g->keys >= TD_SWEEP_MAX_KEYS)
        return reject(e, TD_SWEEP_PART_SPEC, "at most %d swept keys", TD_SWEEP_MAX_KEYS);
    if (with && g->axes == 0)
        return reject(e, TD_SWEEP_PART_SPEC, "no axis to join (--with follows a --vary)");
    if (!with && g->axes >= TD_SWEEP_MAX_AXES)
        return reject(e, TD_SWEEP_PART_SPEC, "at most %d axes", TD_SWEEP_MAX_AXES);
    return TD_OK;
}

/* A zipped key has as many values as the axis it joins; a new axis keeps the grid bounded. */
static td_status check_count(const td_sweep_grid *g, const sweep_key *k, int with, add_error *e)
{
    long points = td_sweep_grid_points(g);
    const sweep_key *first;
    if (with) {
        first = &g->key[g->keys - 1];
        while (first > g->key && first[-1].axis == first->axis)
            first--;
        if (k->count != first->count)
            return reject(e, TD_SWEEP_PART_COUNT, "%s has %ld values but %s, whose axis it joins, has %ld", k->key,
                          k->count, first->key, first->count);
        return TD_OK;
    }
    if (points * k->count > TD_SWEEP_MAX_POINTS)
        return reject(e, TD_SWEEP_PART_SPEC, "the sweep would have %ld points, at most %ld", points * k->count,
                      TD_SWEEP_MAX_POINTS);
    return TD_OK;
}

/* k (with a copy of its spec) joins the grid: on a new axis of origin `origin`, or the last. */
static td_status keep(td_sweep_grid *g, sweep_key *k, const char *spec, int with, const char *origin, add_error *e)
{
    char *origin_copy = NULL;
    if (!(k->spec = malloc(strlen(spec) + 1)) || (!with && !(origin_copy = malloc(strlen(origin ? origin : "") + 1))))
        return reject(e, TD_SWEEP_PART_SPEC, "out of memory");
    strcpy(k->spec, spec);
    if (!with) {
        strcpy(origin_copy, origin ? origin : "");
        g->axis[g->axes].count = k->count;
        g->axis[g->axes++].origin = origin_copy;
    }
    k->axis = g->axes - 1;
    g->key[g->keys++] = *k;
    return TD_OK;
}

td_status td_sweep_grid_add(td_sweep_grid *g, const char *spec, int with, const char *origin, td_sweep_part *part,
                            char *reason, size_t n)
{
    add_error e;
    sweep_key k;
    const char *body = NULL;
    td_status st;
    e.part = TD_SWEEP_PART_SPEC;
    e.reason = reason;
    e.n = n;
    memset(&k, 0, sizeof k);
    st = check_room(g, with, &e);
    if (st == TD_OK)
        st = parse_key(g, &k, spec, &body, &e);
    if (st == TD_OK)
        st = looks_like_range(body) ? parse_range(&k, body, g->dry, &e) : parse_list(&k, body, g->dry, &e);
    if (st == TD_OK)
        st = check_count(g, &k, with, &e);
    if (st == TD_OK)
        st = keep(g, &k, spec, with, origin, &e);
    if (st != TD_OK)
        key_release(&k);
    *part = e.part;
    return st;
}

/* --vary and --with: the rules of td_sweep_grid_add, the error naming the option and its spec. */
static td_status add_option(td_sweep_grid *g, const char *spec, int with, td_error *err)
{
    char reason[TD_ERROR_MESSAGE_SIZE], reason_shown[TD_ERROR_MESSAGE_SIZE], *context, *shown = NULL;
    td_sweep_part part;
    td_status st;
    if (!g || !spec)
        return td_error_set(err, TD_ERR_INVALID, "td_sweep_grid_%s: NULL argument", with ? "with" : "vary");
    st = td_sweep_grid_add(g, spec, with, "command line", &part, reason, sizeof reason);
    if (st == TD_OK)
        return TD_OK;
    /* the spec and the parts of it the reason quotes are the user's text: control characters are
     * shown escaped, as the case reader shows its user text, so the error stays one line */
    if (!(shown = td_cr_printable_dup(spec)) || !(context = malloc(strlen(shown) + 16))) {
        free(shown);
        return td_error_set(err, TD_ERR_NOMEM, "%s: out of memory", with ? "--with" : "--vary");
    }
    sprintf(context, "%s '%s'", with ? "--with" : "--vary", shown); /* a long spec is cut, the reason kept */
    st = td_error_set_reason(err, st, context, td_cr_printable(reason, reason_shown, sizeof reason_shown));
    free(context);
    free(shown);
    return st;
}

td_status td_sweep_grid_vary(td_sweep_grid *g, const char *spec, td_error *err)
{
    return add_option(g, spec, 0, err);
}

td_status td_sweep_grid_with(td_sweep_grid *g, const char *spec, td_error *err)
{
    return add_option(g, spec, 1, err);
}

long td_sweep_grid_points(const td_sweep_grid *g)
{
    long n = 1;
    int i;
    for (i = 0; g && i < g->axes; i++)
        n *= g->axis[i].count;
    return n;
}

int td_sweep_grid_axes(const td_sweep_grid *g)
{
    return g ? g->axes : 0;
}

int td_sweep_grid_keys(const td_sweep_grid *g)
{
    return g ? g->keys : 0;
}

const char *td_sweep_grid_key(const td_sweep_grid *g, int k)
{
    return g->key[k].key;
}

const char *td_sweep_grid_spec(const td_sweep_grid *g, int k)
{
    return g->key[k].spec;
}

int td_sweep_grid_numeric(const td_sweep_grid *g, int k)
{
    return g->key[k].numeric;
}

int td_sweep_grid_axis(const td_sweep_grid *g, int k)
{
    return g->key[k].axis;
}

const char *td_sweep_grid_origin(const td_sweep_grid *g, int k)
{
    return g->axis[g->key[k].axis].origin;
}

/* The first axis varies slowest: the index on an axis is the point divided by the product of the
 * later axes' counts; the keys of one axis share it. */
const char *td_sweep_grid_value(const td_sweep_grid *g, long point, int k)
{
    long stride = 1;
    int i, axis = g->key[k].axis;
    for (i = axis + 1; i < g->axes; i++)
        stride *= g->axis[i].count;
    return g->key[k].values[(point / stride) % g->axis[axis].count];
}

int td_sweep_grid_override(const td_sweep_grid *g, long point, int k, char *buf, size_t n)
{
    return snprintf(buf, n, "%s=%s", g->key[k].key, td_sweep_grid_value(g, point, k));
}
