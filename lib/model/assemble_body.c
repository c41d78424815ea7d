/*
 * The compliant housing's DOFs in the assembled system (touchdown/housing.h td_housing_body, kept by
 * housing_body.c; docs/theory.md, "Compliant housing").
 *
 * The rotor's coordinates q stay relative to the housing; the body's DOFs h (x, y of its centre of
 * mass, then with an inertia its tilts theta, phi: touchdown/dofs.h) are relative to the base and
 * appended after q. With R the rotor's rigid displacement of a unit h (a translation, or a
 * rotation about the body's centre z_c: node i moves by x_i = (z_i - z_c) phi, y_i = -(z_i - z_c)
 * theta and turns by theta, phi), the rotor's absolute displacement is q + R h and Lagrange's
 * equations on the absolute kinetic energy give, in (q, h),
 *
 *   M_c = [M, M R; R^T M, M_h + R^T M R],   G_c = [G, G R; R^T G, R^T G R],
 *   K_c = [K, 0; 0, K_h],                   C_c = [C, 0; 0, C_h],
 *
 * with M_h = diag(m, m, I, I) and K_h, C_h the mounts' (a mount k at z_m: k (x + (z_m - z_c) phi)^2 / 2
 * and likewise in y). K and C stay on q: the shaft's elasticity, its Rayleigh damping and the plain
 * bearings act on the motion relative to the housing, and so do the AMBs and the contacts, whose
 * reactions on the housing cancel their share R^T f on h (internal forces). A force from outside
 * the machine on the rotor (its weight, an unbalance) acts on h through R^T f as well.
 */
#include "model/model_internal.h"
#include "model/rigid_motion.h"
#include "model/system_internal.h"
#include "util/error_internal.h"

#include <stdlib.h>
#include <string.h>

/* The dense R, nr x nb column-major: each rotor coordinate's rigid displacement of a unit body DOF
 * (a modal coordinate of a reduced rotor has none: the boundary's rigid motion carries the interior
 * with it exactly, K R = 0). */
static void rigid_field(const td_system *s, int nr, int nb, double *R)
{
    double zc = s->model->body.centre;
    int i;
    for (i = 0; i < nr; i++) {
        int off, node = td_system_coordinate_node(s, i, &off), j;
        double d = node >= 0 ? td_model_node_position(s->model, node) - zc : 0.0, u[TD_DOFS_PER_NODE];
        if (node < 0)
            continue;
        for (j = 0; j < nb; j++) { /* translation x, y; rotation about x, y (nb = 4) */
            td_rigid_unit_at(j, d, u);
            R[i + (size_t)j * nr] = u[off];
        }
    }
}

/* AR = A R (nr x nb) and RA = (R^T A)^T (nr x nb: column j holds row j of R^T A) for a sparse A. */
static void products(const cs_di *A, const double *R, int nr, int nb, double *AR, double *RA)
{
    int c, p, j;
    memset(AR, 0, (size_t)nr * (size_t)nb * sizeof *AR);
    memset(RA, 0, (size_t)nr * (size_t)nb * sizeof *RA);
    for (c = 0; c < nr; c++)
        for (p = A->p[c]; p < A->p[c + 1]; p++)
            for (j = 0; j < nb; j++) {
                AR[A->i[p] + (size_t)j * nr] += A->x[p] * R[c + (size_t)j * nr];
                RA[c + (size_t)j * nr] += R[A->i[p] + (size_t)j * nr] * A->x[p];
            }
}

/* A entered into the triplets T, rows and columns unchanged. 0 on out-of-memory. */
static int copy_entries(cs_di *T, const cs_di *A)
{
    int c, p;
    for (c = 0; c < A->n; c++)
        for (p = A->p[c]; p < A->p[c + 1]; p++)
            if (!cs_di_entry(T, A->i[p], c, A->x[p]))
                return 0;
    return 1;
}

/* v at (i, j) unless exactly zero; 0 on out-of-memory. */
static int entry(cs_di *T, int i, int j, double v)
{
    return v == 0.0 || cs_di_entry(T, i, j, v);
}

/* A_c = [A, A R; R^T A, B + R^T A R] (B nb x nb, column-major; NULL: none), compressed with rows
 * sorted. NULL on out-of-memory. */
static cs_di *coupled(const cs_di *A, const double *R, int nr, int nb, const double *B)
{
    int n = nr + nb, i, j, ok;
    double *AR = malloc((size_t)nr * (size_t)nb * sizeof *AR), *RA = malloc((size_t)nr * (size_t)nb * sizeof *RA);
    cs_di *T = cs_di_spalloc(n, n, A->p[A->n] + 2 * nr * nb + nb * nb, 1, 1), *C = NULL;
    ok = AR && RA && T && copy_entries(T, A);
    if (ok)
        products(A, R, nr, nb, AR, RA);
    for (j = 0; ok && j < nb; j++) {
        for (i = 0; ok && i < nr; i++)
            ok = entry(T, i, nr + j, AR[i + (size_t)j * nr]) && entry(T, nr + j, i, RA[i + (size_t)j * nr]);
        for (i = 0; ok && i < nb; i++) {
            double v = B ? B[i + j * nb] : 0.0;
            int k;
            for (k = 0; k < nr; k++) /* (R^T A R)(i, j) */
                v += R[k + (size_t)i * nr] * AR[k + (size_t)j * nr];
            ok = entry(T, nr + i, nr + j, v);
        }
    }
    if (ok)
        C = td_system_compress(T);
    free(AR), free(RA), cs_di_spfree(T);
    return C;
}

/* A (nr x nr) with the body's block B (nb x nb, column-major) on the diagonal after it. */
static cs_di *blocked(const cs_di *A, int nr, int nb, const double *B)
{
    int n = nr + nb, i, j, ok;
    cs_di *T = cs_di_spalloc(n, n, A->p[A->n] + nb * nb, 1, 1), *C = NULL;
    ok = T && copy_entries(T, A);
    for (j = 0; ok && j < nb; j++)
        for (i = 0; ok && i < nb; i++)
            ok = entry(T, nr + i, nr + j, B[i + j * nb]);
    if (ok)
        C = td_system_compress(T);
    cs_di_spfree(T);
    return C;
}

/* The mounts' stiffness (which 'K') or damping ('C') on the body's DOFs, nb x nb column-major. */
static void mount_block(const td_housing_body *b, int nb, char which, double *B)
{
    int i;
    memset(B, 0, 16 * sizeof *B);
    for (i = 0; i < b->mount_count; i++) {
        double k = which == 'K' ? b->mounts[i].stiffness : b->mounts[i].damping, d = b->mounts[i].position - b->centre;
        B[0] += k;      /* x x */
        B[1 + nb] += k; /* y y */
        if (nb == 4) {  /* x_m = x + d phi, y_m = y - d theta */
            B[0 + 3 * nb] += k * d, B[3 + 0 * nb] += k * d;
            B[1 + 2 * nb] -= k * d, B[2 + 1 * nb] -= k * d;
            B[2 + 2 * nb] += k * d * d;
            B[3 + 3 * nb] += k * d * d;
        }
    }
}

/* The weight of the whole machine on the body's DOFs: R^T (the rotor's weight) + m g on x, y. */
static td_status body_gravity(td_system *s, int nr, int nb, const double *R, td_error *err)
{
    double *g = realloc(s->gravity_load, (size_t)(nr + nb) * sizeof *g);
    int i, j;
    if (!g)
        return td_error_set(err, TD_ERR_NOMEM, "out of memory for the housing body's weight");
    s->gravity_load = g;
    for (j = 0; j < nb; j++) {
        double v = j < 2 ? s->model->body.mass * s->model->gravity[j] : 0.0;
        for (i = 0; i < nr; i++)
            v += R[i + (size_t)j * nr] * g[i];
        g[nr + j] = v;
    }
    return TD_OK;
}

/* A reduced rotor's T and q_node cover the body's coordinates too: zero columns (the body moves no
 * node relative to the housing), no node. */
static td_status extend_reduction(td_system *s, int nr, int nb, td_error *err)
{
    size_t np = (size_t)s->nphys;
    double *T;
    int *qn, j;
    if (!s->T)
        return TD_OK;
    T = realloc(s->T, np * (size_t)(nr + nb) * sizeof *T);
    if (T)
        s->T = T;
    qn = T ? realloc(s->q_node, (size_t)(nr + nb) * sizeof *qn) : NULL;
    if (!qn)
        return td_error_set(err, TD_ERR_NOMEM, "out of memory for the housing body's coordinates");
    s->q_node = qn;
    memset(T + np * (size_t)nr, 0, np * (size_t)nb * sizeof *T);
    for (j = nr; j < nr + nb; j++)
        qn[j] = -1;
    return TD_OK;
}

/* The housing motion's loads (touchdown/housing.h) with a body: the base moves the mounts. With u the
 * rotor's field of a unit base motion (the rows base_load and base_gyro hold: M u, G u) and w the
 * body's (a translation; a rotation about z_ref moves the body's centre by (z_c - z_ref) and tilts it),
 * the absolute kinetic energy gives the body's rows R^T M u + M_h w, and R^T G u for the base rate's
 * gyroscopic load. Nothing without housing motion. */
static td_status body_base_loads(td_system *s, int nr, int nb, const double *R, td_error *err)
{
    const td_housing_body *b = &s->model->body;
    double dz = b->centre - td_model_housing_reference(s->model);
    int k, i, j;
    for (k = 0; k < 6 && s->base_load[0]; k++) {
        double **f = k < 4 ? &s->base_load[k] : &s->base_gyro[k - 4], *g = realloc(*f, (size_t)(nr + nb) * sizeof *g);
        if (!g)
            return td_error_set(err, TD_ERR_NOMEM, "out of memory for the housing body's base loads");
        *f = g;
        for (j = 0; j < nb; j++) {
            double v = 0.0;
            for (i = 0; i < nr; i++)
                v += R[i + (size_t)j * nr] * g[i];
            g[nr + j] = v;
        }
        if (k < 4) { /* M_h w, w the body's field of the unit base motion k at its centre */
            double w[TD_DOFS_PER_NODE];
            td_rigid_unit_at(k, dz, w);
            for (j = 0; j < nb; j++)
                g[nr + j] += (j < 2 ? b->mass : b->inertia) * w[j];
        }
    }
    return TD_OK;
}

/* Replace M, K, C, G by their coupled forms (the file's comment) and keep R. */
static td_status couple_matrices(td_system *s, int nr, int nb, double *R, td_error *err)
{
    const td_housing_body *b = &s->model->body;
    double Mh[16] = {0}, Kh[16], Ch[16];
    cs_di *M, *K, *C, *G;
    Mh[0] = Mh[1 + nb] = b->mass;
    if (nb == 4)
        Mh[2 + 2 * nb] = Mh[3 + 3 * nb] = b->inertia;
    mount_block(b, nb, 'K', Kh);
    mount_block(b, nb, 'C', Ch);
    M = coupled(s->M, R, nr, nb, Mh);
    G = coupled(s->G, R, nr, nb, NULL);
    K = blocked(s->K, nr, nb, Kh);
    C = blocked(s->C, nr, nb, Ch);
    if (!M || !K || !C || !G) {
        cs_di_spfree(M), cs_di_spfree(K), cs_di_spfree(C), cs_di_spfree(G), free(R);
        return td_error_set(err, TD_ERR_NOMEM, "out of memory coupling the housing body");
    }
    cs_di_spfree(s->M), cs_di_spfree(s->K), cs_di_spfree(s->C), cs_di_spfree(s->G);
    s->M = M, s->K = K, s->C = C, s->G = G;
    s->body_field = R;
    return TD_OK;
}

td_status td_system_add_housing_body(td_system *s, td_error *err)
{
    int nr = s->ndof, nb = td_model_housing_body_dofs(s->model);
    double *R;
    td_status st;
    if (nb == 0)
        return TD_OK;
    R = calloc((size_t)nr * (size_t)nb, sizeof *R);
    if (!R)
        return td_error_set(err, TD_ERR_NOMEM, "out of memory for the housing body's field");
    rigid_field(s, nr, nb, R);
    st = body_gravity(s, nr, nb, R, err);
    if (st == TD_OK)
        st = extend_reduction(s, nr, nb, err);
    if (st == TD_OK)
        st = body_base_loads(s, nr, nb, R, err);
    if (st != TD_OK) {
        free(R);
        return st;
    }
    st = couple_matrices(s, nr, nb, R, err);
    if (st == TD_OK) {
        s->nbody = nb;
        s->ndof = nr + nb;
    }
    return st;
}

void td_system_body_share(const td_system *s, double *f)
{
    int nr = s->ndof - s->nbody, i, j;
    for (j = 0; j < s->nbody; j++) {
        double v = 0.0;
        for (i = 0; i < nr; i++)
            v += s->body_field[i + (size_t)j * nr] * f[i];
        f[nr + j] += v;
    }
}

void td_system_body_point_field(const td_system *s, int node, double rx[4], double ry[4])
{
    double d = td_model_node_position(s->model, node) - s->model->body.centre;
    int j;
    for (j = 0; j < 4; j++)
        rx[j] = ry[j] = 0.0;
    if (s->nbody == 0)
        return;
    for (j = 0; j < s->nbody; j++) {
        double u[TD_DOFS_PER_NODE];
        td_rigid_unit_at(j, d, u);
        rx[j] = u[TD_DOF_X];
        ry[j] = u[TD_DOF_Y];
    }
}

void td_system_body_point_force(const td_system *s, int node, double fx, double fy, double *f)
{
    double rx[4], ry[4];
    int h = s->ndof - s->nbody, j;
    if (s->nbody == 0)
        return;
    td_system_body_point_field(s, node, rx, ry);
    for (j = 0; j < s->nbody; j++)
        f[h + j] += rx[j] * fx + ry[j] * fy;
}

void td_system_body_static(const td_system *s, const double *load, double *dh)
{
    double K[16], det;
    int nb = s->nbody;
    mount_block(&s->model->body, nb, 'K', K);
    dh[0] = load[0] / K[0], dh[1] = load[1] / K[1 + nb];
    if (nb < 4)
        return;
    /* the x-phi and y-theta pairs, each 2 x 2 (positive definite: td_model_set_housing_body) */
    det = K[0] * K[3 + 3 * nb] - K[3] * K[3 * nb];
    dh[0] = (K[3 + 3 * nb] * load[0] - K[3 * nb] * load[3]) / det;
    dh[3] = (K[0] * load[3] - K[3] * load[0]) / det;
    det = K[1 + nb] * K[2 + 2 * nb] - K[2 + nb] * K[1 + 2 * nb];
    dh[1] = (K[2 + 2 * nb] * load[1] - K[1 + 2 * nb] * load[2]) / det;
    dh[2] = (K[1 + nb] * load[2] - K[2 + nb] * load[1]) / det;
}
