/*
 * The machine's energy account (touchdown/records.h td_energy), kept at the same points as the
 * retainers' totals (totals.c): what the rotor and the races hold, and the powers that fill and
 * drain them, integrated by the trapezoid rule over the integrator's steps.
 *
 *     d/dt (1/2 v^T M v + 1/2 q^T K q + E_c) = P_ext + P_drive + P_housing - v^T C v - P_contact - P_drag
 *
 * P_housing = f_housing . v, the power of the housing motion's inertial loads on the relative
 * velocities (touchdown/housing.h), kept apart from P_ext so that the account says what the base put in.
 * The gyroscopic forces do no work (v^T G v = 0). E_c is the contact springs' energy
 * Kc delta^(p+1)/(p+1). The friction force F_t on the race along t has the rotor's surface, moving
 * at R_s Omega with the spin the model holds fixed, push against it: the drive that holds the
 * speed does the work F_t R_s Omega, and the contact dissipates what its damper and the sliding
 * take, P_contact = (N - N_el) ddelta/dt + F_t (R_s Omega + r dtheta/dt - R_b Omega_b), the second
 * term the friction heat F_t v_s of eq. (16). An impact takes the kinetic energy the impact map
 * removes.
 */
#include "sim/sim_internal.h"

#include <math.h>
#include <string.h>

/* x^T A y over the structural operator's row-compressed values `vals` (s->st_*). */
static double quadratic(const td_sim *s, const double *vals, const double *x, const double *y)
{
    double sum = 0.0;
    int i, p;
    for (i = 0; i < s->dae.n; i++) {
        double row = 0.0;
        for (p = s->ops.st_rowptr[i]; p < s->ops.st_rowptr[i + 1]; p++)
            row += vals[p] * y[s->ops.st_col[p]];
        sum += x[i] * row;
    }
    return sum;
}

/* v^T M v, q^T K q and v^T D v into out[0..2] in one pass over the shared pattern, M, K and D stored
 * on it (row-compressed, n rows). Each sum is accumulated in the same order as quadratic() takes it,
 * row by row and along each row, so the three are bit for bit what three separate passes give. */
void td_sim_quadratic_forms(int n, const int *rowptr, const int *col, const double *M, const double *K, const double *D,
                            const double *q, const double *v, double out[3])
{
    double sm = 0.0, sk = 0.0, sd = 0.0;
    int i, p;
    for (i = 0; i < n; i++) {
        double rm = 0.0, rk = 0.0, rd = 0.0;
        for (p = rowptr[i]; p < rowptr[i + 1]; p++) {
            double vc = v[col[p]];
            rm += M[p] * vc;
            rk += K[p] * q[col[p]];
            rd += D[p] * vc;
        }
        sm += v[i] * rm;
        sk += q[i] * rk;
        sd += v[i] * rd;
    }
    out[0] = sm;
    out[1] = sk;
    out[2] = sd;
}

double td_sim_mass_form(const td_sim *s, const double *x, const double *y)
{
    return quadratic(s, s->ops.st_M, x, y);
}

double td_sim_kinetic_energy(const td_sim *s, const double *y)
{
    return 0.5 * quadratic(s, s->ops.st_M, y + s->dae.ov, y + s->dae.ov);
}

/* Elastic energy of retainer k's contact spring and the power its contact dissipates, at y. */
static double contact_spring(const td_sim *s, int k, const double *y, double *loss)
{
    const td_sim_retainer *r = &s->contacts.ret[k];
    double x, yy, vx, vy, rad, delta, rate, n, n_el = 0.0, e = 0.0, ft, vt;
    *loss = 0.0;
    if (r->mode == TD_RMODE_FREE && !r->compliant)
        return 0.0;
    td_sim_node_state(s, k, y, &x, &yy, &vx, &vy);
    rad = hypot(x, yy);
    delta = rad - r->r.clearance;
    rate = td_contact_radial_velocity(x, yy, vx, vy);
    n = td_sim_normal_force(s, k, y);
    if (r->compliant && delta > 0.0) {
        double p = r->law.exponent;
        n_el = r->law.stiffness * pow(delta, p);
        e = n_el * delta / (p + 1.0);
    }
    if (r->mode == TD_RMODE_FREE)
        return e; /* a spring that holds energy only while the node is inside: no force yet */
    ft = td_sim_friction_force(s, k, y);
    vt = td_contact_tangential_velocity(x, yy, vx, vy);
    *loss = (n - n_el) * rate +
            ft * (r->r.shaft_radius * td_sim_rotor_speed(s, y) + vt - r->r.bore_radius * td_sim_race_speed(s, k, y));
    return e;
}

/* The powers at y (external, drive, damping, contact, drag) into pw, the housing motion's into
 * *housing and the kinetic energy into *kinetic; returns the energy held. */
static double powers(td_sim *s, double t, const double *y, double pw[5], double *housing, double *kinetic)
{
    const double *q = y + s->dae.oq, *v = y + s->dae.ov;
    double forms[3], held;
    int i, k;
    td_sim_quadratic_forms(s->dae.n, s->ops.st_rowptr, s->ops.st_col, s->ops.st_M, s->ops.st_K, s->ops.st_D, q, v,
                           forms);
    *kinetic = 0.5 * forms[0];
    held = *kinetic + 0.5 * forms[1];
    memset(s->monitor.energy_f, 0, sizeof(double) * (size_t)s->dae.n);
    td_sim_external_forces(s, t, y, 1.0, s->monitor.energy_f);
    memset(pw, 0, 5 * sizeof *pw);
    for (i = 0; i < s->dae.n; i++)
        pw[0] += s->monitor.energy_f[i] * v[i];
    *housing = 0.0;
    if (s->sys->base_load[0]) { /* the housing motion's share of those forces, booked apart */
        memset(s->monitor.energy_f, 0, sizeof(double) * (size_t)s->dae.n);
        td_sim_housing_forces(s, t, y, 1.0, s->monitor.energy_f);
        for (i = 0; i < s->dae.n; i++)
            *housing += s->monitor.energy_f[i] * v[i];
        pw[0] -= *housing;
    }
    pw[0] += td_sim_unbalance_spin_coupling(s, t, y, N_VGetArrayPointer(s->dae.yp), NULL);
    pw[2] = forms[2];
    for (k = 0; k < s->dae.nr; k++) {
        double loss;
        held += contact_spring(s, k, y, &loss);
        pw[3] += loss;
        if (s->contacts.ret[k].mode != TD_RMODE_FREE &&
            !s->machine.spin_free) /* the drive holds the speed against it */
            pw[1] += td_sim_friction_force(s, k, y) * s->contacts.ret[k].r.shaft_radius * td_sim_rotor_speed(s, y);
        if (s->contacts.ret[k].rs >= 0)
            pw[4] += td_sim_race_drag(s, k, y, NULL) * v[s->contacts.ret[k].rs];
    }
    if (s->machine.spin_free)
        pw[4] += td_sim_spin_drag(s, y, NULL) * v[s->machine.spin];
    return held;
}

void td_sim_energy_point(td_sim *s, double t, int restart, double dt)
{
    const double *y = N_VGetArrayPointer(s->dae.y);
    double pw[5], ph, ke, held = powers(s, t, y, pw, &ph, &ke), *prev = s->monitor.energy_prev;
    td_energy *e = &s->monitor.energy;
    if (dt > 0.0) {
        e->housing_work += 0.5 * dt * (s->monitor.housing_prev + ph);
        e->external_work += 0.5 * dt * (prev[0] + pw[0]);
        e->drive_work += 0.5 * dt * (prev[1] + pw[1]);
        e->damping_loss += 0.5 * dt * (prev[2] + pw[2]);
        e->contact_loss += 0.5 * dt * (prev[3] + pw[3]);
        e->drag_loss += 0.5 * dt * (prev[4] + pw[4]);
    }
    if (restart && !s->monitor.energy_started) {
        e->initial = held;
        s->monitor.energy_started = 1;
    }
    memcpy(prev, pw, sizeof pw);
    s->monitor.housing_prev = ph;
    e->kinetic = ke;
    e->elastic = held - e->kinetic;
}

void td_sim_energy_impact(td_sim *s, double before, double after)
{
    s->monitor.energy.impact_loss += before - after;
}

/* The account at s->dae.t when the last point lies beyond it (an output, the end time, or a change
 * inside the integrator's last step): the trapezoids from s->dae.t to that point taken back, and what
 * the machine holds read at s->dae.t, as the retainers' totals do (totals.c). Returns the powers at
 * s->dae.t (the housing motion's in *ph). */
static void energy_back_to_now(td_sim *s, td_energy *e, double pw[5], double *ph)
{
    const double *y = N_VGetArrayPointer(s->dae.y), *prev = s->monitor.energy_prev;
    double ke, dt = s->monitor.totals_t - s->dae.t, held = powers(s, s->dae.t, y, pw, ph, &ke);
    if (dt > 0.0) {
        e->housing_work -= 0.5 * dt * (s->monitor.housing_prev + *ph);
        e->external_work -= 0.5 * dt * (prev[0] + pw[0]);
        e->drive_work -= 0.5 * dt * (prev[1] + pw[1]);
        e->damping_loss -= 0.5 * dt * (prev[2] + pw[2]);
        e->contact_loss -= 0.5 * dt * (prev[3] + pw[3]);
        e->drag_loss -= 0.5 * dt * (prev[4] + pw[4]);
    }
    e->kinetic = ke;
    e->elastic = held - e->kinetic;
}

void td_sim_energy_rewind(td_sim *s)
{
    double pw[5], ph;
    if (!s->opt.energy || !(s->monitor.totals_t > s->dae.t))
        return;
    energy_back_to_now(s, &s->monitor.energy, pw, &ph);
    memcpy(s->monitor.energy_prev, pw, sizeof pw);
    s->monitor.housing_prev = ph;
}

void td_sim_energy_get(const td_sim *s, td_energy *out)
{
    double pw[5], ph;
    *out = s->monitor.energy;
    if (s->monitor.totals_t > s->dae.t) /* powers() uses the sim's scratch force vector only */
        energy_back_to_now((td_sim *)s, out, pw, &ph);
    out->residual = out->kinetic + out->elastic - out->initial - out->external_work - out->drive_work +
                    out->damping_loss + out->contact_loss + out->drag_loss + out->impact_loss - out->housing_work;
}
