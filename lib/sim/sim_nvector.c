/*
 * Compiled replacements for the operations of SUNDIALS's serial N_Vector.
 *
 * Why: the Debian 12 build of SUNDIALS 6.4.1 is compiled without optimisation (its object code
 * keeps every loop variable on the stack), and with ~100 unknowns IDA's time goes into vector
 * operations: a profile of case A (callgrind) put 60 % of all instructions in N_VLinearSum,
 * N_VLinearCombination, N_VWrmsNormMask and friends, at 20-40 instructions per element. The
 * vectors stay serial N_Vectors (same content, same ID, so KLU, the dense solver and the sparse
 * matrix accept them); only the function pointers of their operations table are replaced by the
 * loops below, compiled with the library. Clones copy the table, so every vector IDA, the
 * Newton solver and the linear solver make from the template inherits them.
 *
 * Each function computes what the SUNDIALS documentation specifies for the operation (the same
 * formulas as nvector_serial.c, element by element, with the same handling of aliased
 * arguments: every loop reads element i of its inputs before it writes element i of its output).
 * The fused and vector-array operations are provided too: unset, SUNDIALS falls back to loops of
 * the single operations, one call (and one pass over memory) per vector.
 *
 * The hot loops take two elements per iteration, each iteration loading before it stores, so that
 * the compiler's straight-line (SLP) vectoriser, on at -O2, turns them into packed SSE2 arithmetic
 * without alias checks; sums keep two partial sums (a different rounding order from the serial
 * vector's, at the level of one ulp per element).
 */
#include "sim/sim_internal.h"

#include <float.h>
#include <math.h>

#define LEN(v) ((int)NV_LENGTH_S(v))
#define DAT(v) NV_DATA_S(v)

/* z = a x + b y on raw arrays (z may be x or y). */
static void axpby(int n, sunrealtype a, const sunrealtype *xd, sunrealtype b, const sunrealtype *yd, sunrealtype *zd)
{
    int i;
    for (i = 0; i + 1 < n; i += 2) {
        sunrealtype x0 = xd[i], x1 = xd[i + 1], y0 = yd[i], y1 = yd[i + 1];
        zd[i] = a * x0 + b * y0;
        zd[i + 1] = a * x1 + b * y1;
    }
    if (i < n)
        zd[i] = a * xd[i] + b * yd[i];
}

static void lin_sum(sunrealtype a, N_Vector x, sunrealtype b, N_Vector y, N_Vector z)
{
    axpby(LEN(x), a, DAT(x), b, DAT(y), DAT(z));
}

static void set_const(sunrealtype c, N_Vector z)
{
    sunrealtype *zd = DAT(z);
    int i, n = LEN(z);
    for (i = 0; i < n; i++)
        zd[i] = c;
}

static void prod(N_Vector x, N_Vector y, N_Vector z)
{
    const sunrealtype *xd = DAT(x), *yd = DAT(y);
    sunrealtype *zd = DAT(z);
    int i, n = LEN(x);
    for (i = 0; i < n; i++)
        zd[i] = xd[i] * yd[i];
}

static void divide(N_Vector x, N_Vector y, N_Vector z)
{
    const sunrealtype *xd = DAT(x), *yd = DAT(y);
    sunrealtype *zd = DAT(z);
    int i, n = LEN(x);
    for (i = 0; i < n; i++)
        zd[i] = xd[i] / yd[i];
}

static void scale(sunrealtype c, N_Vector x, N_Vector z)
{
    const sunrealtype *xd = DAT(x);
    sunrealtype *zd = DAT(z);
    int i, n = LEN(x);
    for (i = 0; i + 1 < n; i += 2) {
        sunrealtype x0 = xd[i], x1 = xd[i + 1];
        zd[i] = c * x0;
        zd[i + 1] = c * x1;
    }
    if (i < n)
        zd[i] = c * xd[i];
}

static void vabs(N_Vector x, N_Vector z)
{
    const sunrealtype *xd = DAT(x);
    sunrealtype *zd = DAT(z);
    int i, n = LEN(x);
    for (i = 0; i < n; i++)
        zd[i] = fabs(xd[i]);
}

static void inv(N_Vector x, N_Vector z)
{
    const sunrealtype *xd = DAT(x);
    sunrealtype *zd = DAT(z);
    int i, n = LEN(x);
    /* IDA's error weights every step (IDAEwtSet): two per iteration, a packed division */
    for (i = 0; i + 1 < n; i += 2) {
        sunrealtype x0 = xd[i], x1 = xd[i + 1];
        zd[i] = 1.0 / x0;
        zd[i + 1] = 1.0 / x1;
    }
    if (i < n)
        zd[i] = 1.0 / xd[i];
}

static void add_const(N_Vector x, sunrealtype b, N_Vector z)
{
    const sunrealtype *xd = DAT(x);
    sunrealtype *zd = DAT(z);
    int i, n = LEN(x);
    for (i = 0; i < n; i++)
        zd[i] = xd[i] + b;
}

static sunrealtype dot(N_Vector x, N_Vector y)
{
    const sunrealtype *xd = DAT(x), *yd = DAT(y);
    sunrealtype s = 0.0;
    int i, n = LEN(x);
    for (i = 0; i < n; i++)
        s += xd[i] * yd[i];
    return s;
}

static sunrealtype max_norm(N_Vector x)
{
    const sunrealtype *xd = DAT(x);
    sunrealtype m = 0.0;
    int i, n = LEN(x);
    for (i = 0; i < n; i++)
        if (fabs(xd[i]) > m)
            m = fabs(xd[i]);
    return m;
}

static sunrealtype wsqr_sum(N_Vector x, N_Vector w)
{
    const sunrealtype *xd = DAT(x), *wd = DAT(w);
    sunrealtype s0 = 0.0, s1 = 0.0;
    int i, n = LEN(x);
    for (i = 0; i + 1 < n; i += 2) {
        sunrealtype p0 = xd[i] * wd[i], p1 = xd[i + 1] * wd[i + 1];
        s0 += p0 * p0;
        s1 += p1 * p1;
    }
    if (i < n)
        s0 += (xd[i] * wd[i]) * (xd[i] * wd[i]);
    return s0 + s1;
}

static sunrealtype wsqr_sum_mask(N_Vector x, N_Vector w, N_Vector id)
{
    const sunrealtype *xd = DAT(x), *wd = DAT(w), *idd = DAT(id);
    sunrealtype s0 = 0.0, s1 = 0.0;
    int i, n = LEN(x);
    for (i = 0; i + 1 < n; i += 2) {
        sunrealtype p0 = idd[i] > 0.0 ? xd[i] * wd[i] : 0.0, p1 = idd[i + 1] > 0.0 ? xd[i + 1] * wd[i + 1] : 0.0;
        s0 += p0 * p0;
        s1 += p1 * p1;
    }
    if (i < n && idd[i] > 0.0)
        s0 += (xd[i] * wd[i]) * (xd[i] * wd[i]);
    return s0 + s1;
}

static sunrealtype wrms_norm(N_Vector x, N_Vector w)
{
    return sqrt(wsqr_sum(x, w) / LEN(x));
}

static sunrealtype wrms_norm_mask(N_Vector x, N_Vector w, N_Vector id)
{
    return sqrt(wsqr_sum_mask(x, w, id) / LEN(x));
}

static sunrealtype vmin(N_Vector x)
{
    const sunrealtype *xd = DAT(x);
    sunrealtype m = xd[0];
    int i, n = LEN(x);
    for (i = 1; i < n; i++)
        if (xd[i] < m)
            m = xd[i];
    return m;
}

static sunrealtype wl2_norm(N_Vector x, N_Vector w)
{
    return sqrt(wsqr_sum(x, w));
}

static sunrealtype l1_norm(N_Vector x)
{
    const sunrealtype *xd = DAT(x);
    sunrealtype s = 0.0;
    int i, n = LEN(x);
    for (i = 0; i < n; i++)
        s += fabs(xd[i]);
    return s;
}

static void compare(sunrealtype c, N_Vector x, N_Vector z)
{
    const sunrealtype *xd = DAT(x);
    sunrealtype *zd = DAT(z);
    int i, n = LEN(x);
    for (i = 0; i < n; i++)
        zd[i] = fabs(xd[i]) >= c ? 1.0 : 0.0;
}

static sunbooleantype inv_test(N_Vector x, N_Vector z)
{
    const sunrealtype *xd = DAT(x);
    sunrealtype *zd = DAT(z);
    sunbooleantype ok = SUNTRUE;
    int i, n = LEN(x);
    for (i = 0; i < n; i++) {
        if (xd[i] == 0.0)
            ok = SUNFALSE;
        else
            zd[i] = 1.0 / xd[i];
    }
    return ok;
}

/* c_i = +-2: x_i of that sign (>= 0 for |c_i| = 1, > 0 for 2); m_i = 1 where violated. */
static sunbooleantype constr_mask(N_Vector c, N_Vector x, N_Vector m)
{
    const sunrealtype *cd = DAT(c), *xd = DAT(x);
    sunrealtype *md = DAT(m);
    sunbooleantype ok = SUNTRUE;
    int i, n = LEN(x);
    for (i = 0; i < n; i++) {
        int bad = 0;
        md[i] = 0.0;
        if (cd[i] == 0.0)
            continue;
        if (fabs(cd[i]) > 1.5)
            bad = xd[i] * cd[i] <= 0.0;
        else if (fabs(cd[i]) > 0.5)
            bad = xd[i] * cd[i] < 0.0;
        if (bad) {
            ok = SUNFALSE;
            md[i] = 1.0;
        }
    }
    return ok;
}

/* min over denom_i != 0 of num_i / denom_i; DBL_MAX (SUNDIALS's BIG_REAL) if there is none. */
static sunrealtype min_quotient(N_Vector num, N_Vector denom)
{
    const sunrealtype *nd = DAT(num), *dd = DAT(denom);
    sunrealtype m = DBL_MAX;
    int i, n = LEN(num), found = 0;
    for (i = 0; i < n; i++) {
        if (dd[i] == 0.0)
            continue;
        if (!found || nd[i] / dd[i] < m)
            m = nd[i] / dd[i];
        found = 1;
    }
    return m;
}

/* ---- fused and vector-array operations ----------------------------------------------------- */

static int lin_comb(int nv, sunrealtype *c, N_Vector *X, N_Vector z)
{
    sunrealtype *zd = DAT(z);
    int j, n = LEN(z);
    if (nv == 1) {
        scale(c[0], X[0], z);
        return 0;
    }
    if (nv == 2) {
        lin_sum(c[0], X[0], c[1], X[1], z);
        return 0;
    }
    axpby(n, c[0], DAT(X[0]), c[1], DAT(X[1]), zd);
    for (j = 2; j < nv; j++)
        axpby(n, 1.0, zd, c[j], DAT(X[j]), zd);
    return 0;
}

static int scale_add_multi(int nv, sunrealtype *a, N_Vector x, N_Vector *Y, N_Vector *Z)
{
    const sunrealtype *xd = DAT(x);
    int j, n = LEN(x);
    for (j = 0; j < nv; j++)
        axpby(n, a[j], xd, 1.0, DAT(Y[j]), DAT(Z[j]));
    return 0;
}

static int dot_multi(int nv, N_Vector x, N_Vector *Y, sunrealtype *d)
{
    int j;
    for (j = 0; j < nv; j++)
        d[j] = dot(x, Y[j]);
    return 0;
}

static int lin_sum_array(int nv, sunrealtype a, N_Vector *X, sunrealtype b, N_Vector *Y, N_Vector *Z)
{
    int j;
    for (j = 0; j < nv; j++)
        lin_sum(a, X[j], b, Y[j], Z[j]);
    return 0;
}

static int scale_array(int nv, sunrealtype *c, N_Vector *X, N_Vector *Z)
{
    int j;
    for (j = 0; j < nv; j++)
        scale(c[j], X[j], Z[j]);
    return 0;
}

static int const_array(int nv, sunrealtype c, N_Vector *Z)
{
    int j;
    for (j = 0; j < nv; j++)
        set_const(c, Z[j]);
    return 0;
}

static int wrms_array(int nv, N_Vector *X, N_Vector *W, sunrealtype *nrm)
{
    int j;
    for (j = 0; j < nv; j++)
        nrm[j] = wrms_norm(X[j], W[j]);
    return 0;
}

static int wrms_mask_array(int nv, N_Vector *X, N_Vector *W, N_Vector id, sunrealtype *nrm)
{
    int j;
    for (j = 0; j < nv; j++)
        nrm[j] = wrms_norm_mask(X[j], W[j], id);
    return 0;
}

/* Z[j][i] = a[j] X[i] + Y[j][i], i < nv vectors, j < ns sums. */
static int scale_add_multi_array(int nv, int ns, sunrealtype *a, N_Vector *X, N_Vector **Y, N_Vector **Z)
{
    int i, j;
    for (i = 0; i < nv; i++)
        for (j = 0; j < ns; j++)
            lin_sum(a[j], X[i], 1.0, Y[j][i], Z[j][i]);
    return 0;
}

/* Z[i] = sum_j c[j] X[j][i], i < nv vectors. */
static int lin_comb_array(int nv, int ns, sunrealtype *c, N_Vector **X, N_Vector *Z)
{
    int i, j;
    N_Vector cols[64];
    if (ns > 64)
        return -1;
    for (i = 0; i < nv; i++) {
        for (j = 0; j < ns; j++)
            cols[j] = X[j][i];
        lin_comb(ns, c, cols, Z[i]);
    }
    return 0;
}

static sunrealtype min_local(N_Vector x)
{
    return vmin(x);
}

void td_sim_nvector_optimize(N_Vector v)
{
    struct _generic_N_Vector_Ops *o = v->ops;
    o->nvlinearsum = lin_sum;
    o->nvconst = set_const;
    o->nvprod = prod;
    o->nvdiv = divide;
    o->nvscale = scale;
    o->nvabs = vabs;
    o->nvinv = inv;
    o->nvaddconst = add_const;
    o->nvdotprod = dot;
    o->nvmaxnorm = max_norm;
    o->nvwrmsnorm = wrms_norm;
    o->nvwrmsnormmask = wrms_norm_mask;
    o->nvmin = vmin;
    o->nvwl2norm = wl2_norm;
    o->nvl1norm = l1_norm;
    o->nvcompare = compare;
    o->nvinvtest = inv_test;
    o->nvconstrmask = constr_mask;
    o->nvminquotient = min_quotient;
    o->nvlinearcombination = lin_comb;
    o->nvscaleaddmulti = scale_add_multi;
    o->nvdotprodmulti = dot_multi;
    o->nvlinearsumvectorarray = lin_sum_array;
    o->nvscalevectorarray = scale_array;
    o->nvconstvectorarray = const_array;
    o->nvwrmsnormvectorarray = wrms_array;
    o->nvwrmsnormmaskvectorarray = wrms_mask_array;
    o->nvscaleaddmultivectorarray = scale_add_multi_array;
    o->nvlinearcombinationvectorarray = lin_comb_array;
    o->nvdotprodlocal = dot;
    o->nvmaxnormlocal = max_norm;
    o->nvminlocal = min_local;
    o->nvl1normlocal = l1_norm;
    o->nvinvtestlocal = inv_test;
    o->nvconstrmasklocal = constr_mask;
    o->nvminquotientlocal = min_quotient;
    o->nvwsqrsumlocal = wsqr_sum;
    o->nvwsqrsummasklocal = wsqr_sum_mask;
}
