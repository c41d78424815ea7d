/*
 * The loop analysis of touchdown/modal.h (docs/theory.md, "Sensitivity"): the plant from the
 * amplifier commands to the sensors, the controllers as frequency responses, and per controlled
 * axis the input sensitivity S_j = [(I + K P)^-1]_jj, the open loop L_j = 1/S_j - 1, the peak of
 * |S_j| and its ISO 14839-3:2006 zone ("Evaluation of stability margin"), and the compliance at
 * the bearings with every loop closed.
 *
 * The plant is the system's own first-order form (state_space.c) with the controlled axes' laws
 * taken out (kp = kd = kint = 0, no linear controller): rotor, ks and the amplifier lag stay as
 * the AMB law of model/amb.c states them. Its inputs are the current commands (the amplifier
 * law's td_amb_axis_current_command, through the lag td_amb_axis_lag_rate or directly as a force
 * when tau = 0) and unit forces at the actuator nodes; its outputs are the sensor and actuator
 * displacements. The state matrix is balanced and brought to upper Hessenberg form once, so that
 * each frequency costs O(n^2) per input (Laub, "Efficient multivariable frequency response
 * computations", IEEE Trans. Autom. Control 26(2), 1981; SLICOT's TB05AD does the same).
 *
 * With sampled controllers the loop is the sampled-data one, exact at the sample instants: the
 * sampled laws' axes, the rest of the machine (continuous laws, shorthands) closed inside the plant
 * (td_state_space_build_plant); the held currents reach the sensors through the plant's zero-order
 * hold over one sample (sampled.c, td_sampled_hold), P_zoh(z) = C (z I - Phi)^-1 Gamma at
 * z = e^{jwT}, and K(z) is the sampled law's response, up to the Nyquist frequency; the forces of
 * the compliance go through the continuous plant at jw (a sinusoidal force, sampled, is the sinusoid
 * at the samples). Stable iff |mu| < 1 for the loop over one sample (docs/theory.md, "Sensitivity").
 */
#include "modal/modal_internal.h"
#include "touchdown/controller.h"
#include "util/error_internal.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_linalg.h>
#include <gsl/gsl_min.h>

#include <complex.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define LOOP_TWO_PI 6.283185307179586
/* Closed-loop modes damped less than this are searched for narrow peaks of |S| (mode_peaks): the
 * grid's spacing (1.2 % at the defaults) is about the half-power width 2 zeta of a 0.6 % mode. */
#define LOOP_LIGHT_DAMPING 0.05

/* One controller as the loop sees it: k maps sensors cols[] (indices among the sensed axes) to
 * currents rows[] (indices among the controlled axes). */
typedef struct loop_block {
    td_controller *k;
    int *rows, *cols;
    int nout, nin;
} loop_block;

/* The plant's response to m of its inputs, the columns col0.. of G: C (x I - H)^-1 B with H upper
 * Hessenberg (n x n), B (n x m), C (p x n), row-major, at x = jw (continuous) or x = e^{jwT}
 * (discrete: the zero-order hold over one sample period T). */
typedef struct loop_plant {
    int m, col0, discrete;
    double *H, *B, *C;
} loop_plant;

struct td_loop {
    double omega;
    double rate;    /* Hz: the sampled controllers' rate; 0 for a continuous loop */
    int n;          /* plant states */
    int nc, ns, na; /* controlled axes (current inputs), sensed axes (controller inputs), AMB axes */
    int m, p;       /* plant inputs nc + na, outputs ns + na */
    int *axis;      /* nc: AMB axis of each current input */
    int *sensor;    /* ns: AMB axis of each sensor */
    int n_plants;   /* 1: continuous, every input; 2: sampled, the held currents (discrete), then the forces */
    loop_plant plant[2];
    int n_blocks;
    loop_block *blocks;
    int nf;
    double *freq;                 /* Hz */
    double complex *s, *l, *comp; /* nf x nc, nf x nc, nf x na */
    double *peak, *peak_freq;     /* nc */
    int stable;
    double max_real;
    int n_modes;                /* lightly damped closed-loop modes (peak candidates) */
    double *mode_f, *mode_zeta; /* their damped frequencies (Hz) and damping ratios */
};

/* Scratch of one frequency evaluation. */
typedef struct loop_work {
    double complex *T, *Y, *G, *K, *M, *X;
    double *kre, *kim;
    gsl_permutation *perm;
} loop_work;

void td_loop_options_default(td_loop_options *opt)
{
    if (!opt)
        return;
    opt->f_min = 0.5;
    opt->f_max = 5000.0;
    opt->points = 800;
}

char td_loop_zone(double peak)
{
    /* ISO 14839-3:2006, "Evaluation of stability margin": zone limits on the peak sensitivity */
    if (!isfinite(peak))
        return 0;
    return peak < 3.0 ? 'A' : peak < 4.0 ? 'B' : peak < 5.0 ? 'C' : 'D';
}

/* ---- which axes are in the loop ----------------------------------------------------------- */

/* 1 if the shorthand law of axis a (td_amb: kp, kd, kint) closes a loop. */
static int shorthand_controlled(const td_amb_axis *a)
{
    return a->law < 0 && !a->off && (a->kp != 0.0 || a->kd != 0.0 || a->kint != 0.0);
}

/* Flags over the AMB axes: driven[a] when a current command of the loop reaches axis a, sensed[a]
 * when such a controller reads its sensor; *rate the sampled laws' rate (0: none). With a sampled
 * controller the loop is the sampled one: the sampled laws' axes, every continuous law and
 * shorthand closed inside the plant (td_state_space_build_plant). */
static void loop_axes(const td_system *sys, int *driven, int *sensed, double *rate)
{
    int a, i, j, sampled = td_system_has_sampled_law(sys);
    *rate = 0.0;
    for (a = 0; a < sys->n_amb_axes; a++)
        driven[a] = sensed[a] = !sampled && shorthand_controlled(&sys->amb_axes[a]);
    for (i = 0; i < sys->n_laws; i++) {
        const td_lti_law *w = &sys->laws[i];
        if ((w->state < 0) != sampled || w->standby)
            continue; /* a recovery law standing by drives nothing: the nominal is analysed */
        if (sampled && *rate == 0.0)
            *rate = w->sample_rate; /* another rate is refused by the closed loop (sampled.c) */
        for (j = 0; j < w->nout; j++)
            driven[w->out_axis[j]] = 1;
        for (j = 0; j < w->nin; j++)
            sensed[w->in_axis[j]] = 1;
    }
}

/* Index lists of the flagged axes; the index of each axis in its list into pos[] (-1: none). */
static int list_axes(const int *flag, int n, int *list, int *pos)
{
    int a, k = 0;
    for (a = 0; a < n; a++) {
        pos[a] = flag[a] ? k : -1;
        if (flag[a])
            list[k++] = a;
    }
    return k;
}

/* ---- the plant ---------------------------------------------------------------------------- */

/* The machine without the controlled axes' laws: the plant's state space at `omega` (a sampled
 * loop's: without the sampled laws, td_state_space_build_plant). */
static td_status open_loop_state_space(const td_system *sys, const int *driven, double omega, td_state_space *ss,
                                       td_error *err)
{
    td_system open = *sys;
    td_amb_axis *axes = malloc((size_t)(sys->n_amb_axes > 0 ? sys->n_amb_axes : 1) * sizeof *axes);
    td_status st;
    int a;
    if (!axes)
        return td_error_set(err, TD_ERR_NOMEM, "loop analysis: out of memory");
    if (td_system_has_sampled_law(sys)) {
        free(axes);
        return td_state_space_build_plant(sys, omega, ss, err);
    }
    for (a = 0; a < sys->n_amb_axes; a++) {
        axes[a] = sys->amb_axes[a];
        if (driven[a]) {
            axes[a].kp = axes[a].kd = axes[a].kint = 0.0;
            axes[a].law = axes[a].law_output = -1;
        }
    }
    open.amb_axes = axes;
    open.n_laws = 0;
    open.laws = NULL;
    st = td_state_space_build(&open, omega, ss, err);
    free(axes);
    return st;
}

/* Column `col` of the input matrix Bz (n x m, row-major): a current command of 1 A on axis a
 * (current = 1, td_sampled_current_column) or a force of 1 N at its actuator node (current = 0). */
static td_status input_column(const td_state_space *ss, const td_amb_axis *a, int current, double *col, td_error *err)
{
    double *f;
    td_status st;
    if (current)
        return td_sampled_current_column(ss, a, col, err);
    if (!(f = calloc((size_t)ss->ndof, sizeof *f)))
        return td_error_set(err, TD_ERR_NOMEM, "loop analysis: out of memory");
    f[a->actuator_dof] = 1.0;
    st = td_state_space_load(ss, f, col, err);
    free(f);
    return st;
}

/* Bz (n x m) and Cz (p x n), row-major, of the plant in the state space's own coordinates. */
static td_status plant_io(const td_system *sys, const td_loop *l, const td_state_space *ss, double *Bz, double *Cz,
                          td_error *err)
{
    double *col = malloc((size_t)ss->n * sizeof *col);
    td_status st = col ? TD_OK : td_error_set(err, TD_ERR_NOMEM, "loop analysis: out of memory");
    int c, i;
    for (c = 0; st == TD_OK && c < l->m; c++) {
        const td_amb_axis *a = &sys->amb_axes[c < l->nc ? l->axis[c] : c - l->nc];
        st = input_column(ss, a, c < l->nc, col, err);
        for (i = 0; st == TD_OK && i < ss->n; i++)
            Bz[(size_t)i * (size_t)l->m + (size_t)c] = col[i];
    }
    memset(Cz, 0, (size_t)l->p * (size_t)ss->n * sizeof *Cz);
    for (c = 0; c < l->p; c++) {
        const td_amb_axis *a = &sys->amb_axes[c < l->ns ? l->sensor[c] : c - l->ns];
        Cz[(size_t)c * (size_t)ss->n + (size_t)(c < l->ns ? a->sensor_dof : a->actuator_dof)] = 1.0;
    }
    free(col);
    return st;
}

/* Balance A (D^-1 A D), reduce it to Hessenberg form U^T (D^-1 A D) U and carry B and C along:
 * pl->H, pl->B = U^T D^-1 Bz, pl->C = Cz D U, with Bz's pl->m columns from Bz[0] (row stride ldb). */
static td_status hessenberg_plant(const td_loop *l, loop_plant *pl, gsl_matrix *A, const double *Bz, int ldb,
                                  const double *Cz, td_error *err)
{
    size_t n = A->size1, i, j, k;
    gsl_vector *D = gsl_vector_alloc(n), *tau = gsl_vector_alloc(n);
    gsl_matrix *U = gsl_matrix_alloc(n, n);
    td_status st = TD_OK;
    pl->H = malloc(n * n * sizeof *pl->H);
    pl->B = malloc(n * (size_t)pl->m * sizeof *pl->B);
    pl->C = malloc(n * (size_t)l->p * sizeof *pl->C);
    if (!D || !tau || !U || !pl->H || !pl->B || !pl->C)
        st = td_error_set(err, TD_ERR_NOMEM, "loop analysis: out of memory for a %d-state plant", (int)n);
    else if (gsl_linalg_balance_matrix(A, D) != GSL_SUCCESS || gsl_linalg_hessenberg_decomp(A, tau) != GSL_SUCCESS ||
             gsl_linalg_hessenberg_unpack(A, tau, U) != GSL_SUCCESS || gsl_linalg_hessenberg_set_zero(A) != GSL_SUCCESS)
        st = td_error_set(err, TD_ERR_NUMERIC, "loop analysis: the Hessenberg reduction of the plant failed");
    for (i = 0; st == TD_OK && i < n; i++) {
        for (j = 0; j < n; j++)
            pl->H[i * n + j] = gsl_matrix_get(A, i, j);
        for (j = 0; j < (size_t)pl->m; j++) { /* (U^T D^-1 Bz)(i, j) */
            double s = 0.0;
            for (k = 0; k < n; k++)
                s += gsl_matrix_get(U, k, i) * Bz[k * (size_t)ldb + j] / gsl_vector_get(D, k);
            pl->B[i * (size_t)pl->m + j] = s;
        }
        for (j = 0; j < (size_t)l->p; j++) { /* (Cz D U)(j, i) */
            double s = 0.0;
            for (k = 0; k < n; k++)
                s += Cz[j * n + k] * gsl_vector_get(D, k) * gsl_matrix_get(U, k, i);
            pl->C[j * n + i] = s;
        }
    }
    gsl_vector_free(D);
    gsl_vector_free(tau);
    gsl_matrix_free(U);
    return st;
}

/* The sampled loop's plant: the held currents through the zero-order hold over one sample
 * (td_sampled_hold: Phi, Gamma; plant[0], at e^{jwT}), the forces through the continuous plant
 * (plant[1], at jw): a sensor read at the samples sees a sinusoidal force as the sinusoid. */
static td_status sampled_plant(td_loop *l, const td_state_space *ss, const double *Bz, const double *Cz, td_error *err)
{
    size_t n = (size_t)ss->n, nc = (size_t)l->nc, i, j;
    double *A = malloc(n * n * sizeof *A), *Bu = malloc(n * nc * sizeof *Bu), *Ph = malloc(n * n * sizeof *Ph);
    double *Ga = malloc(n * nc * sizeof *Ga), *Gr = malloc(n * nc * sizeof *Gr);
    gsl_matrix *Phi = gsl_matrix_alloc(n, n);
    td_status st =
        A && Bu && Ph && Ga && Gr && Phi ? TD_OK : td_error_set(err, TD_ERR_NOMEM, "loop analysis: out of memory");
    for (i = 0; st == TD_OK && i < n; i++) {
        for (j = 0; j < n; j++)
            A[i + j * n] = gsl_matrix_get(ss->A, i, j);
        for (j = 0; j < nc; j++)
            Bu[i + j * n] = Bz[i * (size_t)l->m + j];
    }
    if (st == TD_OK)
        st = td_sampled_hold(ss->n, l->rate, A, Bu, l->nc, Ph, Ga, err);
    for (i = 0; st == TD_OK && i < n; i++) {
        for (j = 0; j < n; j++)
            gsl_matrix_set(Phi, i, j, Ph[i + j * n]);
        for (j = 0; j < nc; j++)
            Gr[i * nc + j] = Ga[i + j * n];
    }
    l->n_plants = 2;
    l->plant[0].m = l->nc, l->plant[0].col0 = 0, l->plant[0].discrete = 1;
    l->plant[1].m = l->na, l->plant[1].col0 = l->nc, l->plant[1].discrete = 0;
    if (st == TD_OK)
        st = hessenberg_plant(l, &l->plant[0], Phi, Gr, l->nc, Cz, err);
    if (st == TD_OK)
        st = hessenberg_plant(l, &l->plant[1], ss->A, Bz + l->nc, l->m, Cz, err);
    free(A), free(Bu), free(Ph), free(Ga), free(Gr);
    gsl_matrix_free(Phi);
    return st;
}

static td_status build_plant(const td_system *sys, const int *driven, td_loop *l, td_error *err)
{
    td_state_space ss;
    double *Bz = NULL, *Cz = NULL;
    td_status st = open_loop_state_space(sys, driven, l->omega, &ss, err);
    if (st != TD_OK)
        return st;
    l->n = ss.n;
    Bz = malloc((size_t)ss.n * (size_t)l->m * sizeof *Bz);
    Cz = malloc((size_t)ss.n * (size_t)l->p * sizeof *Cz);
    if (!Bz || !Cz)
        st = td_error_set(err, TD_ERR_NOMEM, "loop analysis: out of memory for a %d-state plant", ss.n);
    if (st == TD_OK)
        st = plant_io(sys, l, &ss, Bz, Cz, err);
    if (st == TD_OK && l->rate > 0.0)
        st = sampled_plant(l, &ss, Bz, Cz, err);
    else if (st == TD_OK) {
        l->n_plants = 1;
        l->plant[0].m = l->m, l->plant[0].col0 = 0, l->plant[0].discrete = 0;
        st = hessenberg_plant(l, &l->plant[0], ss.A, Bz, l->m, Cz, err);
    }
    free(Bz);
    free(Cz);
    td_state_space_free(&ss);
    return st;
}

/* ---- the controllers ---------------------------------------------------------------------- */

/* Block b: controller k (taken) from the sensors `in` to the currents `out` (AMB axes). */
static td_status add_block(td_loop *l, td_controller *k, const int *in, const int *out, const int *pos_s,
                           const int *pos_c, td_error *err)
{
    loop_block *b = &l->blocks[l->n_blocks];
    int i;
    if (!k)
        return err && err->code != TD_OK ? err->code : TD_ERR_NOMEM;
    b->k = k;
    l->n_blocks++;
    b->nin = td_controller_inputs(k);
    b->nout = td_controller_outputs(k);
    b->rows = malloc((size_t)b->nout * sizeof *b->rows);
    b->cols = malloc((size_t)b->nin * sizeof *b->cols);
    if (!b->rows || !b->cols)
        return td_error_set(err, TD_ERR_NOMEM, "loop analysis: out of memory");
    for (i = 0; i < b->nout; i++)
        b->rows[i] = pos_c[out[i]];
    for (i = 0; i < b->nin; i++)
        b->cols[i] = pos_s[in[i]];
    return TD_OK;
}

/* Every controller: a PID block (td_controller_create_pid, exact derivative) per shorthand axis,
 * then the system's linear controllers as it runs them. */
static td_status build_controllers(const td_system *sys, td_loop *l, const int *pos_s, const int *pos_c, td_error *err)
{
    td_status st = TD_OK;
    int a, i;
    l->blocks = calloc((size_t)(sys->n_amb_axes + sys->n_laws + 1), sizeof *l->blocks);
    if (!l->blocks)
        return td_error_set(err, TD_ERR_NOMEM, "loop analysis: out of memory");
    for (a = 0; st == TD_OK && a < sys->n_amb_axes; a++) {
        const td_amb_axis *x = &sys->amb_axes[a];
        if (l->rate == 0.0 && shorthand_controlled(x)) { /* a sampled loop's plant holds them */
            /* the shorthand's current -(kp xs + kd vs + kint e) is kp + kd s + kint/s acting on -xs */
            td_pid_block pid;
            pid.kp = x->kp;
            pid.kint = x->kint;
            pid.kd = x->kd;
            pid.derivative_filter = 0.0;
            st = add_block(l, td_controller_create_pid(&pid, err), &a, &a, pos_s, pos_c, err);
        }
    }
    for (i = 0; st == TD_OK && i < sys->n_laws; i++) {
        const td_lti_law *w = &sys->laws[i];
        td_controller *k;
        if ((w->state < 0) != (l->rate > 0.0) || w->standby)
            continue; /* a continuous law in a sampled loop: the plant holds it; a standby law drives nothing */
        k = td_controller_create_ss(w->n, w->nin, w->nout, w->A, w->B, w->C, w->D, w->D1,
                                    w->state < 0 ? w->sample_rate : 0.0, err);
        st = add_block(l, k, w->in_axis, w->out_axis, pos_s, pos_c, err);
    }
    return st;
}

/* ---- one frequency ------------------------------------------------------------------------ */

static void work_free(loop_work *w)
{
    free(w->T);
    free(w->Y);
    free(w->G);
    free(w->K);
    free(w->M);
    free(w->X);
    free(w->kre);
    free(w->kim);
    if (w->perm)
        gsl_permutation_free(w->perm);
    memset(w, 0, sizeof *w);
}

static td_status work_alloc(const td_loop *l, loop_work *w, td_error *err)
{
    size_t n = (size_t)l->n, kmax = 1;
    int i;
    for (i = 0; i < l->n_blocks; i++)
        if ((size_t)(l->blocks[i].nin * l->blocks[i].nout) > kmax)
            kmax = (size_t)(l->blocks[i].nin * l->blocks[i].nout);
    memset(w, 0, sizeof *w);
    w->T = malloc(n * n * sizeof *w->T);
    w->Y = malloc(n * (size_t)l->m * sizeof *w->Y);
    w->G = malloc((size_t)l->p * (size_t)l->m * sizeof *w->G);
    w->K = malloc((size_t)l->nc * (size_t)l->ns * sizeof *w->K);
    w->M = malloc((size_t)l->nc * (size_t)l->nc * sizeof *w->M);
    w->X = malloc((size_t)l->nc * (size_t)(l->nc + l->na) * sizeof *w->X);
    w->kre = malloc(kmax * sizeof *w->kre);
    w->kim = malloc(kmax * sizeof *w->kim);
    w->perm = gsl_permutation_alloc((size_t)l->nc);
    if (w->T && w->Y && w->G && w->K && w->M && w->X && w->kre && w->kim && w->perm)
        return TD_OK;
    work_free(w);
    return td_error_set(err, TD_ERR_NOMEM, "loop analysis: out of memory");
}

/* G's columns pl->col0.. = C (x I - H)^-1 B (p x pl->m): Gaussian elimination with partial pivoting
 * on the Hessenberg matrix (one subdiagonal: each step pivots between two rows), then back
 * substitution. Returns 0 when x is an eigenvalue of the plant to working precision. */
static int plant_block(const td_loop *l, const loop_plant *pl, double complex x, loop_work *wk)
{
    size_t n = (size_t)l->n, m = (size_t)pl->m, p = (size_t)l->p, i, j, k;
    double complex *T = wk->T, *Y = wk->Y;
    for (i = 0; i < n; i++) {
        for (j = 0; j < n; j++)
            T[i * n + j] = (i == j ? x : 0.0) - pl->H[i * n + j];
        for (j = 0; j < m; j++)
            Y[i * m + j] = pl->B[i * m + j];
    }
    for (k = 0; k + 1 < n; k++) {
        double complex f;
        if (cabs(T[(k + 1) * n + k]) > cabs(T[k * n + k])) {
            for (j = k; j < n; j++) {
                double complex t = T[k * n + j];
                T[k * n + j] = T[(k + 1) * n + j];
                T[(k + 1) * n + j] = t;
            }
            for (j = 0; j < m; j++) {
                double complex t = Y[k * m + j];
                Y[k * m + j] = Y[(k + 1) * m + j];
                Y[(k + 1) * m + j] = t;
            }
        }
        if (T[k * n + k] == 0.0)
            return 0;
        f = T[(k + 1) * n + k] / T[k * n + k];
        for (j = k + 1; j < n; j++)
            T[(k + 1) * n + j] -= f * T[k * n + j];
        for (j = 0; j < m; j++)
            Y[(k + 1) * m + j] -= f * Y[k * m + j];
    }
    for (k = n; k-- > 0;) {
        double complex d;
        if (T[k * n + k] == 0.0)
            return 0;
        d = 1.0 / T[k * n + k];
        for (j = 0; j < m; j++) {
            double complex s = Y[k * m + j];
            for (i = k + 1; i < n; i++)
                s -= T[k * n + i] * Y[i * m + j];
            Y[k * m + j] = s * d;
        }
    }
    for (i = 0; i < p; i++)
        for (j = 0; j < m; j++) {
            double complex s = 0.0;
            for (k = 0; k < n; k++)
                s += pl->C[i * n + k] * Y[k * m + j];
            wk->G[i * (size_t)l->m + (size_t)pl->col0 + j] = s;
        }
    return 1;
}

/* G = P (p x m) at w rad/s: each plant part at jw, or at e^{jwT} for the held currents of a sampled
 * loop. Returns 0 at a pole of the plant. */
static int plant_response(const td_loop *l, double w, loop_work *wk)
{
    int b;
    for (b = 0; b < l->n_plants; b++)
        if (!plant_block(l, &l->plant[b], l->plant[b].discrete ? cexp(I * w / l->rate) : I * w, wk))
            return 0;
    return 1;
}

/* K (nc x ns, row-major) at f Hz from every block. */
static td_status controller_response(const td_loop *l, double f, loop_work *wk, td_error *err)
{
    int b, i, j;
    for (i = 0; i < l->nc * l->ns; i++)
        wk->K[i] = 0.0;
    for (b = 0; b < l->n_blocks; b++) {
        const loop_block *k = &l->blocks[b];
        td_status st = td_controller_frequency_response(k->k, f, wk->kre, wk->kim, err);
        if (st != TD_OK)
            return st;
        for (j = 0; j < k->nin; j++) /* column-major outputs x inputs */
            for (i = 0; i < k->nout; i++)
                wk->K[k->rows[i] * l->ns + k->cols[j]] += wk->kre[i + j * k->nout] + I * wk->kim[i + j * k->nout];
    }
    return TD_OK;
}

/* At f Hz: M = I + K P_si, factored, and X = M^-1 [I | K P_sf] (nc x (nc + na)): its first nc
 * columns are the input sensitivity, the rest the currents per unit actuator force. */
static td_status close_loop(const td_loop *l, double f, loop_work *wk, td_error *err)
{
    int nc = l->nc, ns = l->ns, m = l->m, i, j, q, sign;
    gsl_matrix_complex_view M = gsl_matrix_complex_view_array((double *)wk->M, (size_t)nc, (size_t)nc);
    td_status st;
    if (!plant_response(l, LOOP_TWO_PI * f, wk))
        return td_error_set(err, TD_ERR_NUMERIC, "loop analysis: %.9g Hz is a pole of the plant", f);
    if ((st = controller_response(l, f, wk, err)) != TD_OK)
        return st;
    for (i = 0; i < nc; i++) {
        for (j = 0; j < nc + l->na; j++) {
            double complex s = j == i ? 1.0 : 0.0;
            for (q = 0; q < ns; q++) /* K P_si (j < nc) or K P_sf (j >= nc): P_s* are G's first ns rows */
                s += wk->K[i * ns + q] * wk->G[q * m + j];
            if (j < nc)
                wk->M[i * nc + j] = s;
            wk->X[i * m + j] = j < nc ? (j == i ? 1.0 : 0.0) : s;
        }
    }
    if (gsl_linalg_complex_LU_decomp(&M.matrix, wk->perm, &sign) != GSL_SUCCESS)
        return td_error_set(err, TD_ERR_NUMERIC, "loop analysis: I + K P is singular at %.9g Hz", f);
    for (j = 0; j < m; j++) {
        gsl_vector_complex_view x =
            gsl_vector_complex_view_array_with_stride((double *)(wk->X + j), (size_t)m, (size_t)nc);
        if (gsl_linalg_complex_LU_svx(&M.matrix, wk->perm, &x.vector) != GSL_SUCCESS)
            return td_error_set(err, TD_ERR_NUMERIC, "loop analysis: I + K P is singular at %.9g Hz", f);
    }
    return TD_OK;
}

/* Compliance of AMB axis a with the loops closed: P_af - P_ai M^-1 K P_sf, diagonal entry. */
static double complex compliance(const td_loop *l, const loop_work *wk, int a)
{
    int m = l->m, row = l->ns + a, col = l->nc + a, j;
    double complex c = wk->G[row * m + col];
    for (j = 0; j < l->nc; j++)
        c -= wk->G[row * m + j] * wk->X[j * m + col];
    return c;
}

/* ---- the grid, the peaks, stability ------------------------------------------------------- */

/* An undefined complex value: both parts TD_UNDEFINED. */
static double complex undefined_complex(void)
{
    double complex z = 0.0;
    double *part = (double *)&z; /* C99 6.2.5: a complex is an array of its two parts */
    part[0] = part[1] = TD_UNDEFINED;
    return z;
}

static td_status fill_grid(td_loop *l, loop_work *wk, td_error *err)
{
    int k, j;
    for (k = 0; k < l->nf; k++) {
        td_status st = close_loop(l, l->freq[k], wk, err);
        if (st != TD_OK)
            return st;
        for (j = 0; j < l->nc; j++) {
            double complex s = wk->X[j * l->m + j];
            l->l[(size_t)k * (size_t)l->nc + (size_t)j] = 1.0 / s - 1.0;
            l->s[(size_t)k * (size_t)l->nc + (size_t)j] = l->stable ? s : undefined_complex();
        }
        for (j = 0; j < l->na; j++)
            l->comp[(size_t)k * (size_t)l->na + (size_t)j] = l->stable ? compliance(l, wk, j) : undefined_complex();
    }
    return TD_OK;
}

typedef struct peak_fn {
    const td_loop *l;
    loop_work *wk;
    int j;
    int failed;
} peak_fn;

/* -|S_j| at f = e^x (GSL minimises). */
static double minus_abs_s(double x, void *data)
{
    peak_fn *p = data;
    if (close_loop(p->l, exp(x), p->wk, NULL) != TD_OK) {
        p->failed = 1;
        return 0.0;
    }
    return -cabs(p->wk->X[p->j * p->l->m + p->j]);
}

/* Brent's method on -|S_j(e^x)| over [flo, fhi] Hz from f inside, where |S_j| is larger than at
 * both ends (else nothing); a better peak replaces l->peak[j]. */
static void refine_peak(td_loop *l, loop_work *wk, int j, double flo, double f, double fhi)
{
    gsl_min_fminimizer *s = gsl_min_fminimizer_alloc(gsl_min_fminimizer_brent);
    peak_fn p;
    gsl_function fn;
    int it, status = GSL_CONTINUE;
    p.l = l, p.wk = wk, p.j = j, p.failed = 0;
    fn.function = minus_abs_s;
    fn.params = &p;
    if (!s)
        return;
    if (gsl_min_fminimizer_set(s, &fn, log(f), log(flo), log(fhi)) == GSL_SUCCESS) {
        for (it = 0; it < 100 && status == GSL_CONTINUE && !p.failed; it++) {
            if (gsl_min_fminimizer_iterate(s) != GSL_SUCCESS)
                break;
            status = gsl_min_test_interval(gsl_min_fminimizer_x_lower(s), gsl_min_fminimizer_x_upper(s), 0.0, 1e-12);
        }
        if (!p.failed && -gsl_min_fminimizer_f_minimum(s) > l->peak[j]) {
            l->peak[j] = -gsl_min_fminimizer_f_minimum(s);
            l->peak_freq[j] = exp(gsl_min_fminimizer_x_minimum(s));
        }
    }
    gsl_min_fminimizer_free(s);
}

/* A lightly damped closed-loop mode makes a peak of |S| narrower than the grid's spacing, which
 * the grid can step over: |S| at each such mode's damped frequency; per axis the largest, where it
 * beats the grid's peak, refined over +-3 zeta of its mode. */
static void mode_peaks(td_loop *l, loop_work *wk)
{
    double *best = malloc(2u * (size_t)l->nc * sizeof *best);
    int *at = malloc((size_t)l->nc * sizeof *at), i, j;
    for (j = 0; best && at && j < l->nc; j++) {
        best[j] = l->peak[j];
        at[j] = -1;
    }
    for (i = 0; best && at && i < l->n_modes; i++) {
        double f = l->mode_f[i];
        if (f < l->freq[0] || f > l->freq[l->nf - 1] || close_loop(l, f, wk, NULL) != TD_OK)
            continue;
        for (j = 0; j < l->nc; j++)
            if (cabs(wk->X[j * l->m + j]) > best[j]) {
                best[j] = cabs(wk->X[j * l->m + j]);
                at[j] = i;
            }
    }
    for (j = 0; best && at && j < l->nc; j++)
        if (at[j] >= 0) {
            double f = l->mode_f[at[j]], h = fmax(3.0 * l->mode_zeta[at[j]], 1e-9), hi = f * (1.0 + h);
            l->peak[j] = best[j];
            l->peak_freq[j] = f;
            refine_peak(l, wk, j, f / (1.0 + h), f, l->rate > 0.0 ? fmin(hi, l->freq[l->nf - 1]) : hi);
        }
    free(best);
    free(at);
}

static void find_peaks(td_loop *l, loop_work *wk)
{
    int j, k;
    for (j = 0; j < l->nc; j++) {
        int best = 0;
        l->peak[j] = l->peak_freq[j] = TD_UNDEFINED;
        if (!l->stable)
            continue;
        for (k = 1; k < l->nf; k++)
            if (cabs(l->s[(size_t)k * (size_t)l->nc + (size_t)j]) >
                cabs(l->s[(size_t)best * (size_t)l->nc + (size_t)j]))
                best = k;
        l->peak[j] = cabs(l->s[(size_t)best * (size_t)l->nc + (size_t)j]);
        l->peak_freq[j] = l->freq[best];
        if (best > 0 && best + 1 < l->nf)
            refine_peak(l, wk, j, l->freq[best - 1], l->freq[best], l->freq[best + 1]);
    }
    if (l->stable)
        mode_peaks(l, wk);
}

/* The closed loop's eigenvalues (td_modal_solve): stable unless some eigenvalue grows beyond the
 * rounding of a marginal root (td_modal_is_unstable). An undamped closed-loop mode (an undamped
 * shaft's mode that no AMB sees, e.g. with nodes at the AMBs) keeps the loop stable; one that S
 * sees shows as a peak without bound. */
static td_status closed_loop_stability(const td_system *sys, td_loop *l, td_error *err)
{
    td_modal *md = NULL;
    td_status st = td_modal_solve(sys, l->omega, &md, err);
    int i;
    if (st != TD_OK)
        return st;
    l->max_real = td_modal_max_real_part(md);
    l->stable = !td_modal_is_unstable(md); /* a sampled loop's: ln |mu| within the rounding (eigen.c) */
    l->mode_f = malloc(((size_t)td_modal_mode_count(md) + 1u) * sizeof *l->mode_f);
    l->mode_zeta = malloc(((size_t)td_modal_mode_count(md) + 1u) * sizeof *l->mode_zeta);
    for (i = 0; l->mode_f && l->mode_zeta && i < td_modal_mode_count(md); i++) {
        td_mode m;
        td_modal_get_mode(md, i, &m);
        if (m.zeta < LOOP_LIGHT_DAMPING && m.zeta >= 0.0) {
            l->mode_f[l->n_modes] = m.freq_hz;
            l->mode_zeta[l->n_modes++] = m.zeta;
        }
    }
    td_modal_free(&md);
    if (!l->mode_f || !l->mode_zeta)
        return td_error_set(err, TD_ERR_NOMEM, "loop analysis: out of memory");
    return TD_OK;
}

/* ---- public ------------------------------------------------------------------------------- */

static td_status check_options(const td_loop_options *o, td_error *err)
{
    if (!(o->f_min > 0.0) || !(o->f_max > o->f_min) || !isfinite(o->f_max) || o->points < 2 || o->points > 1000000)
        return td_error_set(err, TD_ERR_INVALID,
                            "loop analysis: the grid wants 0 < f_min < f_max (finite) and 2..1000000 points "
                            "(got %g, %g, %d)",
                            o->f_min, o->f_max, o->points);
    return TD_OK;
}

/* The axis lists, the grid and the result arrays of a new analysis. */
static td_status loop_alloc(const td_system *sys, const td_loop_options *o, td_loop *l, int *pos_s, int *pos_c,
                            td_error *err)
{
    int *driven = calloc((size_t)sys->n_amb_axes + 1u, sizeof *driven);
    int *sensed = calloc((size_t)sys->n_amb_axes + 1u, sizeof *sensed), k;
    td_status st = driven && sensed ? TD_OK : td_error_set(err, TD_ERR_NOMEM, "loop analysis: out of memory");
    double f_max = o->f_max;
    if (st == TD_OK)
        loop_axes(sys, driven, sensed, &l->rate);
    if (l->rate > 0.0) /* a sampled loop's response repeats beyond the Nyquist frequency */
        f_max = fmin(f_max, 0.5 * l->rate);
    if (st == TD_OK && !(o->f_min < f_max))
        st = td_error_set(err, TD_ERR_INVALID,
                          "loop analysis: the grid's f_min %g Hz is not below the sampled loop's Nyquist frequency "
                          "%g Hz",
                          o->f_min, f_max);
    l->axis = malloc(((size_t)sys->n_amb_axes + 1u) * sizeof *l->axis);
    l->sensor = malloc(((size_t)sys->n_amb_axes + 1u) * sizeof *l->sensor);
    if (st == TD_OK && (!l->axis || !l->sensor))
        st = td_error_set(err, TD_ERR_NOMEM, "loop analysis: out of memory");
    if (st == TD_OK) {
        l->nc = list_axes(driven, sys->n_amb_axes, l->axis, pos_c);
        l->ns = list_axes(sensed, sys->n_amb_axes, l->sensor, pos_s);
        l->na = sys->n_amb_axes;
        l->m = l->nc + l->na;
        l->p = l->ns + l->na;
        if (l->nc == 0)
            st = td_error_set(err, TD_ERR_INVALID, "no loop analysis: no AMB axis is under control");
    }
    if (st == TD_OK)
        st = build_plant(sys, driven, l, err);
    free(driven);
    free(sensed);
    l->nf = o->points;
    l->freq = malloc((size_t)l->nf * sizeof *l->freq);
    l->s = malloc((size_t)l->nf * (size_t)(l->nc + 1) * sizeof *l->s);
    l->l = malloc((size_t)l->nf * (size_t)(l->nc + 1) * sizeof *l->l);
    l->comp = malloc((size_t)l->nf * (size_t)(l->na + 1) * sizeof *l->comp);
    l->peak = malloc((size_t)(l->nc + 1) * sizeof *l->peak);
    l->peak_freq = malloc((size_t)(l->nc + 1) * sizeof *l->peak_freq);
    if (st == TD_OK && (!l->freq || !l->s || !l->l || !l->comp || !l->peak || !l->peak_freq))
        st = td_error_set(err, TD_ERR_NOMEM, "loop analysis: out of memory");
    for (k = 0; st == TD_OK && k < l->nf; k++) /* log-spaced, the ends exact */
        l->freq[k] = k == 0           ? o->f_min
                     : k == l->nf - 1 ? f_max
                                      : o->f_min * pow(f_max / o->f_min, (double)k / (double)(l->nf - 1));
    return st;
}

td_status td_loop_compute(const td_system *sys, double omega, const td_loop_options *opt, td_loop **out, td_error *err)
{
    td_loop_options o;
    td_loop *l;
    loop_work wk;
    int *pos = NULL;
    td_status st;
    if (!out)
        return td_error_set(err, TD_ERR_INVALID, "td_loop_compute: NULL output pointer");
    *out = NULL;
    if (!sys)
        return td_error_set(err, TD_ERR_INVALID, "td_loop_compute: NULL system");
    if (!TD_SPEED_VALID(omega))
        return td_error_set(err, TD_ERR_INVALID, "loop analysis: speed must be finite and >= 0 rad/s (got %g)", omega);
    if (td_system_refuse_plugins(sys, err) != TD_OK)
        return TD_ERR_INVALID;
    if (td_modal_state_count(sys) > TD_LOOP_MAX_STATES)
        return td_error_set(err, TD_ERR_INVALID,
                            "no loop analysis: %d first-order states, more than the %d it takes (a reduction of "
                            "the shaft brings the model under it)",
                            td_modal_state_count(sys), TD_LOOP_MAX_STATES);
    td_loop_options_default(&o);
    if (opt)
        o = *opt;
    if ((st = check_options(&o, err)) != TD_OK)
        return st;
    td_modal_gsl_quiet();
    l = calloc(1, sizeof *l);
    pos = malloc(2u * ((size_t)sys->n_amb_axes + 1u) * sizeof *pos);
    if (!l || !pos) {
        free(l);
        free(pos);
        return td_error_set(err, TD_ERR_NOMEM, "loop analysis: out of memory");
    }
    l->omega = omega;
    st = loop_alloc(sys, &o, l, pos, pos + sys->n_amb_axes + 1, err);
    if (st == TD_OK)
        st = build_controllers(sys, l, pos, pos + sys->n_amb_axes + 1, err);
    free(pos);
    if (st == TD_OK)
        st = closed_loop_stability(sys, l, err);
    if (st == TD_OK && (st = work_alloc(l, &wk, err)) == TD_OK) {
        st = fill_grid(l, &wk, err);
        if (st == TD_OK)
            find_peaks(l, &wk);
        work_free(&wk);
    }
    if (st != TD_OK)
        td_loop_free(&l);
    *out = l;
    return st;
}

void td_loop_free(td_loop **lp)
{
    td_loop *l;
    int i;
    if (!lp || !*lp)
        return;
    l = *lp;
    for (i = 0; l->blocks && i < l->n_blocks; i++) {
        td_controller_free(&l->blocks[i].k);
        free(l->blocks[i].rows);
        free(l->blocks[i].cols);
    }
    free(l->blocks);
    free(l->axis);
    free(l->sensor);
    for (i = 0; i < 2; i++) {
        free(l->plant[i].H);
        free(l->plant[i].B);
        free(l->plant[i].C);
    }
    free(l->freq);
    free(l->s);
    free(l->l);
    free(l->comp);
    free(l->peak);
    free(l->peak_freq);
    free(l->mode_f);
    free(l->mode_zeta);
    free(l);
    *lp = NULL;
}

double td_loop_speed(const td_loop *l)
{
    return l ? l->omega : TD_UNDEFINED;
}

double td_loop_sample_rate(const td_loop *l)
{
    return l ? l->rate : TD_UNDEFINED;
}

int td_loop_stable(const td_loop *l)
{
    return l ? l->stable : 0;
}

double td_loop_max_real_part(const td_loop *l)
{
    return l ? l->max_real : TD_UNDEFINED;
}

int td_loop_axis_count(const td_loop *l)
{
    return l ? l->nc : 0;
}

int td_loop_axis(const td_loop *l, int j)
{
    return l && j >= 0 && j < l->nc ? l->axis[j] : -1;
}

int td_loop_amb_axis_count(const td_loop *l)
{
    return l ? l->na : 0;
}

int td_loop_frequency_count(const td_loop *l)
{
    return l ? l->nf : 0;
}

double td_loop_frequency(const td_loop *l, int k)
{
    return l && k >= 0 && k < l->nf ? l->freq[k] : TD_UNDEFINED;
}

/* Entry (k, j) of an nf x cols table into re, im. */
static td_status table_get(const td_loop *l, const double complex *t, int cols, int j, int k, double *re, double *im)
{
    double complex v;
    if (!l || j < 0 || j >= cols || k < 0 || k >= l->nf)
        return TD_ERR_INVALID;
    v = t[(size_t)k * (size_t)cols + (size_t)j];
    if (re)
        *re = creal(v);
    if (im)
        *im = cimag(v);
    return TD_OK;
}

td_status td_loop_sensitivity(const td_loop *l, int j, int k, double *re, double *im)
{
    return table_get(l, l ? l->s : NULL, l ? l->nc : 0, j, k, re, im);
}

td_status td_loop_open_loop(const td_loop *l, int j, int k, double *re, double *im)
{
    return table_get(l, l ? l->l : NULL, l ? l->nc : 0, j, k, re, im);
}

td_status td_loop_compliance(const td_loop *l, int a, int k, double *re, double *im)
{
    return table_get(l, l ? l->comp : NULL, l ? l->na : 0, a, k, re, im);
}

double td_loop_sensitivity_peak(const td_loop *l, int j)
{
    return l && j >= 0 && j < l->nc ? l->peak[j] : TD_UNDEFINED;
}

double td_loop_sensitivity_peak_frequency(const td_loop *l, int j)
{
    return l && j >= 0 && j < l->nc ? l->peak_freq[j] : TD_UNDEFINED;
}

char td_loop_sensitivity_zone(const td_loop *l, int j)
{
    return td_loop_zone(td_loop_sensitivity_peak(l, j));
}

char td_loop_worst_zone(const td_loop *l)
{
    char worst = 0;
    int j;
    for (j = 0; l && l->stable && j < l->nc; j++) {
        char z = td_loop_sensitivity_zone(l, j);
        if (z > worst)
            worst = z;
    }
    return worst;
}

td_status td_loop_evaluate(const td_loop *l, int j, double f, double *s_re, double *s_im, double *l_re, double *l_im,
                           td_error *err)
{
    loop_work wk;
    td_status st;
    double complex s;
    if (!l || j < 0 || j >= l->nc || !(f > 0.0) || !isfinite(f) || (l->rate > 0.0 && f > 0.5 * l->rate))
        return td_error_set(err, TD_ERR_INVALID,
                            "td_loop_evaluate: no axis %d or a bad frequency %g Hz (a sampled loop's: up to the "
                            "Nyquist frequency)",
                            j, f);
    if ((st = work_alloc(l, &wk, err)) != TD_OK)
        return st;
    st = close_loop(l, f, &wk, err);
    s = wk.X[j * l->m + j];
    work_free(&wk);
    if (st != TD_OK)
        return st;
    if (s_re)
        *s_re = l->stable ? creal(s) : TD_UNDEFINED;
    if (s_im)
        *s_im = l->stable ? cimag(s) : TD_UNDEFINED;
    if (l_re)
        *l_re = creal(1.0 / s - 1.0);
    if (l_im)
        *l_im = cimag(1.0 / s - 1.0);
    return TD_OK;
}
