/*
 * td_system: assembly of the contact-free linear rotor M q'' + (C + Omega G) q' + K q = f
 * (the paper's eq. 1 with the gyroscopic term explicit; DOFs and signs in touchdown/dofs.h).
 *
 * Matrices are gathered as CXSparse triplets, compressed and summed (cs_di_dupl), then
 * transposed twice so every column holds its row indices in increasing order. Entries that
 * are exactly zero in an element matrix are not entered (so the x-z / y-z decoupling of K and M
 * stays structural); sums that cancel (e.g. the x-phi coupling at a node between two equal
 * elements) are kept as explicit zeros, so the pattern depends on the topology only.
 */
#include "model/elements.h"
#include "model/model_internal.h"
#include "model/rigid_motion.h"
#include "model/system_internal.h"
#include "util/error_internal.h"

#include <stdlib.h>
#include <string.h>

/* The four triplet matrices being gathered. */
typedef struct triplets {
    cs_di *M, *K, *C, *G;
} triplets;

static void triplets_free(triplets *t)
{
    cs_di_spfree(t->M);
    cs_di_spfree(t->K);
    cs_di_spfree(t->C);
    cs_di_spfree(t->G);
    t->M = t->K = t->C = t->G = NULL;
}

/* Add v at (i, j) unless it is exactly zero; 0 on out-of-memory. */
static int add_entry(cs_di *T, int i, int j, double v)
{
    return v == 0.0 || cs_di_entry(T, i, j, v);
}

/* Add an 8 x 8 element matrix (elements.h order) of the element joining `node` and `node + 1`. */
static int add_element_matrix(cs_di *T, int node, const double e[64], double scale)
{
    int i, j, base = TD_DOF(node, 0);
    if (scale == 0.0)
        return 1;
    for (i = 0; i < TD_ELEMENT_DOFS; i++)
        for (j = 0; j < TD_ELEMENT_DOFS; j++)
            if (!add_entry(T, base + i, base + j, scale * e[8 * i + j]))
                return 0;
    return 1;
}

/* Shaft elements: M, K, G, and Rayleigh damping alpha M_shaft + beta K_shaft into C. */
static int add_shaft(const td_model *m, triplets *t)
{
    double Me[64], Ke[64], Ge[64];
    int i;
    for (i = 0; i < m->elements.count; i++) {
        const td_shaft_element *el = &m->elements.items[i];
        td_shaft_element_matrices_kappa(el, m->shaft.beam,
                                        td_shaft_shear_coefficient(el, m->shaft.shear, m->shaft.shear_value),
                                        m->shaft.mass, Me, Ke, Ge);
        if (!add_element_matrix(t->M, i, Me, 1.0) || !add_element_matrix(t->K, i, Ke, 1.0) ||
            !add_element_matrix(t->G, i, Ge, 1.0) || !add_element_matrix(t->C, i, Me, m->shaft.rayleigh_alpha) ||
            !add_element_matrix(t->C, i, Ke, m->shaft.rayleigh_beta))
            return 0;
    }
    return 1;
}

/* Rigid discs and point masses: m on x, y; Id on theta, phi; +Ip at (theta, phi), -Ip at (phi, theta). */
static int add_discs(const td_model *m, triplets *t)
{
    int i;
    for (i = 0; i < m->discs.count; i++) {
        const td_disc *d = &m->discs.items[i];
        int th = TD_DOF(d->node, TD_DOF_THETA), ph = TD_DOF(d->node, TD_DOF_PHI);
        if (!add_entry(t->M, TD_DOF(d->node, TD_DOF_X), TD_DOF(d->node, TD_DOF_X), d->mass) ||
            !add_entry(t->M, TD_DOF(d->node, TD_DOF_Y), TD_DOF(d->node, TD_DOF_Y), d->mass) ||
            !add_entry(t->M, th, th, d->Id) || !add_entry(t->M, ph, ph, d->Id) || !add_entry(t->G, th, ph, d->Ip) ||
            !add_entry(t->G, ph, th, -d->Ip))
            return 0;
    }
    return 1;
}

/* Plain bearings: direct stiffness and damping on x and y. AMBs are not here (the axis table). */
static int add_bearings(const td_model *m, triplets *t)
{
    int i;
    for (i = 0; i < m->bearings.count; i++) {
        const td_bearing *b = &m->bearings.items[i];
        int x = TD_DOF(b->node, TD_DOF_X), y = TD_DOF(b->node, TD_DOF_Y);
        if (!add_entry(t->K, x, x, b->kxx) || !add_entry(t->K, y, y, b->kyy) || !add_entry(t->C, x, x, b->cxx) ||
            !add_entry(t->C, y, y, b->cyy))
            return 0;
    }
    return 1;
}

static td_status assemble_matrices(td_system *s, td_error *err)
{
    triplets t;
    int n = s->ndof, ok;
    /* a banded guess for the entry count; cs_di_entry grows the arrays when it is short */
    int guess = 64 * s->model->elements.count + 8 * (s->model->discs.count + s->model->bearings.count) + 1;
    t.M = cs_di_spalloc(n, n, guess, 1, 1);
    t.K = cs_di_spalloc(n, n, guess, 1, 1);
    t.C = cs_di_spalloc(n, n, guess, 1, 1);
    t.G = cs_di_spalloc(n, n, guess, 1, 1);
    ok = t.M && t.K && t.C && t.G && add_shaft(s->model, &t) && add_discs(s->model, &t) && add_bearings(s->model, &t);
    if (ok) {
        s->M = td_system_compress(t.M);
        s->K = td_system_compress(t.K);
        s->C = td_system_compress(t.C);
        s->G = td_system_compress(t.G);
        ok = s->M && s->K && s->C && s->G;
    }
    triplets_free(&t);
    return ok ? TD_OK : td_error_set(err, TD_ERR_NOMEM, "out of memory assembling the system matrices");
}

/* The AMB axis table: axis 2 i is x of AMB i, 2 i + 1 its y. Controller states: first the lag
 * states of the axes with tau > 0, in axis order, then the integrators of those with kint > 0 (a
 * PD model keeps the numbering it always had), then the linear controllers' (build_laws). */
static td_status build_amb_axes(td_system *s, td_error *err)
{
    const td_model *m = s->model;
    int i, k;
    s->n_amb_axes = 2 * m->ambs.count;
    s->n_controller_states = 0;
    if (s->n_amb_axes == 0)
        return TD_OK;
    s->amb_axes = calloc((size_t)s->n_amb_axes, sizeof *s->amb_axes);
    if (!s->amb_axes)
        return td_error_set(err, TD_ERR_NOMEM, "out of memory building the AMB axis table");
    for (i = 0; i < m->ambs.count; i++) {
        const td_amb *b = &m->ambs.items[i];
        for (k = 0; k < 2; k++) {
            td_amb_axis *a = &s->amb_axes[2 * i + k];
            int offset = k == 0 ? TD_DOF_X : TD_DOF_Y;
            a->amb = i;
            a->axis = k;
            /* both nodes are boundary nodes of a reduced rotor (reduce.c): physical in q */
            a->actuator_dof = td_system_node_dof(s, b->node, offset);
            a->sensor_dof = td_system_node_dof(s, b->sensor_node, offset);
            a->ks = b->ks;
            a->ki = b->ki;
            a->kp = b->kp;
            a->kd = b->kd;
            a->kint = b->kint;
            a->tau = b->tau;
            a->capacity = b->force_capacity;
            a->saturation = b->saturation;
            a->state = b->tau > 0.0 ? s->n_controller_states++ : -1;
            a->law = a->law_output = -1; /* the shorthand until a linear controller claims the axis */
            a->slew_rate = b->slew_rate;
        }
    }
    for (k = 0; k < s->n_amb_axes; k++) {
        td_amb_axis *a = &s->amb_axes[k];
        a->integral = a->kint > 0.0 ? s->n_controller_states++ : -1;
    }
    return TD_OK;
}

/* A plug-in controller's law: no matrices of its own (n = 0, D = 0: the analyses that need a
 * linear law refuse it, lib/modal), sampled, its commands the sampler's (lib/sim/sampler.c). */
static td_status build_plugin_law(td_system *s, int l, const td_plugin_spec *p, td_error *err)
{
    td_lti_law *L = &s->laws[l];
    L->nin = p->n_inputs;
    L->nout = p->n_outputs;
    L->sample_rate = p->sample_rate;
    L->plugin = p;
    L->A = calloc(1, sizeof(double));
    L->B = calloc(1, sizeof(double));
    L->C = calloc(1, sizeof(double));
    L->D = calloc((size_t)L->nout * (size_t)L->nin, sizeof(double));
    L->in_axis = malloc((size_t)L->nin * sizeof(int));
    L->out_axis = malloc((size_t)L->nout * sizeof(int));
    if (!L->A || !L->B || !L->C || !L->D || !L->in_axis || !L->out_axis)
        return td_error_set(err, TD_ERR_NOMEM, "out of memory building controller %d", l);
    memcpy(L->in_axis, p->inputs, (size_t)L->nin * sizeof(int));
    memcpy(L->out_axis, p->outputs, (size_t)L->nout * sizeof(int));
    return TD_OK;
}

/* A linear controller's law: its matrices, its axes, and for a continuous law its first state among
 * the controller states (after every shorthand state, so that a model without controllers keeps its
 * numbering). */
static td_status build_linear_law(td_system *s, int l, td_error *err)
{
    const int *in, *out;
    const td_controller *k = td_model_get_controller(s->model, l, NULL, &in, &out);
    td_lti_law *L = &s->laws[l];
    size_t n, nin, nout;
    L->n = td_controller_order(k);
    L->nin = td_controller_inputs(k);
    L->nout = td_controller_outputs(k);
    L->sample_rate = td_controller_sample_rate(k);
    n = (size_t)L->n;
    nin = (size_t)L->nin;
    nout = (size_t)L->nout;
    /* +1: a law without states still gets valid (unused) pointers */
    L->A = calloc(n * n + 1, sizeof(double));
    L->B = calloc(n * nin + 1, sizeof(double));
    L->C = calloc(nout * n + 1, sizeof(double));
    L->D = calloc(nout * nin, sizeof(double));
    L->D1 = td_controller_has_velocity_feedthrough(k) ? calloc(nout * nin, sizeof(double)) : NULL;
    L->in_axis = malloc(nin * sizeof(int));
    L->out_axis = malloc(nout * sizeof(int));
    if (!L->A || !L->B || !L->C || !L->D || !L->in_axis || !L->out_axis ||
        (td_controller_has_velocity_feedthrough(k) && !L->D1))
        return td_error_set(err, TD_ERR_NOMEM, "out of memory building controller %d", l);
    td_controller_matrices(k, L->A, L->B, L->C, L->D, L->D1);
    memcpy(L->in_axis, in, nin * sizeof(int));
    memcpy(L->out_axis, out, nout * sizeof(int));
    if (L->sample_rate == 0.0) {
        L->state = s->n_controller_states;
        s->n_controller_states += L->n;
    }
    return TD_OK;
}

/* One controller of the model as the system runs it, and the axes it drives (none while it stands
 * by). */
static td_status build_law(td_system *s, int l, td_error *err)
{
    const td_plugin_spec *p = td_model_get_plugin(s->model, l);
    td_lti_law *L = &s->laws[l];
    td_status st;
    int o;
    L->state = -1;
    L->standby = td_model_recovery_standby(s->model, l);
    st = p ? build_plugin_law(s, l, p, err) : build_linear_law(s, l, err);
    for (o = 0; st == TD_OK && o < L->nout && !L->standby; o++) {
        s->amb_axes[L->out_axis[o]].law = l;
        s->amb_axes[L->out_axis[o]].law_output = o;
    }
    return st;
}

static td_status build_laws(td_system *s, td_error *err)
{
    int l;
    s->n_laws = td_model_controller_count(s->model);
    if (s->n_laws == 0)
        return TD_OK;
    s->laws = calloc((size_t)s->n_laws, sizeof *s->laws);
    if (!s->laws)
        return td_error_set(err, TD_ERR_NOMEM, "out of memory building the controllers");
    for (l = 0; l < s->n_laws; l++) {
        td_status st = build_law(s, l, err);
        if (st != TD_OK)
            return st;
    }
    return TD_OK;
}

static void free_laws(td_system *s)
{
    int l;
    for (l = 0; l < s->n_laws; l++) {
        td_lti_law *L = &s->laws[l];
        free(L->A);
        free(L->B);
        free(L->C);
        free(L->D);
        free(L->D1);
        free(L->in_axis);
        free(L->out_axis);
    }
    free(s->laws);
}

void td_system_set_amb_off(td_system *s, int amb, int off)
{
    int k;
    for (k = 0; k < s->n_amb_axes; k++)
        if (s->amb_axes[k].amb == amb)
            s->amb_axes[k].off = off != 0;
}

/* gravity_load = M a with a the uniform acceleration (gx, gy) on every translational DOF. The
 * consistent M also gives the end moments of the distributed weight on the rotations. */
static td_status build_gravity_load(td_system *s, td_error *err)
{
    double *a;
    int i;
    s->gravity_load = calloc((size_t)s->nphys, sizeof *s->gravity_load);
    a = calloc((size_t)s->nphys, sizeof *a);
    if (!s->gravity_load || !a) {
        free(a);
        return td_error_set(err, TD_ERR_NOMEM, "out of memory building the gravity load");
    }
    for (i = 0; i < s->nnodes; i++) {
        a[TD_DOF(i, TD_DOF_X)] = s->model->gravity[0];
        a[TD_DOF(i, TD_DOF_Y)] = s->model->gravity[1];
    }
    cs_di_gaxpy(s->M, a, s->gravity_load);
    free(a);
    return TD_OK;
}

/* The housing motion's loads (docs/theory.md, "Base motion"): base_load = M R_x, M R_y, M T_x, M T_y
 * and base_gyro = G T_x, G T_y, with R a unit rigid translation (1 on every node's x, resp. y) and
 * T a unit rigid rotation about x or y through the reference point (td_rigid_unit_at). */
static td_status build_base_loads(td_system *s, td_error *err)
{
    double zref = td_model_housing_reference(s->model), *u = calloc((size_t)s->nphys, sizeof *u);
    int k, i;
    for (k = 0; k < 6 && u; k++) {
        double **out = k < 4 ? &s->base_load[k] : &s->base_gyro[k - 4];
        int j = k < 4 ? k : k - 2; /* the unit motion: translation x, y; rotation about x, y */
        if (!(*out = calloc((size_t)s->nphys, sizeof **out)))
            break;
        memset(u, 0, (size_t)s->nphys * sizeof *u);
        for (i = 0; i < s->nnodes; i++)
            td_rigid_unit_at(j, td_model_node_position(s->model, i) - zref, u + TD_DOF(i, 0));
        cs_di_gaxpy(k < 4 ? s->M : s->G, u, *out);
    }
    free(u);
    return k == 6 ? TD_OK : td_error_set(err, TD_ERR_NOMEM, "out of memory building the housing motion's loads");
}

td_status td_system_create(const td_model *model, td_system **out, td_error *err)
{
    td_system *s;
    td_status st;
    if (!model || !out)
        return td_error_set(err, TD_ERR_INVALID, "td_system_create: NULL argument");
    *out = NULL;
    st = td_model_validate(model, err);
    if (st != TD_OK)
        return st;
    s = calloc(1, sizeof *s);
    if (!s)
        return td_error_set(err, TD_ERR_NOMEM, "out of memory creating a system");
    st = td_model_clone(model, &s->model, err);
    if (st == TD_OK) {
        s->nnodes = td_model_node_count(s->model);
        s->nphys = s->ndof = TD_DOFS_PER_NODE * s->nnodes;
        st = assemble_matrices(s, err);
    }
    if (st == TD_OK)
        st = build_gravity_load(s, err);
    if (st == TD_OK && td_model_has_housing_motion(s->model))
        st = build_base_loads(s, err);
    if (st == TD_OK && s->model->reduction_cutoff > 0.0)
        st = td_system_reduce(s, err);
    if (st == TD_OK)
        st = td_system_add_housing_body(s, err);
    if (st == TD_OK)
        st = build_amb_axes(s, err);
    if (st == TD_OK)
        st = build_laws(s, err);
    if (st != TD_OK) {
        td_system_free(&s);
        return st;
    }
    *out = s;
    return TD_OK;
}

void td_system_free(td_system **sys)
{
    td_system *s;
    int k;
    if (!sys || !*sys)
        return;
    s = *sys;
    td_model_free(&s->model);
    cs_di_spfree(s->M);
    cs_di_spfree(s->K);
    cs_di_spfree(s->C);
    cs_di_spfree(s->G);
    free(s->amb_axes);
    free_laws(s);
    free(s->gravity_load);
    for (k = 0; k < 4; k++)
        free(s->base_load[k]);
    for (k = 0; k < 2; k++)
        free(s->base_gyro[k]);
    free(s->body_field);
    td_system_reduction_free(s);
    free(s);
    *sys = NULL;
}

int td_system_dof_count(const td_system *sys)
{
    return sys ? sys->ndof : 0;
}

const td_model *td_system_model(const td_system *sys)
{
    return sys ? sys->model : NULL;
}

static const cs_di *matrix_of(const td_system *sys, td_matrix_kind which)
{
    switch (which) {
    case TD_MATRIX_MASS: return sys->M;
    case TD_MATRIX_STIFFNESS: return sys->K;
    case TD_MATRIX_DAMPING: return sys->C;
    case TD_MATRIX_GYROSCOPIC: return sys->G;
    }
    return NULL;
}

td_status td_system_dense(const td_system *sys, td_matrix_kind which, double *out, td_error *err)
{
    const cs_di *A;
    int j, p, n;
    if (!sys || !out)
        return td_error_set(err, TD_ERR_INVALID, "td_system_dense: NULL argument");
    A = matrix_of(sys, which);
    if (!A)
        return td_error_set(err, TD_ERR_INVALID, "td_system_dense: unknown matrix kind %d", (int)which);
    n = sys->ndof;
    memset(out, 0, (size_t)n * (size_t)n * sizeof *out);
    for (j = 0; j < n; j++)
        for (p = A->p[j]; p < A->p[j + 1]; p++)
            out[A->i[p] + (size_t)j * (size_t)n] += A->x[p];
    return TD_OK;
}

int td_system_nnz(const td_system *sys, td_matrix_kind which)
{
    const cs_di *A;
    if (!sys)
        return 0;
    A = matrix_of(sys, which);
    return A ? A->p[A->n] : 0;
}
