/*
 * The housing's prescribed motion (touchdown/housing.h): its pulses, history and reference point,
 * each checked once as it is added, and its exact evaluation. Every pulse shape has closed-form
 * integrals (docs/theory.md, "Base motion"); the piecewise-linear history is integrated exactly
 * segment by segment, its running integrals kept at each point so that an evaluation is one binary
 * search.
 */
#include "model/model_internal.h"
#include "touchdown/dofs.h"
#include "util/error_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const td_error_site no_site = {NULL, 0, NULL};

#define FAIL_AT(err, part, index, field, ...)                                                                          \
    td_error_set_site((err), TD_ERR_INVALID, &(td_error_site){(part), (index), (field)}, &no_site, __VA_ARGS__)

/* Columns of a history row (model_internal.h). */
enum { H_T, H_AX, H_AY, H_VX, H_VY, H_DX, H_DY, H_COLS };

void td_model_free_housing(td_model *m)
{
    free(m->shocks.items);
    free(m->rotations.items);
    free(m->history);
    memset(&m->shocks, 0, sizeof m->shocks);
    memset(&m->rotations, 0, sizeof m->rotations);
    m->history = NULL;
    m->history_count = 0;
}

/* A copy of `count` items of `size` bytes, or NULL (none, or out of memory: *ok = 0). */
static void *copy_of(const void *items, int count, size_t size, int *ok)
{
    void *p;
    if (count == 0)
        return NULL;
    p = malloc((size_t)count * size);
    if (!p)
        *ok = 0;
    else
        memcpy(p, items, (size_t)count * size);
    return p;
}

int td_model_clone_housing(td_model *m, const td_model *src)
{
    int ok = 1;
    m->shocks.items = copy_of(src->shocks.items, src->shocks.count, sizeof *src->shocks.items, &ok);
    m->shocks.count = m->shocks.capacity = m->shocks.items ? src->shocks.count : 0;
    m->rotations.items = copy_of(src->rotations.items, src->rotations.count, sizeof *src->rotations.items, &ok);
    m->rotations.count = m->rotations.capacity = m->rotations.items ? src->rotations.count : 0;
    m->history = copy_of(src->history, src->history_count * H_COLS, sizeof *src->history, &ok);
    m->history_count = m->history ? src->history_count : 0;
    m->housing_reference = src->housing_reference;
    m->has_housing_reference = src->has_housing_reference;
    return ok;
}

/* ---- the rules ----------------------------------------------------------------------------- */

/* A pulse's values (part "shock" or "rotation", index i); its direction normalised into *out. */
static td_status check_pulse(const td_housing_pulse *p, const char *part, int i, td_housing_pulse *out, td_error *err)
{
    double scale, norm;
    if (p->shape < TD_PULSE_HALF_SINE || p->shape > TD_PULSE_RAMP)
        return FAIL_AT(err, part, i, "shape", "unknown shape %d", (int)p->shape);
    if (!(isfinite(p->amplitude) && p->amplitude > 0.0))
        return FAIL_AT(err, part, i, "amplitude", "must be > 0 (got %g)", p->amplitude);
    if (!(isfinite(p->duration) && p->duration > 0.0))
        return FAIL_AT(err, part, i, "duration", "must be > 0 s (got %g)", p->duration);
    if (!(isfinite(p->start) && p->start >= 0.0))
        return FAIL_AT(err, part, i, "start", "must be >= 0 s (got %g)", p->start);
    if (!isfinite(p->start + p->duration))
        return FAIL_AT(err, part, i, "duration", "start + duration overflows (%g + %g s)", p->start, p->duration);
    if (!isfinite(p->direction[0]) || !isfinite(p->direction[1]))
        return FAIL_AT(err, part, i, "direction", "must be finite (got [%g, %g])", p->direction[0], p->direction[1]);
    /* scaled by the larger component first, so that the norm cannot overflow */
    scale = fmax(fabs(p->direction[0]), fabs(p->direction[1]));
    if (!(scale > 0.0))
        return FAIL_AT(err, part, i, "direction", "must not be the zero vector");
    *out = *p;
    norm = hypot(p->direction[0] / scale, p->direction[1] / scale);
    out->direction[0] = p->direction[0] / scale / norm;
    out->direction[1] = p->direction[1] / scale / norm;
    return TD_OK;
}

/* Append *p to a pulse array (items, count, capacity). */
static td_status append_pulse(td_housing_pulse **items, int *count, int *capacity, const td_housing_pulse *p,
                              td_error *err)
{
    if (*count == *capacity) {
        int cap = *capacity ? 2 * *capacity : 4;
        td_housing_pulse *q = realloc(*items, (size_t)cap * sizeof *q);
        if (!q)
            return td_error_set(err, TD_ERR_NOMEM, "out of memory adding a housing motion");
        *items = q;
        *capacity = cap;
    }
    (*items)[(*count)++] = *p;
    return TD_OK;
}

td_status td_model_add_housing_shock(td_model *m, const td_housing_pulse *p, td_error *err)
{
    td_housing_pulse q;
    if (!m || !p)
        return td_error_set(err, TD_ERR_INVALID, "housing shock: NULL argument");
    if (check_pulse(p, "shock", m->shocks.count, &q, err))
        return TD_ERR_INVALID;
    return append_pulse(&m->shocks.items, &m->shocks.count, &m->shocks.capacity, &q, err);
}

td_status td_model_add_housing_rotation(td_model *m, const td_housing_pulse *p, td_error *err)
{
    td_housing_pulse q;
    if (!m || !p)
        return td_error_set(err, TD_ERR_INVALID, "housing rotation: NULL argument");
    if (check_pulse(p, "rotation", m->rotations.count, &q, err))
        return TD_ERR_INVALID;
    /* A rate that falls from A to 0 at once has alpha = -A delta(t - end): an angular impulse that the
     * load -M T alpha (docs/theory.md, "Base motion") cannot apply between integrator steps, so the
     * rotor's relative velocity would miss its jump of +T A. An acceleration's jump (a shock's
     * sawtooth) is only a step of the load, which the integrator stops at. */
    if (q.shape == TD_PULSE_SAWTOOTH)
        return FAIL_AT(err, "rotation", m->rotations.count, "shape",
                       "a rate that drops at once is an angular impulse: use triangle or versine");
    return append_pulse(&m->rotations.items, &m->rotations.count, &m->rotations.capacity, &q, err);
}

/* The history's points: finite, t[0] >= 0 (the housing is at rest from t = 0), t increasing. */
static td_status check_history(int n, const double *t, const double *ax, const double *ay, td_error *err)
{
    int i;
    if (n < 2)
        return FAIL_AT(err, "history", -1, "time", "needs at least 2 points (got %d)", n);
    for (i = 0; i < n; i++) {
        if (!isfinite(t[i]))
            return FAIL_AT(err, "history", i, "time", "must be finite (got %g)", t[i]);
        if (i == 0 && t[i] < 0.0)
            return FAIL_AT(err, "history", i, "time",
                           "must be >= 0 s (got %g; the run starts at 0 with the housing at rest)", t[i]);
        if (i > 0 && !(t[i] > t[i - 1]))
            return FAIL_AT(err, "history", i, "time", "must come after the previous point's %g s, not %g s", t[i - 1],
                           t[i]);
        if (!isfinite(ax[i]))
            return FAIL_AT(err, "history", i, "x", "must be finite (got %g)", ax[i]);
        if (!isfinite(ay[i]))
            return FAIL_AT(err, "history", i, "y", "must be finite (got %g)", ay[i]);
    }
    return TD_OK;
}

td_status td_model_set_housing_history(td_model *m, int n, const double *t, const double *ax, const double *ay,
                                       td_error *err)
{
    double *h;
    int i, c;
    if (!m || (n > 0 && (!t || !ax || !ay)))
        return td_error_set(err, TD_ERR_INVALID, "housing history: NULL argument");
    if (check_history(n, t, ax, ay, err))
        return TD_ERR_INVALID;
    h = malloc((size_t)n * H_COLS * sizeof *h);
    if (!h)
        return td_error_set(err, TD_ERR_NOMEM, "out of memory setting the housing's history");
    for (i = 0; i < n; i++) {
        double *r = h + (size_t)i * H_COLS;
        r[H_T] = t[i], r[H_AX] = ax[i], r[H_AY] = ay[i];
        for (c = 0; c < 2; c++) {
            /* over a segment of length d with end values a0, a1: v gains d (a0 + a1) / 2,
             * x gains d v0 + d^2 (2 a0 + a1) / 6 (the exact integrals of a linear a) */
            const double *p = r - H_COLS;
            double d = i > 0 ? r[H_T] - p[H_T] : 0.0;
            r[H_VX + c] = i > 0 ? p[H_VX + c] + 0.5 * d * (p[H_AX + c] + r[H_AX + c]) : 0.0;
            r[H_DX + c] = i > 0 ? p[H_DX + c] + d * p[H_VX + c] + d * d * (2.0 * p[H_AX + c] + r[H_AX + c]) / 6.0 : 0.0;
        }
    }
    free(m->history);
    m->history = h;
    m->history_count = n;
    return TD_OK;
}

td_status td_model_set_housing_reference(td_model *m, double z, td_error *err)
{
    if (!m)
        return td_error_set(err, TD_ERR_INVALID, "housing reference: NULL model");
    if (!isfinite(z))
        return FAIL_AT(err, "housing", 0, "reference", "must be finite (got %g)", z);
    m->housing_reference = z;
    m->has_housing_reference = 1;
    return TD_OK;
}

int td_model_has_housing_motion(const td_model *m)
{
    return m && (m->shocks.count > 0 || m->rotations.count > 0 || m->history_count > 0);
}

int td_model_housing_shock_count(const td_model *m)
{
    return m ? m->shocks.count : 0;
}
int td_model_housing_rotation_count(const td_model *m)
{
    return m ? m->rotations.count : 0;
}
int td_model_housing_history_count(const td_model *m)
{
    return m ? m->history_count : 0;
}

td_status td_model_get_housing_shock(const td_model *m, int i, td_housing_pulse *out)
{
    if (!m || !out || i < 0 || i >= m->shocks.count)
        return TD_ERR_INVALID;
    *out = m->shocks.items[i];
    return TD_OK;
}

td_status td_model_get_housing_rotation(const td_model *m, int i, td_housing_pulse *out)
{
    if (!m || !out || i < 0 || i >= m->rotations.count)
        return TD_ERR_INVALID;
    *out = m->rotations.items[i];
    return TD_OK;
}

/* ---- evaluation ---------------------------------------------------------------------------- */

/* x - sin x without the cancellation of small x (its Taylor series below 1, to rounding). */
static double x_minus_sin(double x)
{
    double term, sum = 0.0, x2 = x * x;
    int k;
    if (fabs(x) >= 1.0)
        return x - sin(x);
    term = x * x2 / 6.0; /* x^3 / 3! */
    for (k = 5; fabs(term) > 1e-18 * fabs(sum) && k < 40; k += 2) {
        sum += term;
        term *= -x2 / ((double)(k - 1) * (double)k);
    }
    return sum;
}

/* x^2 / 2 - (1 - cos x) likewise (its series x^4/4! - x^6/6! + ... below 1). */
static double cos_rest(double x)
{
    double term, sum = 0.0, x2 = x * x;
    int k;
    if (fabs(x) >= 1.0)
        return 0.5 * x2 - 2.0 * sin(0.5 * x) * sin(0.5 * x);
    term = x2 * x2 / 24.0;
    for (k = 6; fabs(term) > 1e-18 * fabs(sum) && k < 40; k += 2) {
        sum += term;
        term *= -x2 / ((double)(k - 1) * (double)k);
    }
    return sum;
}

/* Pulse of unit amplitude and duration T at tau in [0, T] (tau = t - start; `later`: a triangle
 * past its peak): out = {p', p, its integral, its double integral}, each from 0 at tau = 0. */
static void unit_pulse_inside(td_pulse_shape shape, double T, double tau, int later, double out[4])
{
    double s, x;
    switch (shape) {
    case TD_PULSE_HALF_SINE: /* sin(pi tau / T) */
        x = TD_PI * tau / T;
        s = T / TD_PI;
        out[0] = cos(x) / s, out[1] = sin(x), out[2] = s * 2.0 * sin(0.5 * x) * sin(0.5 * x);
        out[3] = s * s * x_minus_sin(x);
        return;
    case TD_PULSE_TRIANGLE: /* 2 tau / T to the peak 1 at T/2, then back down */
        if (!later) {
            out[0] = 2.0 / T, out[1] = 2.0 * tau / T, out[2] = tau * tau / T, out[3] = tau * tau * tau / (3.0 * T);
            return;
        }
        s = tau - 0.5 * T;
        out[0] = -2.0 / T, out[1] = 1.0 - 2.0 * s / T, out[2] = 0.25 * T + s - s * s / T;
        out[3] = T * T / 24.0 + 0.25 * T * s + 0.5 * s * s - s * s * s / (3.0 * T);
        return;
    case TD_PULSE_VERSINE: /* (1 - cos(2 pi tau / T)) / 2 */
        x = 2.0 * TD_PI * tau / T;
        s = T / (2.0 * TD_PI);
        out[0] = 0.5 * sin(x) / s, out[1] = sin(0.5 * x) * sin(0.5 * x), out[2] = 0.5 * s * x_minus_sin(x);
        out[3] = 0.5 * s * s * cos_rest(x);
        return;
    case TD_PULSE_SAWTOOTH: /* the final-peak sawtooth and the ramp's rise: tau / T */
    case TD_PULSE_RAMP:
        out[0] = 1.0 / T, out[1] = tau / T, out[2] = 0.5 * tau * tau / T, out[3] = tau * tau * tau / (6.0 * T);
        return;
    }
    memset(out, 0, 4 * sizeof *out);
}

/* Pulse p at time t: out = {rate of change, value, integral, double integral}, from rest at t = 0
 * (before its start all 0; after its end the pulse is 0, or held for a ramp, and the integrals go on). */
static void pulse_at(const td_housing_pulse *p, double t, double out[4])
{
    /* the kinks compared as td_model_housing_next_kink computes them, so that at a stop there the
     * pulse is the one after it */
    double T = p->duration, end_t = p->start + T, end[4];
    int k;
    if (!(t >= p->start)) {
        memset(out, 0, 4 * sizeof *out);
        return;
    }
    if (t < end_t) {
        unit_pulse_inside(p->shape, T, fmin(t - p->start, T), t >= p->start + 0.5 * T, out);
    } else {
        double s = t - end_t;
        /* the integrals at the end: 2T/pi and T^2/pi (half-sine), T/2 and T^2/4 (triangle,
         * versine), T/2 and T^2/6 (sawtooth, ramp) */
        if (p->shape == TD_PULSE_HALF_SINE)
            end[2] = 2.0 * T / TD_PI, end[3] = T * T / TD_PI;
        else if (p->shape == TD_PULSE_TRIANGLE || p->shape == TD_PULSE_VERSINE)
            end[2] = 0.5 * T, end[3] = 0.25 * T * T;
        else
            end[2] = 0.5 * T, end[3] = T * T / 6.0;
        if (p->shape == TD_PULSE_RAMP) { /* held at 1 */
            out[0] = 0.0, out[1] = 1.0, out[2] = end[2] + s, out[3] = end[3] + end[2] * s + 0.5 * s * s;
        } else {
            out[0] = 0.0, out[1] = 0.0, out[2] = end[2], out[3] = end[3] + end[2] * s;
        }
    }
    for (k = 0; k < 4; k++)
        out[k] *= p->amplitude;
}

/* The history's acceleration, velocity and displacement at t into acc, vel, dis (added to them). */
static void history_at(const td_model *m, double t, double *acc, double *vel, double *dis)
{
    const double *h = m->history, *last = h + (size_t)(m->history_count - 1) * H_COLS;
    int lo = 0, hi = m->history_count - 1, c;
    if (!(t >= h[H_T]))
        return;
    if (t >= last[H_T]) { /* after the record: no acceleration, the velocity reached held */
        for (c = 0; c < 2; c++) {
            vel[c] += last[H_VX + c];
            dis[c] += last[H_DX + c] + last[H_VX + c] * (t - last[H_T]);
        }
        return;
    }
    while (hi - lo > 1) { /* the segment [lo, lo + 1] holding t */
        int mid = lo + (hi - lo) / 2;
        if (h[(size_t)mid * H_COLS + H_T] <= t)
            lo = mid;
        else
            hi = mid;
    }
    {
        const double *a = h + (size_t)lo * H_COLS, *b = a + H_COLS;
        double s = t - a[H_T], d = b[H_T] - a[H_T];
        for (c = 0; c < 2; c++) {
            double slope = (b[H_AX + c] - a[H_AX + c]) / d;
            acc[c] += a[H_AX + c] + slope * s;
            vel[c] += a[H_VX + c] + s * (a[H_AX + c] + 0.5 * slope * s);
            dis[c] += a[H_DX + c] + s * (a[H_VX + c] + s * (0.5 * a[H_AX + c] + slope * s / 6.0));
        }
    }
}

void td_model_housing_motion_at(const td_model *m, double t, td_housing_motion *out)
{
    int i, c;
    if (!out)
        return;
    memset(out, 0, sizeof *out);
    if (!m)
        return;
    for (i = 0; i < m->shocks.count; i++) {
        const td_housing_pulse *p = &m->shocks.items[i];
        double v[4];
        pulse_at(p, t, v);
        for (c = 0; c < 2; c++) {
            out->acceleration[c] += v[1] * p->direction[c];
            out->velocity[c] += v[2] * p->direction[c];
            out->displacement[c] += v[3] * p->direction[c];
        }
    }
    if (m->history_count > 0)
        history_at(m, t, out->acceleration, out->velocity, out->displacement);
    for (i = 0; i < m->rotations.count; i++) {
        const td_housing_pulse *p = &m->rotations.items[i];
        double v[4];
        pulse_at(p, t, v);
        for (c = 0; c < 2; c++) {
            out->rate_change[c] += v[0] * p->direction[c];
            out->rate[c] += v[1] * p->direction[c];
            out->angle[c] += v[2] * p->direction[c];
        }
    }
}

/* The smaller of *next and the first of a pulse's kinks after t: its start, a triangle's peak (its
 * slope jumps there: a rotation's rate change, and the load M T alpha, step), its end. */
static void pulse_kinks(const td_housing_pulse *p, double t, double *next)
{
    double end = p->start + p->duration, peak = p->start + 0.5 * p->duration;
    if (p->start > t)
        *next = fmin(*next, p->start);
    else if (p->shape == TD_PULSE_TRIANGLE && peak > t)
        *next = fmin(*next, peak);
    else if (end > t)
        *next = fmin(*next, end);
}

double td_model_housing_next_kink(const td_model *m, double t)
{
    double next = INFINITY;
    int i;
    if (!m)
        return next;
    for (i = 0; i < m->shocks.count; i++)
        pulse_kinks(&m->shocks.items[i], t, &next);
    for (i = 0; i < m->rotations.count; i++)
        pulse_kinks(&m->rotations.items[i], t, &next);
    if (m->history_count > 0) {
        double first = m->history[H_T], last = m->history[(size_t)(m->history_count - 1) * H_COLS + H_T];
        if (first > t)
            next = fmin(next, first);
        else if (last > t)
            next = fmin(next, last);
    }
    return next;
}
