/*
 * Campbell diagram (modes over a speed grid, branches tracked by sorting) and critical speeds
 * (crossings of a whirl branch with the synchronous line omega_d = Omega, refined by the
 * Illinois variant of regula falsi on fresh eigen-solves).
 */
#include "modal/modal_internal.h"
#include "touchdown/dofs.h"
#include "util/error_internal.h"

#include <math.h>
#include <stdlib.h>

struct td_campbell {
    int nspeeds;
    int nbranches;
    double *speeds;  /* nspeeds */
    td_mode *points; /* nspeeds x nbranches, speed-major */
};

/* Relative width at which a critical-speed bracket counts as converged. */
#define TD_CRITICAL_RTOL 1e-12
/* A converged point must lie this close to the 1x line, else the bracket straddled a branch jump. */
#define TD_CRITICAL_CHECK 1e-7
#define TD_CRITICAL_MAX_ITER 200

static td_status check_options(const td_modal_options *opt, td_error *err)
{
    if (!opt)
        return td_error_set(err, TD_ERR_INVALID, "modal: NULL options");
    if (!isfinite(opt->speed_min) || !isfinite(opt->speed_max) || opt->speed_max < opt->speed_min)
        return td_error_set(err, TD_ERR_INVALID, "modal: speed range must be finite with speed_max >= speed_min");
    if (opt->speed_steps < 2)
        return td_error_set(err, TD_ERR_INVALID, "modal: speed_steps must be >= 2");
    if (opt->mode_count < 1)
        return td_error_set(err, TD_ERR_INVALID, "modal: mode_count must be >= 1");
    return TD_OK;
}

static double grid_speed(const td_modal_options *opt, int k)
{
    if (k == opt->speed_steps - 1)
        return opt->speed_max;
    return opt->speed_min + (opt->speed_max - opt->speed_min) * (double)k / (double)(opt->speed_steps - 1);
}

void td_campbell_free(td_campbell **c)
{
    if (!c || !*c)
        return;
    free((*c)->speeds);
    free((*c)->points);
    free(*c);
    *c = NULL;
}

int td_mode_is_vibration(const td_mode *m)
{
    return m && m->zeta < TD_MODAL_OVERDAMPED_ZETA;
}

const char *td_whirl_name(td_whirl w)
{
    switch (w) {
    case TD_WHIRL_FORWARD: return "forward";
    case TD_WHIRL_BACKWARD: return "backward";
    case TD_WHIRL_MIXED: return "mixed";
    }
    return NULL;
}

/* Branch j at one speed is the j-th lowest vibration mode there (overdamped pairs skipped);
 * missing branches are NAN. */
static void fill_branches(const td_modal *m, td_mode *row, int nbranches)
{
    int i, j = 0;
    for (i = 0; i < m->n_modes && j < nbranches; i++)
        if (td_mode_is_vibration(&m->modes[i]))
            row[j++] = m->modes[i];
    for (; j < nbranches; j++) {
        row[j].sigma = row[j].omega_d = row[j].freq_hz = row[j].omega_n = row[j].zeta = row[j].whirl_index = NAN;
        row[j].whirl = TD_WHIRL_MIXED;
    }
}

td_status td_campbell_compute(const td_system *sys, const td_modal_options *opt, td_campbell **out, td_error *err)
{
    td_campbell *c;
    td_status st;
    int k;
    if (!out)
        return td_error_set(err, TD_ERR_INVALID, "td_campbell_compute: NULL output pointer");
    *out = NULL;
    st = check_options(opt, err);
    if (st != TD_OK)
        return st;
    c = calloc(1, sizeof *c);
    if (!c)
        return td_error_set(err, TD_ERR_NOMEM, "modal: out of memory for the Campbell diagram");
    c->nspeeds = opt->speed_steps;
    c->nbranches = opt->mode_count;
    c->speeds = malloc((size_t)c->nspeeds * sizeof *c->speeds);
    c->points = malloc((size_t)c->nspeeds * (size_t)c->nbranches * sizeof *c->points);
    if (!c->speeds || !c->points) {
        td_campbell_free(&c);
        return td_error_set(err, TD_ERR_NOMEM, "modal: out of memory for the Campbell diagram");
    }
    for (k = 0; k < c->nspeeds; k++) {
        td_modal *m = NULL;
        c->speeds[k] = grid_speed(opt, k);
        st = td_modal_solve_lowest(sys, c->speeds[k], c->nbranches, &m, err);
        if (st != TD_OK) {
            td_campbell_free(&c);
            return st;
        }
        fill_branches(m, c->points + (size_t)k * (size_t)c->nbranches, c->nbranches);
        td_modal_free(&m);
    }
    *out = c;
    return TD_OK;
}

int td_campbell_speed_count(const td_campbell *c)
{
    return c ? c->nspeeds : 0;
}
int td_campbell_branch_count(const td_campbell *c)
{
    return c ? c->nbranches : 0;
}

double td_campbell_speed(const td_campbell *c, int k)
{
    if (!c || k < 0 || k >= c->nspeeds)
        return NAN;
    return c->speeds[k];
}

td_status td_campbell_get(const td_campbell *c, int k, int j, td_mode *out)
{
    if (!c || !out || k < 0 || k >= c->nspeeds || j < 0 || j >= c->nbranches)
        return TD_ERR_INVALID;
    *out = c->points[(size_t)k * (size_t)c->nbranches + (size_t)j];
    return TD_OK;
}

/* ---- critical speeds ---------------------------------------------------------------------- */

/* Modes of one whirl sense at one speed (ascending omega_d, as td_modal stores them). */
typedef struct whirl_list {
    int count;
    td_mode *modes;
} whirl_list;

/* What the crossing search solves: the system, and the damped frequency up to which every vibration
 * mode is needed (the top of the speed range: a branch crossing the 1x line there lies below it). */
typedef struct crossing_problem {
    const td_system *sys;
    double wmax;
} crossing_problem;

/* The forward (lists[0]) and backward (lists[1]) vibration modes at one speed, from one eigen-solve. */
static td_status whirl_modes(const crossing_problem *cp, double omega, whirl_list lists[2], td_error *err)
{
    static const td_whirl senses[2] = {TD_WHIRL_FORWARD, TD_WHIRL_BACKWARD};
    td_modal *m = NULL;
    td_status st = td_modal_lowest(cp->sys, omega, 1, cp->wmax, 0, &m, err);
    int i, s;
    for (s = 0; s < 2; s++) {
        lists[s].count = 0;
        lists[s].modes = NULL;
    }
    if (st != TD_OK)
        return st;
    for (s = 0; s < 2 && st == TD_OK; s++) {
        lists[s].modes = malloc((size_t)(m->n_modes > 0 ? m->n_modes : 1) * sizeof *lists[s].modes);
        if (!lists[s].modes)
            st = td_error_set(err, TD_ERR_NOMEM, "modal: out of memory");
        for (i = 0; st == TD_OK && i < m->n_modes; i++)
            if (m->modes[i].whirl == senses[s] && td_mode_is_vibration(&m->modes[i]) &&
                m->modes[i].omega_d < m->complete_below)
                lists[s].modes[lists[s].count++] = m->modes[i];
    }
    td_modal_free(&m);
    return st;
}

static void whirl_lists_free(whirl_list lists[2])
{
    free(lists[0].modes);
    free(lists[1].modes);
    lists[0].modes = lists[1].modes = NULL;
}

/* g(Omega) = omega_d - Omega of branch `branch` of whirl `which`; *ok = 0 if the branch is absent. */
static td_status branch_gap(const crossing_problem *cp, double omega, td_whirl which, int branch, double *g,
                            td_mode *mode, int *ok, td_error *err)
{
    whirl_list l[2];
    const whirl_list *w = &l[which == TD_WHIRL_FORWARD ? 0 : 1];
    td_status st = whirl_modes(cp, omega, l, err);
    if (st != TD_OK)
        return st;
    *ok = branch < w->count;
    if (*ok) {
        *g = w->modes[branch].omega_d - omega;
        if (mode)
            *mode = w->modes[branch];
    }
    whirl_lists_free(l);
    return TD_OK;
}

/* Refine a bracketed crossing [a, b] (ga, gb of opposite signs) by the Illinois method. *found = 0
 * when the branch vanished inside or the limit is a jump between branches, not a crossing. */
static td_status refine(const crossing_problem *cp, td_whirl which, int branch, double a, double ga, double b,
                        double gb, td_critical_speed *cs, int *found, td_error *err)
{
    int side = 0, iter, ok;
    double x = a, gx = ga;
    td_mode mode;
    td_status st;
    *found = 0;
    for (iter = 0; iter < TD_CRITICAL_MAX_ITER; iter++) {
        x = (a * gb - b * ga) / (gb - ga);
        if (!(x > a && x < b))
            x = 0.5 * (a + b);
        st = branch_gap(cp, x, which, branch, &gx, &mode, &ok, err);
        if (st != TD_OK)
            return st;
        if (!ok)
            return TD_OK;
        if (gx == 0.0)
            break;
        if ((gx > 0.0) == (ga > 0.0)) {
            a = x;
            ga = gx;
            if (side == -1)
                gb *= 0.5; /* Illinois: halve the stale end's weight */
            side = -1;
        } else {
            b = x;
            gb = gx;
            if (side == 1)
                ga *= 0.5;
            side = 1;
        }
        if (b - a <= TD_CRITICAL_RTOL * fabs(b))
            break;
    }
    /* x, gx, mode: the last evaluated point, at most one bracket width from the root */
    if (fabs(gx) > TD_CRITICAL_CHECK * fabs(x))
        return TD_OK;
    cs->speed = x;
    cs->freq_hz = x / (2.0 * TD_PI);
    cs->zeta = mode.zeta;
    cs->sigma = mode.sigma;
    cs->whirl = which;
    cs->branch = branch;
    *found = 1;
    return TD_OK;
}

/* A growable result list. */
typedef struct cs_list {
    td_critical_speed *items;
    int count, capacity;
} cs_list;

static td_status cs_push(cs_list *l, const td_critical_speed *c, td_error *err)
{
    if (l->count == l->capacity) {
        int cap = l->capacity ? 2 * l->capacity : 8;
        td_critical_speed *p = realloc(l->items, (size_t)cap * sizeof *p);
        if (!p)
            return td_error_set(err, TD_ERR_NOMEM, "modal: out of memory collecting critical speeds");
        l->items = p;
        l->capacity = cap;
    }
    l->items[l->count++] = *c;
    return TD_OK;
}

static int cmp_speed(const void *a, const void *b)
{
    const td_critical_speed *x = a, *y = b;
    return x->speed < y->speed ? -1 : (x->speed > y->speed ? 1 : 0);
}

/* Scan one grid interval [s0, s1] (whirl lists l0, l1 there) for branch crossings. */
static td_status scan_interval(const crossing_problem *cp, td_whirl which, double s0, const whirl_list *l0, double s1,
                               const whirl_list *l1, cs_list *res, td_error *err)
{
    int j, n = l0->count < l1->count ? l0->count : l1->count;
    for (j = 0; j < n; j++) {
        double g0 = l0->modes[j].omega_d - s0, g1 = l1->modes[j].omega_d - s1;
        td_critical_speed cs;
        int found = 0;
        td_status st;
        if (g0 == 0.0 || g1 == 0.0 || (g0 > 0.0) == (g1 > 0.0))
            continue;
        st = refine(cp, which, j, s0, g0, s1, g1, &cs, &found, err);
        if (st != TD_OK)
            return st;
        if (found && (st = cs_push(res, &cs, err)) != TD_OK)
            return st;
    }
    /* a crossing exactly on the grid point s0 */
    for (j = 0; j < l0->count; j++)
        if (l0->modes[j].omega_d - s0 == 0.0) {
            td_critical_speed cs = {s0, s0 / (2.0 * TD_PI), l0->modes[j].zeta, l0->modes[j].sigma, which, j};
            td_status st = cs_push(res, &cs, err);
            if (st != TD_OK)
                return st;
        }
    return TD_OK;
}

td_status td_modal_critical_speeds(const td_system *sys, const td_modal_options *opt, td_critical_speed *out,
                                   int capacity, int *count, td_error *err)
{
    static const td_whirl senses[2] = {TD_WHIRL_FORWARD, TD_WHIRL_BACKWARD};
    cs_list res = {NULL, 0, 0};
    td_status st;
    int s, k, i;
    crossing_problem cp;
    whirl_list prev[2] = {{0, NULL}, {0, NULL}}, cur[2];
    double sprev = 0.0;
    if (!count || capacity < 0 || (capacity > 0 && !out))
        return td_error_set(err, TD_ERR_INVALID, "td_modal_critical_speeds: bad output arguments");
    *count = 0;
    st = check_options(opt, err);
    if (st != TD_OK)
        return st;
    cp.sys = sys;
    cp.wmax = opt->speed_max;
    /* one eigen-solve per grid speed serves both whirl senses */
    for (k = 0; k < opt->speed_steps && st == TD_OK; k++) {
        double sp = grid_speed(opt, k);
        st = whirl_modes(&cp, sp, cur, err);
        for (s = 0; s < 2 && st == TD_OK && k > 0; s++)
            st = scan_interval(&cp, senses[s], sprev, &prev[s], sp, &cur[s], &res, err);
        whirl_lists_free(prev);
        prev[0] = cur[0];
        prev[1] = cur[1];
        sprev = sp;
    }
    whirl_lists_free(prev);
    if (st != TD_OK) {
        free(res.items);
        return st;
    }
    qsort(res.items, (size_t)res.count, sizeof *res.items, cmp_speed);
    for (i = 0; i < res.count && i < capacity; i++)
        out[i] = res.items[i];
    *count = res.count;
    free(res.items);
    return TD_OK;
}
