/*
 * blocks.c - the blocks of a controller drawn as a chain (gain, PID, lead-lag, low-pass, notch, resonant),
 * each realised by its closed form (docs/theory.md, "Controllers"). A first-order term r/(s + a)
 * is split evenly between B and C (sqrt|r| each), and the second-order sections use states
 * scaled by the natural frequency, so that no realisation starts badly balanced.
 */
#include "control/control_internal.h"

#include "touchdown/dofs.h" /* TD_PI */
#include "util/error_internal.h"

#include <math.h>
#include <stddef.h>

/* State i of k is the first-order term r/(s + a): A = -a, B = sqrt|r|, C = sign(r) sqrt|r|. */
static void first_order_state(td_controller *k, int i, double a, double r)
{
    double s = sqrt(fabs(r));
    k->A[i + i * k->n] = -a;
    k->B[i] = s;
    k->C[i] = r < 0.0 ? -s : s;
}

/* States i, i+1 of k: x1' = wn x2, x2' = -wn x1 - 2 zeta wn x2 + wn u, so that x1 = wn^2/d u and
 * x2 = wn s/d u with d = s^2 + 2 zeta wn s + wn^2. C is left to the caller. */
static void second_order_states(td_controller *k, int i, double wn, double zeta)
{
    int n = k->n;
    k->A[i + (i + 1) * n] = wn;
    k->A[(i + 1) + i * n] = -wn;
    k->A[(i + 1) + (i + 1) * n] = -2.0 * zeta * wn;
    k->B[i + 1] = wn;
}

td_controller *td_controller_create_gain(double gain, td_error *err)
{
    td_controller *k;
    if (!isfinite(gain)) {
        td_ctl_invalid(err, "gain", NULL, "must be finite (got %g)", gain);
        return NULL;
    }
    k = td_ctl_alloc(0, 1, 1, 0.0, err);
    if (k)
        k->D[0] = gain;
    return k;
}

static td_status check_pid(const td_pid_block *b, td_error *err)
{
    if (!b)
        return td_error_set(err, TD_ERR_INVALID, "pid: NULL block");
    if (!isfinite(b->kp))
        return td_ctl_invalid(err, "pid", "kp", "must be finite (got %g)", b->kp);
    if (!isfinite(b->kd))
        return td_ctl_invalid(err, "pid", "kd", "must be finite (got %g)", b->kd);
    if (!(isfinite(b->kint) && b->kint >= 0.0))
        return td_ctl_invalid(err, "pid", "kint", "must be finite and >= 0 (got %g)", b->kint);
    return td_ctl_check_frequency(b->derivative_filter, 1, "pid", "derivative_filter", err);
}

/* kp + kint/s + kd s/(1 + s/wd) = (kp + kd wd) + kint/s - kd wd^2/(s + wd): an integrator state
 * when kint > 0, a filter state when kd != 0 and wd > 0; without a filter kd s is D1. */
td_controller *td_controller_create_pid(const td_pid_block *b, td_error *err)
{
    td_controller *k;
    double wd;
    int integ, filt, i = 0;
    if (check_pid(b, err) != TD_OK)
        return NULL;
    wd = 2.0 * TD_PI * b->derivative_filter;
    integ = b->kint > 0.0;
    filt = b->kd != 0.0 && wd > 0.0;
    k = td_ctl_alloc(integ + filt, 1, 1, 0.0, err);
    if (!k)
        return NULL;
    if (integ)
        first_order_state(k, i++, 0.0, b->kint);
    if (filt)
        first_order_state(k, i, wd, -b->kd * wd * wd);
    k->D[0] = b->kp + (filt ? b->kd * wd : 0.0);
    k->D1[0] = wd > 0.0 ? 0.0 : b->kd;
    return td_ctl_finite(k, "pid", err);
}

/* g (1 + s/wz)/(1 + s/wp) = g wp/wz + g (wp/wz)(wz - wp)/(s + wp). */
td_controller *td_controller_create_leadlag(const td_leadlag_block *b, td_error *err)
{
    td_controller *k;
    double wz, wp, r;
    if (!b) {
        td_error_set(err, TD_ERR_INVALID, "leadlag: NULL block");
        return NULL;
    }
    if (!isfinite(b->gain)) {
        td_ctl_invalid(err, "leadlag", "gain", "must be finite (got %g)", b->gain);
        return NULL;
    }
    if (td_ctl_check_frequency(b->zero, 0, "leadlag", "zero", err) != TD_OK ||
        td_ctl_check_frequency(b->pole, 0, "leadlag", "pole", err) != TD_OK)
        return NULL;
    wz = 2.0 * TD_PI * b->zero;
    wp = 2.0 * TD_PI * b->pole;
    r = b->gain * (wp / wz) * (wz - wp);
    k = td_ctl_alloc(r != 0.0, 1, 1, 0.0, err);
    if (!k)
        return NULL;
    if (r != 0.0)
        first_order_state(k, 0, wp, r);
    k->D[0] = b->gain * wp / wz;
    return td_ctl_finite(k, "leadlag", err);
}

td_controller *td_controller_create_lowpass(const td_lowpass_block *b, td_error *err)
{
    td_controller *k;
    double wc;
    if (!b) {
        td_error_set(err, TD_ERR_INVALID, "lowpass: NULL block");
        return NULL;
    }
    if (b->order != 1 && b->order != 2) {
        td_ctl_invalid(err, "lowpass", "order", "must be 1 or 2 (got %d)", b->order);
        return NULL;
    }
    if (td_ctl_check_frequency(b->frequency, 0, "lowpass", "frequency", err) != TD_OK ||
        (b->order == 2 && td_ctl_check_positive(b->damping, "lowpass", "damping", err) != TD_OK))
        return NULL;
    wc = 2.0 * TD_PI * b->frequency;
    k = td_ctl_alloc(b->order, 1, 1, 0.0, err);
    if (!k)
        return NULL;
    if (b->order == 1) {
        first_order_state(k, 0, wc, wc);
    } else {
        second_order_states(k, 0, wc, b->damping);
        k->C[0] = 1.0; /* x1 = wc^2 / (s^2 + 2 zeta wc s + wc^2) u */
    }
    return td_ctl_finite(k, "lowpass", err);
}

/* (s^2 + 2 zz wn s + wn^2)/(s^2 + 2 zp wn s + wn^2) = 1 + 2 (zz - zp) wn s/(s^2 + 2 zp wn s + wn^2),
 * and wn s/(...) u is the second state of second_order_states. */
td_controller *td_controller_create_notch(const td_notch_block *b, td_error *err)
{
    td_controller *k;
    double wn, zp, zz;
    if (!b) {
        td_error_set(err, TD_ERR_INVALID, "notch: NULL block");
        return NULL;
    }
    if (td_ctl_check_frequency(b->frequency, 0, "notch", "frequency", err) != TD_OK ||
        td_ctl_check_frequency(b->width, 0, "notch", "width", err) != TD_OK)
        return NULL;
    if (!(isfinite(b->depth) && b->depth >= 0.0 && b->depth < 1.0)) {
        td_ctl_invalid(err, "notch", "depth", "must be >= 0 and < 1 (got %g)", b->depth);
        return NULL;
    }
    wn = 2.0 * TD_PI * b->frequency;
    zp = b->width / (2.0 * b->frequency);
    zz = b->depth * zp;
    k = td_ctl_alloc(2, 1, 1, 0.0, err);
    if (!k)
        return NULL;
    second_order_states(k, 0, wn, zp);
    k->C[1] = 2.0 * (zz - zp);
    k->D[0] = 1.0;
    return td_ctl_finite(k, "notch", err);
}

/* g (s cos phi + w sin phi)/(s^2 + 2 zeta w s + w^2): the states of second_order_states are
 * x1 = w^2/d u and x2 = w s/d u (d that denominator), so the output is (g sin phi/w) x1 + (g cos phi/w) x2.
 * zeta = 0 (undamped) writes the same A, entry for entry, as the block had before it took a damping. */
td_controller *td_controller_create_resonant(const td_resonant_block *b, td_error *err)
{
    td_controller *k;
    double w, phi;
    if (!b) {
        td_error_set(err, TD_ERR_INVALID, "resonant: NULL block");
        return NULL;
    }
    if (!isfinite(b->gain)) {
        td_ctl_invalid(err, "resonant", "gain", "must be finite (got %g)", b->gain);
        return NULL;
    }
    if (!isfinite(b->phase)) {
        td_ctl_invalid(err, "resonant", "phase", "must be finite degrees (got %g)", b->phase);
        return NULL;
    }
    if (td_ctl_check_frequency(b->frequency, 0, "resonant", "frequency", err) != TD_OK)
        return NULL;
    if (!(isfinite(b->damping) && b->damping >= 0.0 && b->damping < 1.0)) {
        td_ctl_invalid(err, "resonant", "damping", "must be >= 0 and < 1 (got %g)", b->damping);
        return NULL;
    }
    w = 2.0 * TD_PI * b->frequency;
    phi = b->phase * (TD_PI / 180.0);
    k = td_ctl_alloc(2, 1, 1, 0.0, err);
    if (!k)
        return NULL;
    second_order_states(k, 0, w, b->damping);
    k->C[0] = b->gain * sin(phi) / w;
    k->C[1] = b->gain * cos(phi) / w;
    return td_ctl_finite(k, "resonant", err);
}
