/*
 * Linear controllers (touchdown/controller.h) in the DAE. A continuous law's states x join block w
 * after every shorthand state (model/assemble.c numbers them), with the rows
 *
 *   x' - A x - B e = 0,    e = -xs (the sensor displacements of its input axes),
 *
 * and output o commands the amplifier of its axis with the current i = C x + D e + D1 e', e' = -vs
 * (the exact sensor velocities, the signal the shorthand's kd reads). The amplifier turns it into
 * the target force ki i (model/amb.c), lagged by tau or taken directly, then clipped, as the
 * shorthand's command is. A sampled law has no DAE state: its axes hold the current its last
 * sample set (machine.held_current). The functions here are linear in y, so their Jacobian
 * entries are the matrices themselves.
 */
#include "sim/sim_internal.h"

#include <stddef.h>

/* Sensor DOF of input m of law L. */
static int input_dof(const td_sim *s, const td_lti_law *L, int m)
{
    return s->sys->amb_axes[L->in_axis[m]].sensor_dof;
}

double td_sim_lti_current(const td_sim *s, const td_amb_axis *a, const double *y)
{
    const td_lti_law *L = &s->sys->laws[a->law];
    int o = a->law_output, nout = L->nout, j, m;
    double i = 0.0;
    if (L->state < 0)
        return s->machine.held_current[2 * a->amb + a->axis];
    for (j = 0; j < L->n; j++)
        i += L->C[o + (size_t)j * nout] * y[s->dae.ow + L->state + j];
    for (m = 0; m < L->nin; m++) {
        int dof = input_dof(s, L, m);
        i -= L->D[o + (size_t)m * nout] * y[s->dae.oq + dof];
        if (L->D1)
            i -= L->D1[o + (size_t)m * nout] * y[s->dae.ov + dof];
    }
    return i;
}

/* Rate of state r of continuous law L at y: (A x + B e)_r. */
static double state_rate(const td_sim *s, const td_lti_law *L, int r, const double *y)
{
    const double *x = y + s->dae.ow + L->state;
    double rate = 0.0;
    int j, m;
    for (j = 0; j < L->n; j++)
        rate += L->A[r + (size_t)j * L->n] * x[j];
    for (m = 0; m < L->nin; m++)
        rate -= L->B[r + (size_t)m * L->n] * y[s->dae.oq + input_dof(s, L, m)];
    return rate;
}

void td_sim_lti_rows(const td_sim *s, const double *y, const double *yp, double *res)
{
    int l, r;
    for (l = 0; l < s->sys->n_laws; l++) {
        const td_lti_law *L = &s->sys->laws[l];
        for (r = 0; L->state >= 0 && r < L->n; r++)
            res[s->dae.ow + L->state + r] = yp[s->dae.ow + L->state + r] - state_rate(s, L, r, y);
    }
}

void td_sim_lti_rates(const td_sim *s, const double *y, double *yp)
{
    int l, r;
    for (l = 0; l < s->sys->n_laws; l++) {
        const td_lti_law *L = &s->sys->laws[l];
        for (r = 0; L->state >= 0 && r < L->n; r++)
            yp[s->dae.ow + L->state + r] = state_rate(s, L, r, y);
    }
}

/* jdata[pos(row, col)] += v (the pattern holds every entry written here: sim_pattern.c). */
static void jadd(td_sim *s, int row, int col, double v)
{
    int p = td_sim_pattern_find(s, row, col);
    if (p >= 0)
        s->ops.jdata[p] += v;
}

void td_sim_lti_jacobian_current(td_sim *s, const td_amb_axis *a, int row, double scale)
{
    const td_lti_law *L = &s->sys->laws[a->law];
    int o = a->law_output, nout = L->nout, j, m;
    if (L->state < 0 || scale == 0.0)
        return; /* a held current does not move with y */
    for (j = 0; j < L->n; j++)
        jadd(s, row, s->dae.ow + L->state + j, scale * L->C[o + (size_t)j * nout]);
    for (m = 0; m < L->nin; m++) {
        int dof = input_dof(s, L, m);
        jadd(s, row, s->dae.oq + dof, -scale * L->D[o + (size_t)m * nout]);
        if (L->D1)
            jadd(s, row, s->dae.ov + dof, -scale * L->D1[o + (size_t)m * nout]);
    }
}

void td_sim_lti_jacobian_rows(td_sim *s)
{
    int l, r, j, m;
    for (l = 0; l < s->sys->n_laws; l++) {
        const td_lti_law *L = &s->sys->laws[l];
        for (r = 0; L->state >= 0 && r < L->n; r++) {
            int row = s->dae.ow + L->state + r;
            for (j = 0; j < L->n; j++)
                jadd(s, row, s->dae.ow + L->state + j, -L->A[r + (size_t)j * L->n]);
            for (m = 0; m < L->nin; m++) /* -B de/dxs, de/dxs = -1 */
                jadd(s, row, s->dae.oq + input_dof(s, L, m), L->B[r + (size_t)m * L->n]);
        }
    }
}
