/* The energy account's fused quadratic forms (lib/sim/energy.c td_sim_quadratic_forms) against three
 * separate plain row-by-row passes, bit for bit, on random sparse patterns with stored zeros and
 * values spread over many decades, so that any other order of the sums would show in the last bits
 * (the test checks that the data are that sensitive). */
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

/* A value of random sign over twelve decades, or an exact zero one time in four (a stored zero). */
static double spread_value(unsigned long *seed)
{
    double u = uniform(seed), mag = pow(10.0, 12.0 * uniform(seed) - 6.0);
    if (u < 0.25)
        return 0.0;
    return u < 0.625 ? mag : -mag;
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
    int trial, sensitive = 0;
    (void)state;
    for (trial = 0; trial < 40; trial++) {
        double out[3], want[3];
        make_pattern(&p, 1 + (7 * trial) % NMAX, &seed);
        td_sim_quadratic_forms(p.n, p.rowptr, p.col, p.M, p.K, p.D, p.q, p.v, out);
        want[0] = plain(&p, p.M, p.v, p.v);
        want[1] = plain(&p, p.K, p.q, p.q);
        want[2] = plain(&p, p.D, p.v, p.v);
        assert_memory_equal(out, want, sizeof out);
        if (memcmp(&want[0], &(double){flat(&p, p.M, p.v, p.v)}, sizeof(double)) ||
            memcmp(&want[1], &(double){flat(&p, p.K, p.q, p.q)}, sizeof(double)))
            sensitive++;
    }
    assert_true(sensitive >= 10); /* most trials' bits depend on the order of the sums */
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fused_equals_separate),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
