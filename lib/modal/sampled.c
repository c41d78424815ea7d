/*
 * The closed loop of sampled controllers, exact at the samples. Between two samples t_k, t_k + T
 * (T = 1 / sample_rate) the plant (the rotor, the AMB lags and any continuous controller:
 * td_state_space_build_plant) is linear with the sampled laws' currents u held (zero-order hold):
 *
 *   z' = A z + Bu u   =>   z[k+1] = Phi z[k] + Gamma u[k],   Phi = exp(A T),  Gamma = int_0^T exp(A s) ds Bu
 *
 * (SLICOT MB05ND through td_slicot_expm). Each sampled law reads e[k] = -xs(t_k) and sets
 * x[k+1] = Ad x[k] + Bd e[k], u[k] = Cd x[k] + Dd e[k] (touchdown/controller.h; a delay's states are
 * among x), so over one period
 *
 *   [z; x][k+1] = [Phi - Gamma Dd Cy   Gamma Cd;  -Bd Cy   Ad] [z; x][k],    e = -Cy z.
 *
 * Its eigenvalues mu are the sampled loop's; s = ln(mu) / T gives the same growth rates and
 * frequencies (up to the Nyquist frequency) as a continuous analysis, stable iff |mu| < 1.
 */
#include "control/numerics.h"
#include "modal/modal_internal.h"
#include "util/error_internal.h"

#include <stdlib.h>
#include <string.h>

int td_system_has_sampled_law(const td_system *sys)
{
    int l;
    for (l = 0; sys && l < sys->n_laws; l++)
        if (sys->laws[l].state < 0)
            return 1;
    return 0;
}

/* The common rate of the sampled laws into *rate, and their total states, outputs into *nx, *nu. */
static td_status sampled_sizes(const td_system *sys, double *rate, int *nx, int *nu, td_error *err)
{
    int l;
    *rate = 0.0;
    *nx = *nu = 0;
    for (l = 0; l < sys->n_laws; l++) {
        const td_lti_law *L = &sys->laws[l];
        if (L->state >= 0 || L->standby) /* a recovery law standing by drives nothing */
            continue;
        if (*rate != 0.0 && L->sample_rate != *rate)
            return td_error_set(err, TD_ERR_INVALID,
                                "modal: controller %d is sampled at %g Hz, another at %g Hz: the closed-loop analysis "
                                "needs one sample rate",
                                l, L->sample_rate, *rate);
        *rate = L->sample_rate;
        *nx += L->n;
        *nu += L->nout;
    }
    return TD_OK;
}

td_status td_sampled_current_column(const td_state_space *ss, const td_amb_axis *a, double *col, td_error *err)
{
    double dfdx, dfdfc, target = td_amb_axis_current_command(a, 1.0), *f;
    td_status st;
    int i;
    (void)td_amb_axis_force(a, !a->off, 0.0, 0.0, &dfdx, &dfdfc);
    if (a->state >= 0) { /* the command sets the lag's target: dFc/dt = (ki i - Fc) / tau */
        for (i = 0; i < ss->n; i++)
            col[i] = 0.0;
        col[2 * ss->ndof + a->state] = td_amb_axis_lag_rate(a, target, 0.0);
        return TD_OK;
    }
    if (!(f = calloc((size_t)ss->ndof, sizeof *f)))
        return td_error_set(err, TD_ERR_NOMEM, "modal: out of memory for the plant's inputs");
    f[a->actuator_dof] = dfdfc * target;
    st = td_state_space_load(ss, f, col, err);
    free(f);
    return st;
}

/* Bu (n x nu, column-major): column j is the plant's rate per ampere of the held current of
 * sampled output j (td_sampled_current_column). */
static td_status input_matrix(const td_system *sys, const td_state_space *ss, double *Bu, td_error *err)
{
    size_t n = (size_t)ss->n;
    int l, o, j = 0;
    td_status st = TD_OK;
    for (l = 0; st == TD_OK && l < sys->n_laws; l++) {
        const td_lti_law *L = &sys->laws[l];
        for (o = 0; L->state < 0 && !L->standby && st == TD_OK && o < L->nout; o++, j++)
            st = td_sampled_current_column(ss, &sys->amb_axes[L->out_axis[o]], Bu + (size_t)j * n, err);
    }
    return st;
}

td_status td_sampled_hold(int n, double rate, const double *A, const double *Bu, int nu, double *Phi, double *Gamma,
                          td_error *err)
{
    double *EI = malloc((size_t)n * (size_t)n * sizeof *EI);
    size_t i, j, k, un = (size_t)n;
    td_status st = EI ? td_slicot_expm(n, 1.0 / rate, A, Phi, EI, err)
                      : td_error_set(err, TD_ERR_NOMEM, "modal: out of memory for the sampled plant (%d states)", n);
    for (i = 0; st == TD_OK && i < un; i++) /* Gamma = EXINT Bu */
        for (j = 0; j < (size_t)nu; j++) {
            Gamma[i + j * un] = 0.0;
            for (k = 0; k < un; k++)
                Gamma[i + j * un] += EI[i + k * un] * Bu[k + j * un];
        }
    free(EI);
    return st;
}

/* P += the controllers' part of the loop: Phi - Gamma Dd Cy, Gamma Cd, -Bd Cy and Ad (header). */
static void close_loop(const td_system *sys, size_t n, const double *G, gsl_matrix *P)
{
    int l, o, m, r, c, j = 0;
    size_t xo = n;
    for (l = 0; l < sys->n_laws; l++) {
        const td_lti_law *L = &sys->laws[l];
        size_t i, ln = (size_t)L->n, no = (size_t)L->nout;
        if (L->state >= 0 || L->standby)
            continue;
        for (o = 0; o < L->nout; o++, j++)
            for (i = 0; i < n; i++) {
                double g = G[i + (size_t)j * n];
                for (m = 0; m < L->nin; m++) /* -Gamma Dd Cy: u = Cd x + Dd e, e = -xs */
                    *gsl_matrix_ptr(P, i, (size_t)sys->amb_axes[L->in_axis[m]].sensor_dof) -=
                        g * L->D[(size_t)o + (size_t)m * no];
                for (c = 0; c < L->n; c++)
                    *gsl_matrix_ptr(P, i, xo + (size_t)c) += g * L->C[(size_t)o + (size_t)c * no];
            }
        for (r = 0; r < L->n; r++) {
            for (m = 0; m < L->nin; m++) /* -Bd Cy */
                *gsl_matrix_ptr(P, xo + (size_t)r, (size_t)sys->amb_axes[L->in_axis[m]].sensor_dof) -=
                    L->B[(size_t)r + (size_t)m * ln];
            for (c = 0; c < L->n; c++)
                gsl_matrix_set(P, xo + (size_t)r, xo + (size_t)c, L->A[(size_t)r + (size_t)c * ln]);
        }
        xo += ln;
    }
}

td_status td_sampled_closed_loop(const td_system *sys, double omega, gsl_matrix **P, double *rate, td_error *err)
{
    td_state_space ss;
    double *A = NULL, *EX = NULL, *Bu = NULL, *G = NULL;
    size_t n, i, j;
    int nx, nu;
    td_status st = td_system_refuse_plugins(sys, err);
    *P = NULL;
    if (st == TD_OK)
        st = sampled_sizes(sys, rate, &nx, &nu, err);
    if (st == TD_OK)
        st = td_state_space_build_plant(sys, omega, &ss, err);
    if (st != TD_OK)
        return st;
    n = (size_t)ss.n;
    A = malloc(n * n * sizeof *A);
    EX = malloc(n * n * sizeof *EX);
    Bu = calloc(n * (size_t)nu + 1, sizeof *Bu);
    G = calloc(n * (size_t)nu + 1, sizeof *G);
    *P = gsl_matrix_calloc(n + (size_t)nx, n + (size_t)nx);
    if (!A || !EX || !Bu || !G || !*P)
        st = td_error_set(err, TD_ERR_NOMEM, "modal: out of memory for the sampled loop (%d states)", ss.n + nx);
    for (i = 0; st == TD_OK && i < n; i++)
        for (j = 0; j < n; j++)
            A[i + j * n] = gsl_matrix_get(ss.A, i, j);
    if (st == TD_OK)
        st = input_matrix(sys, &ss, Bu, err);
    if (st == TD_OK)
        st = td_sampled_hold(ss.n, *rate, A, Bu, nu, EX, G, err);
    for (i = 0; st == TD_OK && i < n; i++) /* P = Phi, then the loop */
        for (j = 0; j < n; j++)
            gsl_matrix_set(*P, i, j, EX[i + j * n]);
    if (st == TD_OK)
        close_loop(sys, n, G, *P);
    free(A), free(EX), free(Bu), free(G);
    td_state_space_free(&ss);
    if (st != TD_OK) {
        gsl_matrix_free(*P);
        *P = NULL;
    }
    return st;
}
