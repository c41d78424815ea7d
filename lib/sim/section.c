/*
 * The once-per-revolution section (section.h). The spin angle is phi(t) = spin_ref + omega (t -
 * t_spin_ref) at a prescribed constant speed, or the spin DOF's own angle when the speed varies
 * (spin.c). Over each stretch the simulation has just covered (an accepted IDA step, the part of
 * one up to a stop, a flight), every t with phi(t) = 2 pi k in it is found (in closed form, or by
 * a safeguarded secant on the interpolated angle) and the state there read from that stretch's
 * interpolant into work space: y and the integrator are never touched.
 */
#include "sim/section.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sim/sim_internal.h"
#include "util/error_internal.h"

/* Secant iterations on a crossing of the interpolated angle; each at least halves the bracket. */
#define SECTION_MAX_ITER 100

struct td_sim_section {
    double t_from;  /* crossings before this time are not kept (the transient) */
    double t_done;  /* crossings up to here are taken */
    int capacity;   /* crossings kept, the last ones */
    long count;     /* crossings taken since t_from */
    long high;      /* the most count has been (a rewind lowers count; slots before high -
                       capacity are overwritten) */
    double *time;   /* capacity: a ring, crossing i at i % capacity */
    double *radius; /* capacity x nr: retainer k's node radius of crossing i at (i % capacity) nr + k */
    double *y;      /* neq: the state at a crossing */
    double *work;   /* 2 neq: the flight's modal coordinates */
    N_Vector dky;   /* IDA's interpolant at a crossing */
};

typedef struct td_sim_section section;

/* Where the state between steps comes from. */
typedef enum { FROM_IDA, FROM_FLIGHT } source;

void td_sim_section_free(td_sim *s)
{
    section *c = s ? s->section : NULL;
    if (!c)
        return;
    free(c->time);
    free(c->radius);
    free(c->y);
    free(c->work);
    if (c->dky)
        N_VDestroy(c->dky);
    free(c);
    s->section = NULL;
}

td_status td_sim_section_begin(td_sim *s, double t_from, int capacity, td_error *err)
{
    section *c;
    size_t neq;
    if (!s || capacity <= 0 || isnan(t_from))
        return td_error_set(err, TD_ERR_INVALID, "td_sim_section_begin: NULL simulation or no capacity");
    td_sim_section_free(s);
    neq = (size_t)s->dae.neq;
    c = calloc(1, sizeof *c);
    if (c) {
        c->time = calloc((size_t)capacity, sizeof *c->time);
        c->radius = calloc((size_t)capacity * (size_t)(s->dae.nr > 0 ? s->dae.nr : 1), sizeof *c->radius);
        c->y = calloc(neq, sizeof *c->y);
        c->work = calloc(2 * neq, sizeof *c->work);
        c->dky = N_VClone(s->dae.y);
    }
    s->section = c;
    if (!c || !c->time || !c->radius || !c->y || !c->work || !c->dky) {
        td_sim_section_free(s);
        return td_error_set(err, TD_ERR_NOMEM, "out of memory for the once-per-revolution section");
    }
    c->t_from = t_from;
    c->t_done = s->dae.t;
    c->capacity = capacity;
    return TD_OK;
}

/* The state at t into c->y: IDA's interpolant (t inside its last step) or the flight's closed
 * form (displacements only, the rest as at s->dae.t). 0 if it cannot be had. */
static int state_at(td_sim *s, source from, double t)
{
    section *c = s->section;
    if (from == FROM_FLIGHT) {
        memcpy(c->y, N_VGetArrayPointer(s->dae.y), sizeof(double) * (size_t)s->dae.neq);
        return td_sim_flight_peek(s, t, c->y, c->work);
    }
    if (IDAGetDky(s->solver.ida, t, 0, c->dky) != IDA_SUCCESS)
        return 0;
    memcpy(c->y, N_VGetArrayPointer(c->dky), sizeof(double) * (size_t)s->dae.neq);
    td_sim_spin_hold(s, t, c->y, NULL);
    return 1;
}

/* The spin angle at t on the stretch's interpolant; NAN if the state cannot be had. */
static double angle_at(td_sim *s, source from, double t)
{
    if (s->machine.spin < 0) /* prescribed: phi(t) in closed form, no state needed */
        return s->machine.spin_ref + s->machine.omega * (t - s->machine.t_spin_ref);
    return state_at(s, from, t) ? td_sim_rotor_angle(s, t, s->section->y) : NAN;
}

/* The time in [a, b] where the angle is `target`, the angle being phi_a at a and phi_b at b on
 * either side of it: exact at a prescribed speed, else a secant kept inside its bracket. */
static double crossing_time(td_sim *s, source from, double a, double b, double phi_a, double phi_b, double target)
{
    int i;
    if (s->machine.spin < 0)
        return s->machine.t_spin_ref + (target - s->machine.spin_ref) / s->machine.omega;
    for (i = 0; i < SECTION_MAX_ITER && b - a > 4.0 * DBL_EPSILON * fmax(fabs(b), 1.0); i++) {
        double t = a + (b - a) * (target - phi_a) / (phi_b - phi_a), mid = 0.5 * (a + b), phi;
        /* a secant point too near an end would shrink the bracket slowly: bisect instead */
        if (!(t > a + 0.01 * (b - a) && t < b - 0.01 * (b - a)))
            t = mid;
        phi = angle_at(s, from, t);
        if (isnan(phi))
            return NAN;
        if ((phi - target) * (phi_a - target) > 0.0) {
            a = t;
            phi_a = phi;
        } else {
            b = t;
            phi_b = phi;
        }
    }
    return fabs(phi_a - target) < fabs(phi_b - target) ? a : b;
}

/* Record crossing time t: every retainer node's radius there. */
static void record(td_sim *s, source from, double t)
{
    section *c = s->section;
    long slot = c->count % c->capacity;
    int k;
    if (t + s->monitor.leapt < c->t_from || !state_at(s, from, t))
        return;
    c->time[slot] = t + s->monitor.leapt;
    if (++c->count > c->high)
        c->high = c->count;
    for (k = 0; k < s->dae.nr; k++) {
        double x, yy, vx, vy;
        td_sim_node_state(s, k, c->y, &x, &yy, &vx, &vy);
        c->radius[slot * s->dae.nr + k] = hypot(x, yy);
    }
}

/* Every crossing of a multiple of 2 pi in (c->t_done, t]: phi_a < 2 pi k <= phi_b going forward,
 * phi_b <= 2 pi k < phi_a backward. */
static void cover(td_sim *s, source from, double t)
{
    section *c = s->section;
    double a = c->t_done, phi_a, phi_b, lo, hi, k;
    if (!(t > a))
        return;
    c->t_done = t;
    if (t + s->monitor.leapt < c->t_from)
        return;
    phi_a = angle_at(s, from, a);
    phi_b = angle_at(s, from, t);
    if (isnan(phi_a) || isnan(phi_b) || phi_a == phi_b)
        return;
    lo = fmin(phi_a, phi_b) / (2.0 * TD_PI);
    hi = fmax(phi_a, phi_b) / (2.0 * TD_PI);
    for (k = phi_b > phi_a ? floor(lo) + 1.0 : ceil(lo); phi_b > phi_a ? k <= hi : k < hi; k += 1.0) {
        double tc = crossing_time(s, from, a, t, phi_a, phi_b, 2.0 * TD_PI * k);
        if (!isnan(tc))
            record(s, from, fmin(fmax(tc, a), t));
    }
}

void td_sim_section_ida(td_sim *s, double t)
{
    if (s->section)
        cover(s, FROM_IDA, t);
}

void td_sim_section_flight(td_sim *s, double t)
{
    if (s->section)
        cover(s, FROM_FLIGHT, t);
}

void td_sim_section_rewind(td_sim *s)
{
    section *c = s->section;
    if (!c || c->t_done <= s->dae.t)
        return;
    while (c->count > 0 && c->time[(c->count - 1) % c->capacity] > s->dae.t + s->monitor.leapt)
        c->count--;
    c->t_done = s->dae.t;
}

void td_sim_section_end(td_sim *s)
{
    if (s)
        td_sim_section_free(s);
}

/* The crossings taken up to the time reached: an integrator step is covered whole when it is
 * accepted, and an output inside it leaves its crossings beyond the output stored, to count once
 * the run gets there (as the retainers' totals take back the part of the step beyond it), never at
 * an end_time before them. */
static long reached_count(const td_sim *s)
{
    const section *c = s->section;
    long n = c->count, kept = c->high - c->capacity > 0 ? c->high - c->capacity : 0;
    while (n > kept && c->time[(n - 1) % c->capacity] > s->dae.t + s->monitor.leapt)
        n--;
    return n;
}

long td_sim_section_count(const td_sim *s)
{
    return s && s->section ? reached_count(s) : 0;
}

int td_sim_section_read(const td_sim *s, int retainer, double *t, double *r, int max)
{
    const section *c = s ? s->section : NULL;
    long first, i, count;
    int n = 0;
    if (!c || retainer < 0 || retainer >= s->dae.nr || max <= 0)
        return 0;
    count = reached_count(s);
    first = c->high - c->capacity > 0 ? c->high - c->capacity : 0;
    if (count - first > max)
        first = count - max;
    for (i = first; i < count; i++, n++) {
        long slot = i % c->capacity;
        if (t)
            t[n] = c->time[slot];
        if (r)
            r[n] = c->radius[slot * s->dae.nr + retainer];
    }
    return n;
}
