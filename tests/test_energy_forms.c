/* The energy account's quadratic forms (lib/sim/energy.c td_sim_quadratic_forms: one sweep, M and K
 * without the stored zeros, td_sim_operators_compress_mk) against three separate plain row-by-row
 * passes over the whole union pattern, bit for bit, on random sparse patterns with stored zeros
 * (also where M and K both are zero, also negative zeros, also a q or v of zero) and values spread
 * over many decades, so that any other order of the sums would show in the last bits (the test
 * checks that the data are that sensitive). */
#include "td_test.h"

#include "sim/sim_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define NMAX 60

typedef struct pattern {
    int n, rowptr[NMAX + 1], col[NMAX * NMAX];
    double M[NMAX * NMAX], K[NMAX * NMAX], D[NMAX * NMAX], q[NMAX], v[NMAX];
} pattern;

/* A linear congruential generator in [0, 1), its state passed along (no global). */
static double uniform(unsigned long *seed)
{
    *seed = (*seed * 6364136223846793005UL + 1442695040888963407UL) & 0xffffffffffffffffUL;
    return (double)((*seed >> 11) & 0x1fffffffffffffUL) / 9007199254740992.0;
}

/* A value of random sign over twelve decades, or an exact zero one time in three (a stored zero,
 * of either sign). */
static double spread_value(unsigned long *seed)
{
    double u = uniform(seed), mag = pow(10.0, 12.0 * uniform(seed) - 6.0);
    if (u < 0.33)
        return u < 0.165 ? 0.0 : -0.0;
    return u < 0.665 ? mag : -mag;
}

static void make_pattern(pattern *p, int n, unsigned long *seed)
{
    int i, j, nnz = 0;
    p->n = n;
    for (i = 0; i < n; i++) {
        p->rowptr[i] = nnz;
        for (j = 0; j < n; j++)
            if (j == i || uniform(seed) < 0.3) {
                p->col[nnz] = j;
                p->M[nnz] = spread_value(seed);
                p->K[nnz] = spread_value(seed);
                p->D[nnz] = spread_value(seed);
                nnz++;
            }
        p->q[i] = spread_value(seed);
        p->v[i] = spread_value(seed);
    }
    p->rowptr[n] = nnz;
}

/* x^T A y row by row, each row's sum first: the plain pass the fused one must reproduce. */
static double plain(const pattern *p, const double *a, const double *x, const double *y)
{
    double sum = 0.0;
    int i, k;
    for (i = 0; i < p->n; i++) {
        double row = 0.0;
        for (k = p->rowptr[i]; k < p->rowptr[i + 1]; k++)
            row += a[k] * y[p->col[k]];
        sum += x[i] * row;
    }
    return sum;
}

/* x^T A y as one flat sum of the products: another order, to show the data tell orders apart. */
static double flat(const pattern *p, const double *a, const double *x, const double *y)
{
    double sum = 0.0;
    int i, k;
    for (i = 0; i < p->n; i++)
        for (k = p->rowptr[i]; k < p->rowptr[i + 1]; k++)
            sum += x[i] * a[k] * y[p->col[k]];
    return sum;
}

static void test_fused_equals_separate(void **state)
{
    static pattern p; /* large: off the stack */
    unsigned long seed = 20261128UL;
    int trial, sensitive = 0, skipped = 0;
    (void)state;
    for (trial = 0; trial < 40; trial++) {
        double out[3], want[3];
        td_sim_operators ops;
        memset(&ops, 0, sizeof ops);
        make_pattern(&p, 1 + (7 * trial) % NMAX, &seed);
        ops.st_nnz = p.rowptr[p.n];
        ops.st_rowptr = p.rowptr;
        ops.st_col = p.col;
        ops.st_M = p.M;
        ops.st_K = p.K;
        ops.st_D = p.D;
        assert_int_equal(td_sim_operators_compress_mk(&ops, p.n), 1);
        skipped += ops.st_nnz - ops.mk_rowptr[p.n];
        td_sim_quadratic_forms(&ops, p.n, p.q, p.v, out);
        free(ops.mk_rowptr);
        free(ops.mk_col);
        free(ops.mk_M);
        free(ops.mk_K);
        want[0] = plain(&p, p.M, p.v, p.v);
        want[1] = plain(&p, p.K, p.q, p.q);
        want[2] = plain(&p, p.D, p.v, p.v);
        assert_memory_equal(out, want, sizeof out);
        if (memcmp(&want[0], &(double){flat(&p, p.M, p.v, p.v)}, sizeof(double)) ||
            memcmp(&want[1], &(double){flat(&p, p.K, p.q, p.q)}, sizeof(double)))
            sensitive++;
    }
    assert_true(sensitive >= 10); /* most trials' bits depend on the order of the sums */
    assert_true(skipped >= 100);  /* and the compressed M and K leave entries out */
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fused_equals_separate),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
