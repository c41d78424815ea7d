/*
 * The grid of a sweep (touchdown/sweep.h): axes parsed from "KEY=START:STOP:N" or
 * "KEY=V1,V2,..." specs, each holding its values as the text of a --set override, so that a
 * point is nothing but the case loaded with one more override per axis.
 */
#include "touchdown/sweep.h"
#include "util/error_internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef char td_sweep_value[TD_SWEEP_VALUE_SIZE];

typedef struct sweep_axis {
    char key[TD_SWEEP_KEY_SIZE];
    char *spec;
    int numeric;
    long count;
    td_sweep_value *values;
} sweep_axis;

struct td_sweep_grid {
    int axes;
    sweep_axis axis[TD_SWEEP_MAX_AXES];
};

td_status td_sweep_grid_create(td_sweep_grid **out, td_error *err)
{
    if (!out)
        return td_error_set(err, TD_ERR_INVALID, "td_sweep_grid_create: NULL argument");
    *out = calloc(1, sizeof **out);
    return *out ? TD_OK : td_error_set(err, TD_ERR_NOMEM, "td_sweep_grid_create: out of memory");
}

static void axis_release(sweep_axis *a)
{
    free(a->spec);
    free(a->values);
    memset(a, 0, sizeof *a);
}

void td_sweep_grid_free(td_sweep_grid **g)
{
    int i;
    if (!g || !*g)
        return;
    for (i = 0; i < (*g)->axes; i++)
        axis_release(&(*g)->axis[i]);
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

/* x with the fewest significant digits (15, 16, 17) that read back to x: short, and exact. */
static void print_exact(char *buf, size_t n, double x)
{
    int digits;
    for (digits = 15; digits <= 17; digits++) {
        snprintf(buf, n, "%.*g", digits, x);
        if (strtod(buf, NULL) == x)
            return;
    }
}

/* START:STOP:N into a->values; TD_ERR_PARSE naming the spec when `body` is not of that form. */
static td_status parse_range(sweep_axis *a, const char *body, const char *spec, td_error *err)
{
    char start_s[TD_SWEEP_VALUE_SIZE], stop_s[TD_SWEEP_VALUE_SIZE], *end;
    const char *c1 = strchr(body, ':'), *c2 = c1 ? strchr(c1 + 1, ':') : NULL;
    double start, stop;
    long n, i;
    if (!c2 || strchr(c2 + 1, ':') || (size_t)(c1 - body) >= sizeof start_s || (size_t)(c2 - c1) > sizeof stop_s)
        return td_error_set(err, TD_ERR_PARSE, "--vary '%s': expected KEY=START:STOP:N or KEY=V1,V2,...", spec);
    memcpy(start_s, body, (size_t)(c1 - body));
    start_s[c1 - body] = '\0';
    memcpy(stop_s, c1 + 1, (size_t)(c2 - c1 - 1));
    stop_s[c2 - c1 - 1] = '\0';
    if (!parse_number(start_s, &start) || !parse_number(stop_s, &stop))
        return td_error_set(err, TD_ERR_PARSE, "--vary '%s': START and STOP must be numbers", spec);
    n = strtol(c2 + 1, &end, 10);
    if (end == c2 + 1 || *end || n < 1 || n > TD_SWEEP_MAX_POINTS)
        return td_error_set(err, TD_ERR_PARSE, "--vary '%s': N must be a whole number from 1 to %ld", spec,
                            TD_SWEEP_MAX_POINTS);
    if (!(a->values = malloc((size_t)n * sizeof *a->values)))
        return td_error_set(err, TD_ERR_NOMEM, "--vary '%s': out of memory", spec);
    for (i = 0; i < n; i++) /* the last point is STOP itself, not START plus rounded steps */
        print_exact(a->values[i], TD_SWEEP_VALUE_SIZE,
                    i == n - 1 && n > 1 ? stop : start + (stop - start) * (double)i / (double)(n > 1 ? n - 1 : 1));
    a->count = n;
    a->numeric = 1;
    return TD_OK;
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

/* V1,V2,... into a->values. */
static td_status parse_list(sweep_axis *a, const char *body, const char *spec, td_error *err)
{
    long n = count_items(body), i;
    const char *s = body;
    double v;
    if (n > TD_SWEEP_MAX_POINTS)
        return td_error_set(err, TD_ERR_PARSE, "--vary '%s': more than %ld values", spec, TD_SWEEP_MAX_POINTS);
    if (!(a->values = malloc((size_t)n * sizeof *a->values)))
        return td_error_set(err, TD_ERR_NOMEM, "--vary '%s': out of memory", spec);
    a->numeric = 1;
    for (i = 0; i < n; i++) {
        const char *e = item_end(s);
        size_t len = (size_t)(e - s);
        if (len == 0 || len >= TD_SWEEP_VALUE_SIZE)
            return td_error_set(err, TD_ERR_PARSE, "--vary '%s': value %ld is %s", spec, i + 1,
                                len ? "too long" : "empty");
        memcpy(a->values[i], s, len);
        a->values[i][len] = '\0';
        a->numeric = a->numeric && parse_number(a->values[i], &v);
        s = e + 1;
    }
    a->count = n;
    return TD_OK;
}

/* The key before '=' into a->key, checked for size and against the grid's other keys. */
static td_status parse_key(const td_sweep_grid *g, sweep_axis *a, const char *spec, const char **body, td_error *err)
{
    const char *eq = strchr(spec, '=');
    size_t len = eq ? (size_t)(eq - spec) : 0;
    int i;
    if (!eq || len == 0 || !eq[1])
        return td_error_set(err, TD_ERR_PARSE, "--vary '%s': expected KEY=START:STOP:N or KEY=V1,V2,...", spec);
    if (len >= sizeof a->key)
        return td_error_set(err, TD_ERR_PARSE, "--vary '%s': the key is too long", spec);
    memcpy(a->key, spec, len);
    a->key[len] = '\0';
    for (i = 0; i < g->axes; i++)
        if (!strcmp(g->axis[i].key, a->key))
            return td_error_set(err, TD_ERR_PARSE, "--vary '%s': %s is swept twice", spec, a->key);
    *body = eq + 1;
    return TD_OK;
}

/* A list has a comma outside quotes; a range has a colon and no quote; anything else is a
 * list of one value. */
static int looks_like_range(const char *body)
{
    return *item_end(body) == '\0' && strchr(body, ':') && !strchr(body, '"');
}

td_status td_sweep_grid_vary(td_sweep_grid *g, const char *spec, td_error *err)
{
    sweep_axis a;
    const char *body = NULL;
    td_status st;
    if (!g || !spec)
        return td_error_set(err, TD_ERR_INVALID, "td_sweep_grid_vary: NULL argument");
    if (g->axes >= TD_SWEEP_MAX_AXES)
        return td_error_set(err, TD_ERR_PARSE, "--vary '%s': at most %d swept keys", spec, TD_SWEEP_MAX_AXES);
    memset(&a, 0, sizeof a);
    if ((st = parse_key(g, &a, spec, &body, err)) == TD_OK)
        st = looks_like_range(body) ? parse_range(&a, body, spec, err) : parse_list(&a, body, spec, err);
    if (st == TD_OK && td_sweep_grid_points(g) * a.count > TD_SWEEP_MAX_POINTS)
        st = td_error_set(err, TD_ERR_PARSE, "--vary '%s': the sweep would have %ld points, at most %ld", spec,
                          td_sweep_grid_points(g) * a.count, TD_SWEEP_MAX_POINTS);
    if (st == TD_OK && !(a.spec = malloc(strlen(spec) + 1)))
        st = td_error_set(err, TD_ERR_NOMEM, "--vary '%s': out of memory", spec);
    if (st != TD_OK) {
        axis_release(&a);
        return st;
    }
    strcpy(a.spec, spec);
    g->axis[g->axes++] = a;
    return TD_OK;
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

const char *td_sweep_grid_key(const td_sweep_grid *g, int axis)
{
    return g->axis[axis].key;
}

const char *td_sweep_grid_spec(const td_sweep_grid *g, int axis)
{
    return g->axis[axis].spec;
}

int td_sweep_grid_numeric(const td_sweep_grid *g, int axis)
{
    return g->axis[axis].numeric;
}

/* The first axis varies slowest: the index on `axis` is the point divided by the product of the
 * later axes' counts. */
const char *td_sweep_grid_value(const td_sweep_grid *g, long point, int axis)
{
    long stride = 1;
    int i;
    for (i = axis + 1; i < g->axes; i++)
        stride *= g->axis[i].count;
    return g->axis[axis].values[(point / stride) % g->axis[axis].count];
}

int td_sweep_grid_override(const td_sweep_grid *g, long point, int axis, char *buf, size_t n)
{
    return snprintf(buf, n, "%s=%s", g->axis[axis].key, td_sweep_grid_value(g, point, axis));
}
