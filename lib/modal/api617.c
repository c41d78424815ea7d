/*
 * The API 617 unbalance response report (touchdown/modal.h; docs/api617.md): the steady
 * unbalance response over a speed range on an adaptive grid, its peaks with the amplification
 * factor by the half-power method and the separation margin from the operating range (API 617
 * 7th ed., 2002, 2.6.2.10; API 684 2nd ed., 2005: docs/api617.md), the log decrement, the default response
 * nodes and the static reactions under gravity.
 *
 * Every point of the curve is the steady response of td_harmonic_compute, by its second-order
 * solve (td_synchronous_response, lib/modal/synchronous.c; its cost and accuracy: docs/api617.md), so the curve between
 * grid speeds is the exact steady response: the peak and its half-power speeds are found on it by Brent's methods
 * (GSL), not read off the grid, which only has to bracket them.
 */
#include "modal/modal_internal.h"
#include "touchdown/assess.h"
#include "util/error_internal.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_min.h>
#include <gsl/gsl_roots.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define SWEEP_START 101      /* even speeds of the first grid */
#define SWEEP_CHANGE 0.05    /* largest relative change of an amplitude between grid neighbours */
#define SWEEP_FLOOR 1e-6     /* amplitudes below this fraction of a node's largest are not refined */
#define SWEEP_NARROWEST 1e-7 /* narrowest interval, fraction of the range */
/* Peaks below PEAK_FLOOR of their node's largest amplitude are not assessed (docs/api617.md): a
 * ripple of a far mode on the flank of a dominant one is no resonance to clear. */
#define PEAK_FLOOR 1e-2
#define SPEED_TOLERANCE 1e-10 /* relative, of the half-power speeds */

struct td_sweep {
    int n, cap;      /* speeds */
    int nn;          /* response nodes */
    int *nodes;      /* nn */
    double *speed;   /* n */
    td_orbit *orbit; /* n x nn, speed-major */
    int n_peaks;
    td_response_peak *peaks;
    double operating_min, operating_max; /* rad/s, as given */
};

double td_log_decrement(double zeta)
{
    if (!isfinite(zeta) || zeta >= 1.0)
        return TD_UNDEFINED;
    return 2.0 * TD_PI * zeta / sqrt(1.0 - zeta * zeta);
}

double td_api617_required_margin(double af, int above)
{
    double f;
    if (!isfinite(af) || af <= 0.0)
        return TD_UNDEFINED;
    if (af < 2.5)
        return 0.0;
    f = 17.0 * (1.0 - 1.0 / (af - 1.5));
    return above ? fmin(26.0, 10.0 + f) : fmin(16.0, f);
}

void td_sweep_free(td_sweep **s)
{
    if (!s || !*s)
        return;
    free((*s)->nodes);
    free((*s)->speed);
    free((*s)->orbit);
    free((*s)->peaks);
    free(*s);
    *s = NULL;
}

int td_sweep_speed_count(const td_sweep *s)
{
    return s ? s->n : 0;
}
double td_sweep_speed(const td_sweep *s, int k)
{
    return s && k >= 0 && k < s->n ? s->speed[k] : NAN;
}
int td_sweep_node_count(const td_sweep *s)
{
    return s ? s->nn : 0;
}
int td_sweep_node(const td_sweep *s, int j)
{
    return s && j >= 0 && j < s->nn ? s->nodes[j] : -1;
}
td_status td_sweep_orbit(const td_sweep *s, int k, int j, td_orbit *out)
{
    if (!s || !out || k < 0 || k >= s->n || j < 0 || j >= s->nn)
        return TD_ERR_INVALID;
    *out = s->orbit[(size_t)k * (size_t)s->nn + (size_t)j];
    return TD_OK;
}
int td_sweep_peak_count(const td_sweep *s)
{
    return s ? s->n_peaks : 0;
}
void td_sweep_operating_range(const td_sweep *s, double *lo, double *hi)
{
    *lo = s ? s->operating_min : TD_UNDEFINED;
    *hi = s ? s->operating_max : TD_UNDEFINED;
}

td_status td_sweep_get_peak(const td_sweep *s, int i, td_response_peak *out)
{
    if (!s || !out || i < 0 || i >= s->n_peaks)
        return TD_ERR_INVALID;
    *out = s->peaks[i];
    return TD_OK;
}

/* The problem the curve is evaluated on. */
typedef struct sweep_problem {
    const td_system *sys;
    const td_unbalance *u;
    int n_u;
    int node; /* the node of amplitude() */
    td_synchronous *solver;
    td_status st;
    td_error *err;
} sweep_problem;

/* The orbits of nodes[0..nn) at speed w; an undamped resonance (TD_ERR_NUMERIC) gives undefined
 * orbits, any other failure is returned. */
static td_status orbits_at(sweep_problem *p, double w, const int *nodes, int nn, td_orbit *o)
{
    td_harmonic *h = NULL;
    td_error e;
    int j;
    td_status st = td_synchronous_response(p->solver, w, p->u, p->n_u, &h, &e);
    for (j = 0; j < nn; j++) {
        if (st == TD_OK)
            td_harmonic_orbit(h, nodes[j], &o[j]);
        else {
            double nan = TD_UNDEFINED;
            td_orbit undef = {nan, nan, nan, nan, nan, nan, nan, nan, nan, nan, nan, nan};
            o[j] = undef;
        }
    }
    td_harmonic_free(&h);
    if (st != TD_OK && st != TD_ERR_NUMERIC) {
        if (p->err)
            *p->err = e;
        return st;
    }
    return TD_OK;
}

/* The major semi-axis at p->node and speed w (GSL callback; a failure sets p->st, gives NaN). */
static double amplitude(double w, void *params)
{
    sweep_problem *p = params;
    td_orbit o;
    if (p->st == TD_OK)
        p->st = orbits_at(p, w, &p->node, 1, &o);
    return p->st == TD_OK ? o.major : TD_UNDEFINED;
}

static double neg_amplitude(double w, void *params)
{
    return -amplitude(w, params);
}

/* Room for `need` speeds. */
static int sweep_grow(td_sweep *s, int need)
{
    int cap = s->cap ? s->cap : 128;
    double *sp;
    td_orbit *o;
    while (cap < need)
        cap *= 2;
    if (cap == s->cap)
        return 1;
    sp = realloc(s->speed, (size_t)cap * sizeof *sp);
    if (sp)
        s->speed = sp;
    o = sp ? realloc(s->orbit, (size_t)cap * (size_t)s->nn * sizeof *o) : NULL;
    if (!o)
        return 0;
    s->orbit = o;
    s->cap = cap;
    return 1;
}

/* Insert speed w after grid point k, with its orbits. */
static td_status sweep_insert(td_sweep *s, sweep_problem *p, int k, double w)
{
    size_t nn = (size_t)s->nn;
    td_status st;
    if (!sweep_grow(s, s->n + 1))
        return td_error_set(p->err, TD_ERR_NOMEM, "modal: out of memory for the unbalance sweep");
    memmove(&s->speed[k + 2], &s->speed[k + 1], (size_t)(s->n - k - 1) * sizeof *s->speed);
    memmove(&s->orbit[(size_t)(k + 2) * nn], &s->orbit[(size_t)(k + 1) * nn],
            (size_t)(s->n - k - 1) * nn * sizeof *s->orbit);
    s->speed[k + 1] = w;
    s->n++;
    st = orbits_at(p, w, s->nodes, s->nn, &s->orbit[(size_t)(k + 1) * nn]);
    return st;
}

/* Speed w on the grid when it lies inside it (the operating range's ends: the amplitude check at the
 * clearances reads the curve there, not at the nearest grid speed). */
static td_status insert_speed(td_sweep *s, sweep_problem *p, double w)
{
    int k;
    if (!(w > s->speed[0] && w < s->speed[s->n - 1]))
        return TD_OK;
    for (k = 0; s->speed[k + 1] < w; k++)
        ;
    return s->speed[k + 1] == w ? TD_OK : sweep_insert(s, p, k, w);
}

/* The largest amplitude of node j over the grid (0 when none is finite). */
static double node_max(const td_sweep *s, int j)
{
    double m = 0.0;
    int k;
    for (k = 0; k < s->n; k++) {
        double a = s->orbit[(size_t)k * (size_t)s->nn + (size_t)j].major;
        if (isfinite(a) && a > m)
            m = a;
    }
    return m;
}

/* 1 when the interval (k, k+1) needs a speed between: an amplitude changes by more than SWEEP_CHANGE. */
static int too_coarse(const td_sweep *s, int k, const double *top)
{
    int j;
    for (j = 0; j < s->nn; j++) {
        double a0 = s->orbit[(size_t)k * (size_t)s->nn + (size_t)j].major;
        double a1 = s->orbit[(size_t)(k + 1) * (size_t)s->nn + (size_t)j].major;
        double big = fmax(a0, a1);
        if (!isfinite(a0) || !isfinite(a1) || big <= SWEEP_FLOOR * top[j])
            continue;
        if (fabs(a1 - a0) > SWEEP_CHANGE * big)
            return 1;
    }
    return 0;
}

/* Refine the grid until no interval is too coarse (or the limits of the header comment). */
static td_status sweep_refine(td_sweep *s, sweep_problem *p, double range)
{
    double top[TD_SWEEP_MAX_NODES];
    int j, k, inserted = 1;
    td_status st = TD_OK;
    while (inserted && st == TD_OK) {
        inserted = 0;
        for (j = 0; j < s->nn; j++)
            top[j] = node_max(s, j);
        for (k = 0; st == TD_OK && k + 1 < s->n && s->n < TD_SWEEP_MAX_SPEEDS; k++) {
            double w0 = s->speed[k], w1 = s->speed[k + 1];
            if (w1 - w0 <= SWEEP_NARROWEST * range || !too_coarse(s, k, top))
                continue;
            st = sweep_insert(s, p, k, 0.5 * (w0 + w1));
            k++; /* the new interval (k+1, k+2) is looked at in the next pass */
            inserted = 1;
        }
    }
    return st;
}

/* The peak of node p->node between a < w < b (guess w, a(w) above both ends): Brent's minimiser
 * of -a. *speed and *amp; the grid point when the minimiser cannot start. */
static void locate_peak(sweep_problem *p, double a, double w, double b, double *speed, double *amp)
{
    gsl_function f = {neg_amplitude, p};
    gsl_min_fminimizer *m = gsl_min_fminimizer_alloc(gsl_min_fminimizer_brent);
    int it, status = GSL_CONTINUE;
    double fw = -*amp;
    *speed = w;
    if (!m ||
        gsl_min_fminimizer_set_with_values(m, &f, w, fw, a, -amplitude(a, p), b, -amplitude(b, p)) != GSL_SUCCESS) {
        gsl_min_fminimizer_free(m);
        return;
    }
    for (it = 0; it < 100 && status == GSL_CONTINUE && p->st == TD_OK; it++) {
        if (gsl_min_fminimizer_iterate(m) != GSL_SUCCESS)
            break;
        status = gsl_min_test_interval(gsl_min_fminimizer_x_lower(m), gsl_min_fminimizer_x_upper(m), 0.0, 1e-9);
    }
    if (p->st == TD_OK && -gsl_min_fminimizer_f_minimum(m) >= *amp) {
        *speed = gsl_min_fminimizer_x_minimum(m);
        *amp = -gsl_min_fminimizer_f_minimum(m);
    }
    gsl_min_fminimizer_free(m);
}

typedef struct half_power {
    sweep_problem *p;
    double level;
} half_power;

static double below_level(double w, void *params)
{
    half_power *h = params;
    return amplitude(w, h->p) - h->level;
}

/* The speed between lo and hi (the curve crosses `level` there) where the amplitude is `level`. */
static double cross_level(sweep_problem *p, double level, double lo, double hi)
{
    half_power h = {p, level};
    gsl_function f = {below_level, &h};
    gsl_root_fsolver *r = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
    double w = TD_UNDEFINED;
    int it, status = GSL_CONTINUE;
    if (!r || gsl_root_fsolver_set(r, &f, lo, hi) != GSL_SUCCESS) {
        gsl_root_fsolver_free(r);
        return w;
    }
    for (it = 0; it < 200 && status == GSL_CONTINUE && p->st == TD_OK; it++) {
        if (gsl_root_fsolver_iterate(r) != GSL_SUCCESS)
            break;
        status = gsl_root_test_interval(gsl_root_fsolver_x_lower(r), gsl_root_fsolver_x_upper(r), 0.0, SPEED_TOLERANCE);
    }
    if (status == GSL_SUCCESS)
        w = gsl_root_fsolver_root(r);
    gsl_root_fsolver_free(r);
    return w;
}

/* The half-power speed of node j from grid point k towards `dir` (-1 down, +1 up): the first grid
 * interval where the curve falls below level; TD_UNDEFINED when it rises above the peak first or
 * stays above the level to the end of the sweep. */
static double half_power_speed(const td_sweep *s, sweep_problem *p, int j, int k, int dir, double peak)
{
    double level = peak / sqrt(2.0);
    int i;
    for (i = k + dir; i >= 0 && i < s->n; i += dir) {
        double a = s->orbit[(size_t)i * (size_t)s->nn + (size_t)j].major;
        if (!isfinite(a) || a > peak)
            return TD_UNDEFINED;
        if (a < level)
            return dir < 0 ? cross_level(p, level, s->speed[i], s->speed[i + 1])
                           : cross_level(p, level, s->speed[i - 1], s->speed[i]);
    }
    return TD_UNDEFINED;
}

/* The margin of peak speed nc from [lo, hi] (%) and the API 617 requirement of its side. */
static void assess(td_response_peak *pk, double lo, double hi)
{
    double below, above;
    pk->margin = pk->required_margin = TD_UNDEFINED;
    pk->verdict = -1;
    if (!(lo > 0.0 && hi >= lo))
        return;
    below = 100.0 * (lo - pk->speed) / lo;
    above = 100.0 * (pk->speed - hi) / hi;
    pk->margin = fmax(below, above);
    pk->required_margin = td_api617_required_margin(pk->amplification, above > below);
    if (isfinite(pk->amplification) && pk->amplification < 2.5)
        pk->verdict = 1;
    else if (isfinite(pk->required_margin))
        pk->verdict = pk->margin >= pk->required_margin;
}

/* Append the peak of node j at grid point k. */
static td_status add_peak(td_sweep *s, sweep_problem *p, int j, int k, const td_sweep_options *opt)
{
    td_response_peak pk, *grown;
    double amp = s->orbit[(size_t)k * (size_t)s->nn + (size_t)j].major;
    p->node = s->nodes[j];
    locate_peak(p, s->speed[k - 1], s->speed[k], s->speed[k + 1], &pk.speed, &amp);
    pk.node = s->nodes[j];
    pk.amplitude = amp;
    pk.speed_low = half_power_speed(s, p, j, k, -1, amp);
    pk.speed_high = half_power_speed(s, p, j, k, +1, amp);
    pk.amplification = pk.speed / (pk.speed_high - pk.speed_low);
    if (!isfinite(pk.amplification))
        pk.amplification = TD_UNDEFINED;
    assess(&pk, opt->operating_min, opt->operating_max);
    if (p->st != TD_OK)
        return p->st;
    grown = realloc(s->peaks, (size_t)(s->n_peaks + 1) * sizeof *grown);
    if (!grown)
        return td_error_set(p->err, TD_ERR_NOMEM, "modal: out of memory for the response peaks");
    s->peaks = grown;
    s->peaks[s->n_peaks++] = pk;
    return TD_OK;
}

/* Every local maximum of every node's curve of at least PEAK_FLOOR of its largest over the sweep. */
static td_status find_peaks(td_sweep *s, sweep_problem *p, const td_sweep_options *opt)
{
    int j, k;
    td_status st = TD_OK;
    for (j = 0; st == TD_OK && j < s->nn; j++) {
        double top = node_max(s, j);
        for (k = 1; st == TD_OK && k + 1 < s->n; k++) {
            double a0 = s->orbit[(size_t)(k - 1) * (size_t)s->nn + (size_t)j].major;
            double a = s->orbit[(size_t)k * (size_t)s->nn + (size_t)j].major;
            double a1 = s->orbit[(size_t)(k + 1) * (size_t)s->nn + (size_t)j].major;
            if (a > a0 && a >= a1 && a >= PEAK_FLOOR * top)
                st = add_peak(s, p, j, k, opt);
        }
    }
    return st;
}

static td_status check_sweep(const td_system *sys, const td_sweep_options *opt, td_error *err)
{
    int j;
    if (!sys || !opt || !opt->nodes)
        return td_error_set(err, TD_ERR_INVALID, "td_unbalance_sweep: NULL argument");
    if (!(opt->speed_min >= 0.0 && opt->speed_max > opt->speed_min && isfinite(opt->speed_max)))
        return td_error_set(err, TD_ERR_INVALID, "td_unbalance_sweep: the speed range %g..%g rad/s is not one",
                            opt->speed_min, opt->speed_max);
    if (opt->node_count < 1 || opt->node_count > TD_SWEEP_MAX_NODES)
        return td_error_set(err, TD_ERR_INVALID, "td_unbalance_sweep: %d response nodes (1..%d)", opt->node_count,
                            TD_SWEEP_MAX_NODES);
    for (j = 0; j < opt->node_count; j++)
        if (opt->nodes[j] < 0 || opt->nodes[j] >= sys->nnodes)
            return td_error_set(err, TD_ERR_INVALID, "td_unbalance_sweep: node %d is not one of the model's 0..%d",
                                opt->nodes[j], sys->nnodes - 1);
    return TD_OK;
}

td_status td_unbalance_sweep(const td_system *sys, const td_unbalance *u, int n_u, const td_sweep_options *opt,
                             td_sweep **out, td_error *err)
{
    sweep_problem p = {sys, u, n_u, 0, NULL, TD_OK, err};
    td_sweep *s;
    td_status st;
    int k;
    if (!out)
        return td_error_set(err, TD_ERR_INVALID, "td_unbalance_sweep: NULL output pointer");
    *out = NULL;
    if ((st = check_sweep(sys, opt, err)) != TD_OK)
        return st;
    if ((st = td_synchronous_create(sys, &p.solver, err)) != TD_OK)
        return st;
    s = calloc(1, sizeof *s);
    if (s) {
        s->nn = opt->node_count;
        s->nodes = malloc((size_t)s->nn * sizeof *s->nodes);
    }
    if (!s || !s->nodes || !sweep_grow(s, SWEEP_START)) {
        td_sweep_free(&s);
        td_synchronous_free(&p.solver);
        return td_error_set(err, TD_ERR_NOMEM, "modal: out of memory for the unbalance sweep");
    }
    memcpy(s->nodes, opt->nodes, (size_t)s->nn * sizeof *s->nodes);
    s->operating_min = opt->operating_min;
    s->operating_max = opt->operating_max;
    for (k = 0; st == TD_OK && k < SWEEP_START; k++) {
        s->speed[k] = opt->speed_min + (opt->speed_max - opt->speed_min) * k / (SWEEP_START - 1);
        s->n = k + 1;
        st = orbits_at(&p, s->speed[k], s->nodes, s->nn, &s->orbit[(size_t)k * (size_t)s->nn]);
    }
    if (st == TD_OK)
        st = insert_speed(s, &p, opt->operating_min);
    if (st == TD_OK)
        st = insert_speed(s, &p, opt->operating_max);
    if (st == TD_OK)
        st = sweep_refine(s, &p, opt->speed_max - opt->speed_min);
    if (st == TD_OK)
        st = find_peaks(s, &p, opt);
    td_synchronous_free(&p.solver);
    if (st != TD_OK) {
        td_sweep_free(&s);
        return st;
    }
    *out = s;
    return TD_OK;
}

/* Insert `node` into the ascending set nodes[0..*n) (capacity cap; the count still grows past it). */
static void node_set_add(int *nodes, int *n, int cap, int node)
{
    int i, j;
    for (i = 0; i < *n && i < cap; i++)
        if (nodes[i] == node)
            return;
        else if (nodes[i] > node)
            break;
    for (j = (*n < cap ? *n : cap - 1); j > i; j--)
        nodes[j] = nodes[j - 1];
    if (i < cap)
        nodes[i] = node;
    (*n)++;
}

int td_modal_default_response_nodes(const td_model *m, int *nodes, int capacity)
{
    int n = 0, i;
    if (!m || (!nodes && capacity > 0))
        return 0;
    for (i = 0; i < td_model_disc_count(m); i++) {
        td_disc d;
        td_model_get_disc(m, i, &d);
        node_set_add(nodes, &n, capacity, d.node);
    }
    for (i = 0; i < td_model_amb_count(m); i++) {
        td_amb a;
        td_model_get_amb(m, i, &a);
        node_set_add(nodes, &n, capacity, a.sensor_node);
    }
    for (i = 0; i < td_model_retainer_count(m); i++) {
        td_retainer r;
        td_model_get_retainer(m, i, &r);
        node_set_add(nodes, &n, capacity, r.node);
    }
    return n;
}

/* The lateral displacement (DOF offset c: 0 x, 1 y) of `node` in the expanded static state. */
static double static_node(const double *q_phys, int node, int c)
{
    return q_phys[TD_DOF(node, c ? TD_DOF_Y : TD_DOF_X)];
}

/* Static force of AMB axis a on the rotor, ks x + Fc with Fc the lag state, or the law's command
 * at rest (vs = 0) when the axis has no lag; TD_UNDEFINED for a lag-free axis a controller drives. */
static double static_amb_force(const td_system *sys, const td_amb_axis *a, const double *z, const double *q_phys)
{
    td_amb amb;
    double x, xs, e, fc;
    const double *w = z + 2 * sys->ndof;
    if (a->off)
        return 0.0;
    td_model_get_amb(sys->model, a->amb, &amb);
    x = static_node(q_phys, amb.node, a->axis);
    xs = static_node(q_phys, amb.sensor_node, a->axis);
    e = a->integral >= 0 ? w[a->integral] : 0.0;
    if (a->state >= 0)
        fc = w[a->state];
    else if (a->law < 0)
        fc = td_amb_axis_command(a, xs, 0.0, e);
    else
        return TD_UNDEFINED;
    return a->ks * x + fc; /* linear: saturation is ignored, as in the rest of the analysis */
}

td_status td_static_reactions(const td_system *sys, double *amb, double *bearing, td_error *err)
{
    int n, i;
    double *z, *q;
    td_status st;
    if (!sys)
        return td_error_set(err, TD_ERR_INVALID, "td_static_reactions: NULL system");
    n = td_modal_state_count(sys);
    z = malloc((size_t)n * sizeof *z);
    q = malloc((size_t)sys->nphys * sizeof *q);
    if (!z || !q) {
        free(z);
        free(q);
        return td_error_set(err, TD_ERR_NOMEM, "modal: out of memory for the static reactions");
    }
    st = td_modal_start_state(sys, 0.0, NULL, 0, 1, 0.0, z, err);
    if (st == TD_OK)
        st = td_system_expand(sys, z, q, err);
    for (i = 0; st == TD_OK && amb && i < sys->n_amb_axes; i++)
        amb[2 * sys->amb_axes[i].amb + sys->amb_axes[i].axis] = static_amb_force(sys, &sys->amb_axes[i], z, q);
    for (i = 0; st == TD_OK && bearing && i < td_model_bearing_count(sys->model); i++) {
        td_bearing b;
        td_model_get_bearing(sys->model, i, &b);
        bearing[2 * i] = -b.kxx * static_node(q, b.node, 0);
        bearing[2 * i + 1] = -b.kyy * static_node(q, b.node, 1);
    }
    free(z);
    free(q);
    return st;
}

td_status td_sweep_sensor_zones(const td_sweep *s, const td_model *m, int *zones, double *c_min, td_error *err)
{
    td_limits lim;
    int i, j, k, na;
    if (!s || !m || !zones || !c_min)
        return td_error_set(err, TD_ERR_INVALID, "td_sweep_sensor_zones: NULL argument");
    na = td_model_amb_count(m);
    td_model_get_limits(m, &lim);
    *c_min = td_model_min_retainer_clearance(m);
    for (i = 0; i < na; i++) {
        td_amb a;
        td_model_get_amb(m, i, &a);
        for (j = 0; j < s->nn && s->nodes[j] != a.sensor_node; j++)
            ;
        if (j == s->nn)
            return td_error_set(err, TD_ERR_INVALID,
                                "td_sweep_sensor_zones: the sensor node %d of AMB %d is not a response node",
                                a.sensor_node, i);
        for (k = 0; k < s->n; k++)
            zones[(size_t)k * (size_t)na + (size_t)i] =
                td_vibration_zone_of(s->orbit[(size_t)k * (size_t)s->nn + (size_t)j].major, *c_min, &lim.zones);
    }
    return TD_OK;
}

/* The largest major semi-axis of response node j over lo..hi (grid speeds and the located peaks,
 * which the grid only brackets) into c; undefined when the response is somewhere undefined there. */
static void largest_in(const td_sweep *s, int j, double lo, double hi, td_clearance_check *c)
{
    int k;
    c->amplitude = c->speed = TD_UNDEFINED;
    for (k = 0; k < s->n; k++) {
        double a = s->orbit[(size_t)k * (size_t)s->nn + (size_t)j].major;
        if (s->speed[k] < lo || s->speed[k] > hi)
            continue;
        if (!isfinite(a)) { /* an undamped resonance: no amplitude to compare */
            c->amplitude = c->speed = TD_UNDEFINED;
            return;
        }
        if (!(a <= c->amplitude)) {
            c->amplitude = a;
            c->speed = s->speed[k];
        }
    }
    for (k = 0; k < s->n_peaks; k++) {
        const td_response_peak *p = &s->peaks[k];
        if (p->node == s->nodes[j] && p->speed >= lo && p->speed <= hi && p->amplitude > c->amplitude) {
            c->amplitude = p->amplitude;
            c->speed = p->speed;
        }
    }
}

void td_sweep_clearance_range(const td_sweep *s, double *lo, double *hi)
{
    *lo = *hi = TD_UNDEFINED;
    if (!s || s->n < 1)
        return;
    if (s->operating_min > 0.0 && s->operating_max >= s->operating_min) { /* as assess() takes it */
        *lo = s->operating_min;
        *hi = s->operating_max;
    } else {
        *lo = s->speed[0];
        *hi = s->speed[s->n - 1];
    }
}

td_status td_sweep_clearance_check(const td_sweep *s, const td_model *m, td_clearance_check *out, td_error *err)
{
    double lo, hi;
    int i, j;
    if (!s || !m || (!out && td_model_retainer_count(m) > 0))
        return td_error_set(err, TD_ERR_INVALID, "td_sweep_clearance_check: NULL argument");
    td_sweep_clearance_range(s, &lo, &hi);
    for (i = 0; i < td_model_retainer_count(m); i++) {
        td_retainer r;
        td_clearance_check *c = &out[i];
        td_model_get_retainer(m, i, &r);
        c->node = r.node;
        c->clearance = r.clearance;
        c->amplitude = c->speed = TD_UNDEFINED;
        for (j = 0; j < s->nn && s->nodes[j] != r.node; j++)
            ;
        if (j < s->nn)
            largest_in(s, j, lo, hi, c);
        c->ratio = c->amplitude / c->clearance;
        c->verdict = isfinite(c->ratio) ? c->ratio <= TD_API617_CLEARANCE_FRACTION : -1;
        if (!isfinite(c->ratio))
            c->ratio = TD_UNDEFINED;
    }
    return TD_OK;
}
