#include "td_jacobian.h"
#include "td_test.h"

#include "sim/sim_internal.h"

#include <math.h>
#include <stdlib.h>

/* fd (n x n, column-major) of central differences, rowmax the largest |entry| of each row. */
static void differences(td_sim *s, double t, double cj, double *y, double *yp, double rel_step, double *fd,
                        double *rowmax)
{
    int n = s->dae.neq, i, j;
    double *rp = calloc((size_t)n, sizeof(double)), *rm = calloc((size_t)n, sizeof(double));
    assert_true(rp && rm);
    for (j = 0; j < n; j++) {
        double h = rel_step * (fabs(y[j]) > 0.0 ? fabs(y[j]) : 1e-6), yj = y[j], ypj = yp[j];
        y[j] = yj + h;
        yp[j] = ypj + cj * h;
        td_sim_residual(s, t, y, yp, rp);
        y[j] = yj - h;
        yp[j] = ypj - cj * h;
        td_sim_residual(s, t, y, yp, rm);
        y[j] = yj;
        yp[j] = ypj;
        for (i = 0; i < n; i++) {
            fd[i + (size_t)j * n] = (rp[i] - rm[i]) / (2 * h);
            rowmax[i] = fmax(rowmax[i], fabs(fd[i + (size_t)j * n]));
        }
    }
    free(rp), free(rm);
}

void td_test_check_jacobian(td_sim *s, double *y, double *yp, double rel_step, const char *what)
{
    int n = s->dae.neq, i, j;
    double *fd = calloc((size_t)n * (size_t)n, sizeof(double)), *rowmax = calloc((size_t)n, sizeof(double));
    double cj = 2.5e5, t = 0.0123;
    assert_true(fd && rowmax);
    differences(s, t, cj, y, yp, rel_step, fd, rowmax);
    td_sim_jacobian(s, t, cj, y);
    for (j = 0; j < n; j++)
        for (i = 0; i < n; i++) {
            int p = td_sim_pattern_find(s, i, j);
            double an = p >= 0 ? s->ops.jdata[p] : 0.0, f = fd[i + (size_t)j * n];
            if (!(fabs(an - f) <= 1e-6 * rowmax[i] + 1e-9))
                fail_msg("%s: J(%d,%d) analytic %.10g, differences %.10g (row max %.3g, in pattern %d)", what, i, j, an,
                         f, rowmax[i], p >= 0);
        }
    free(fd), free(rowmax);
}
