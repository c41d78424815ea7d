/* Rotor-retainer contact laws: geometry, constraint, penalty force, friction, impact map. */
#include "contact/contact.h"

#include <math.h>
#include <stddef.h>

double td_contact_frame(double x, double y, double n[2], double t[2])
{
    double r = hypot(x, y);
    if (r > 0.0) {
        n[0] = x / r;
        n[1] = y / r;
    } else {
        n[0] = 1.0;
        n[1] = 0.0;
    }
    t[0] = -n[1];
    t[1] = n[0];
    return r;
}

double td_contact_radial_velocity(double x, double y, double vx, double vy)
{
    double r = hypot(x, y);
    return r > 0.0 ? (x * vx + y * vy) / r : 0.0;
}

double td_contact_tangential_velocity(double x, double y, double vx, double vy)
{
    double r = hypot(x, y);
    return r > 0.0 ? (x * vy - y * vx) / r : 0.0;
}

/* eq. (5) divided by -2c. Written as (r - c)(r + c)/(2c) so that a point projected onto the
 * circle gives a value at the rounding level of r rather than of r^2. */
double td_contact_constraint(double x, double y, double c)
{
    double r = hypot(x, y);
    return (r - c) * (r + c) / (2.0 * c);
}

/* eq. (14) divided by -2c. */
void td_contact_constraint_jacobian(double x, double y, double c, double J[2])
{
    J[0] = x / c;
    J[1] = y / c;
}

/* eq. (14), D = 2 (x'^2 + y'^2), divided by 2c. */
double td_contact_constraint_dterm(double vx, double vy, double c)
{
    return (vx * vx + vy * vy) / c;
}

double td_contact_penalty_force(const td_penalty_law *law, double delta, double rate, double *dF_ddelta,
                                double *dF_drate)
{
    double p = law->exponent, k = law->stiffness, d = law->coefficient;
    double s, ds, f, fd, fr;

    if (dF_ddelta)
        *dF_ddelta = 0.0;
    if (dF_drate)
        *dF_drate = 0.0;
    if (!(delta > 0.0))
        return 0.0;
    /* elastic part Kc delta^p and its slope */
    if (p == 1.0) {
        s = k * delta;
        ds = k;
    } else {
        s = k * pow(delta, p);
        ds = k * p * pow(delta, p - 1.0);
    }
    switch (law->damping) {
    case TD_DAMPING_HUNT_CROSSLEY:
        f = s * (1.0 + d * rate);
        fd = ds * (1.0 + d * rate);
        fr = s * d;
        break;
    case TD_DAMPING_KELVIN_VOIGT:
        f = s + d * rate;
        fd = ds;
        fr = d;
        break;
    case TD_DAMPING_NONE:
    default:
        f = s;
        fd = ds;
        fr = 0.0;
        break;
    }
    if (f <= 0.0) /* a separating contact with strong damping would pull: it never does */
        return 0.0;
    if (dF_ddelta)
        *dF_ddelta = fd;
    if (dF_drate)
        *dF_drate = fr;
    return f;
}

/* eq. (16) with dtheta/dt from theta = atan2(y, x) (eq. 12). */
double td_contact_sliding_velocity(const td_retainer *ret, double omega, double race_speed, double x, double y,
                                   double vx, double vy)
{
    double r2 = x * x + y * y;
    double whirl_rate = r2 > 0.0 ? (x * vy - y * vx) / r2 : 0.0;
    return ret->shaft_radius * omega + (ret->bore_radius - ret->shaft_radius) * whirl_rate -
           ret->bore_radius * race_speed;
}

void td_contact_sliding_velocity_gradient(const td_retainer *ret, double x, double y, double vx, double vy, double g[4])
{
    double r2 = x * x + y * y, a = ret->bore_radius - ret->shaft_radius, w;
    if (!(r2 > 0.0)) {
        g[0] = g[1] = g[2] = g[3] = 0.0;
        return;
    }
    w = (x * vy - y * vx) / r2; /* whirl rate */
    g[0] = a * (vy - 2.0 * x * w) / r2;
    g[1] = a * (-vx - 2.0 * y * w) / r2;
    g[2] = a * (-y / r2);
    g[3] = a * (x / r2);
}

double td_contact_slip_factor(double vs, double vreg, double *dphi)
{
    if (vs >= vreg || vs <= -vreg) {
        if (dphi)
            *dphi = 0.0;
        return vs > 0.0 ? 1.0 : -1.0;
    }
    if (dphi)
        *dphi = 1.0 / vreg;
    return vs / vreg;
}

/* eq. (17), regularised: magnitude phi mu N, opposing the sliding velocity. */
double td_contact_friction_force(double mu, double phi, double normal_force)
{
    return -phi * mu * normal_force;
}

int td_contact_dense_solve(int m, double *A, double *b)
{
    int i, j, k, piv;
    for (k = 0; k < m; k++) {
        double best = fabs(A[k + k * m]);
        piv = k;
        for (i = k + 1; i < m; i++)
            if (fabs(A[i + k * m]) > best) {
                best = fabs(A[i + k * m]);
                piv = i;
            }
        if (!(best > 0.0) || !isfinite(best))
            return -1;
        if (piv != k) {
            double tmp;
            for (j = 0; j < m; j++) {
                tmp = A[k + j * m];
                A[k + j * m] = A[piv + j * m];
                A[piv + j * m] = tmp;
            }
            tmp = b[k];
            b[k] = b[piv];
            b[piv] = tmp;
        }
        for (i = k + 1; i < m; i++) {
            double f = A[i + k * m] / A[k + k * m];
            if (f == 0.0)
                continue;
            for (j = k + 1; j < m; j++)
                A[i + j * m] -= f * A[k + j * m];
            b[i] -= f * b[k];
        }
    }
    for (k = m - 1; k >= 0; k--) {
        double s = b[k];
        for (j = k + 1; j < m; j++)
            s -= A[k + j * m] * b[j];
        b[k] = s / A[k + k * m];
    }
    return 0;
}

double td_contact_row_dot(const td_contact_row *row, const double *x)
{
    double acc = row->j[0] * x[row->dof[0]] + row->j[1] * x[row->dof[1]];
    int i;
    for (i = 2; i < row->count; i++)
        acc += row->j[i] * x[row->dof[i]];
    return acc;
}

void td_contact_row_scatter(const td_contact_row *row, double *x)
{
    int i;
    for (i = 0; i < row->count; i++)
        x[row->dof[i]] += row->j[i];
}

int td_contact_impact_map(int n, int m, const td_contact_row *rows, const double *minv_jt, const double *restitution,
                          double *v, double *impulse, double *work)
{
    double *W = work, *P = work + (size_t)m * m;
    int i, k;
    for (i = 0; i < m; i++) {
        for (k = 0; k < m; k++)
            W[i + k * m] = td_contact_row_dot(&rows[i], minv_jt + (size_t)k * n);
        P[i] = (1.0 + restitution[i]) * td_contact_row_dot(&rows[i], v);
    }
    if (td_contact_dense_solve(m, W, P) != 0)
        return -1;
    for (k = 0; k < m; k++) {
        const double *col = minv_jt + (size_t)k * n;
        for (i = 0; i < n; i++)
            v[i] -= col[i] * P[k];
        impulse[k] = P[k];
    }
    return 0;
}
