/*
 * transfer.c - transfer functions and zeros-poles-gain as realisations: polynomial division for a
 * law improper by one (D1 s + D + strictly proper rest), the rest in controllable canonical form
 * (the form of scipy.signal.tf2ss).
 */
#include "control/control_internal.h"

#include "util/error_internal.h"

#include <math.h>
#include <stdlib.h>

static td_status check_coefficients(const double *v, int len, const char *who, const char *name, td_error *err)
{
    if (!v || len < 1)
        return td_ctl_invalid(err, who, name, "needs at least one coefficient");
    if (!td_ctl_all_finite(v, len))
        return td_ctl_invalid(err, who, name, "a coefficient is not finite");
    return TD_OK;
}

/* Divides r (descending, length n + 2, degree <= n + 1) by the monic a (length n + 1) down to
 * degree < n: q1, q0 are the quotient's s and constant coefficients; the rest is left in r[2..]. */
static void divide(double *r, const double *a, int n, double *q1, double *q0)
{
    int i;
    *q1 = r[0];
    for (i = 0; i <= n; i++)
        r[i] -= *q1 * a[i];
    *q0 = r[1];
    for (i = 0; i <= n; i++)
        r[i + 1] -= *q0 * a[i];
}

td_controller *td_ctl_from_polynomials(const double *num, int num_len, const double *den, int den_len,
                                       double sample_rate, const char *who, td_error *err)
{
    td_controller *k = NULL;
    double *a, *r, q1, q0;
    int n = den_len - 1, lead = 0, deg, i;
    if (check_coefficients(num, num_len, who, "num", err) != TD_OK ||
        check_coefficients(den, den_len, who, "den", err) != TD_OK)
        return NULL;
    if (den[0] == 0.0) {
        td_ctl_invalid(err, who, "den", "the leading coefficient den[0] must be nonzero");
        return NULL;
    }
    while (lead < num_len - 1 && num[lead] == 0.0)
        lead++;
    deg = num_len - 1 - lead;
    if (deg > n + (sample_rate > 0.0 ? 0 : 1)) {
        if (sample_rate > 0.0)
            td_ctl_invalid(err, who, "num", "improper sampled law (%d more zeros than poles)", deg - n);
        else
            td_ctl_invalid(err, who, "num", "improper by %d (at most one more zero than poles: a PD without filter)",
                           deg - n);
        return NULL;
    }
    a = calloc(2 * (size_t)n + 3, sizeof *a);
    if (!a) {
        td_error_set(err, TD_ERR_NOMEM, "out of memory creating a controller");
        return NULL;
    }
    r = a + n + 1;
    for (i = 0; i <= n; i++)
        a[i] = den[i] / den[0];
    for (i = 0; i <= deg; i++)
        r[n + 1 - deg + i] = num[lead + i] / den[0];
    divide(r, a, n, &q1, &q0);
    k = td_ctl_alloc(n, 1, 1, sample_rate, err);
    if (k) {
        for (i = 0; i < n; i++) {
            k->A[0 + i * n] = -a[i + 1];
            if (i > 0)
                k->A[i + (i - 1) * n] = 1.0;
            k->C[i] = r[i + 2];
        }
        if (n > 0)
            k->B[0] = 1.0;
        k->D[0] = q0;
        k->D1[0] = q1;
    }
    free(a);
    return td_ctl_finite(k, who, err);
}

/* Trailing zeros of a z^-1 polynomial (powers beyond its last term) carry nothing. */
static int trimmed_length(const double *v, int len)
{
    while (len > 1 && v[len - 1] == 0.0)
        len--;
    return len;
}

/* num/den in ascending powers of z^-1 times z^N (N the larger degree) is the same ratio in
 * descending powers of z, each padded with zeros to N + 1 terms. */
static td_controller *sampled_tf(const double *num, int num_len, const double *den, int den_len, double sample_rate,
                                 td_error *err)
{
    td_controller *k;
    double *p;
    int nl, dl, len, i;
    if (check_coefficients(num, num_len, "tf", "num", err) != TD_OK ||
        check_coefficients(den, den_len, "tf", "den", err) != TD_OK)
        return NULL;
    nl = trimmed_length(num, num_len);
    dl = trimmed_length(den, den_len);
    len = nl > dl ? nl : dl;
    p = calloc(2 * (size_t)len, sizeof *p);
    if (!p) {
        td_error_set(err, TD_ERR_NOMEM, "out of memory creating a controller");
        return NULL;
    }
    for (i = 0; i < nl; i++)
        p[i] = num[i];
    for (i = 0; i < dl; i++)
        p[len + i] = den[i];
    k = td_ctl_from_polynomials(p, len, p + len, len, sample_rate, "tf", err);
    free(p);
    return k;
}

td_controller *td_controller_create_tf(const double *num, int num_len, const double *den, int den_len,
                                       double sample_rate, td_error *err)
{
    if (!(isfinite(sample_rate) && sample_rate >= 0.0)) {
        td_ctl_invalid(err, "tf", "sample_rate", "must be finite and >= 0 (got %g)", sample_rate);
        return NULL;
    }
    if (sample_rate > 0.0)
        return sampled_tf(num, num_len, den, den_len, sample_rate, err);
    return td_ctl_from_polynomials(num, num_len, den, den_len, 0.0, "tf", err);
}

/* The monic real polynomial (descending) with the given roots, a root with im != 0 standing for
 * its conjugate pair too; p has room for 2 count + 1 terms; returns the degree. */
static int expand_roots(const double *re, const double *im, int count, double *p)
{
    int deg = 0, i, j;
    p[0] = 1.0;
    for (i = 0; i < count; i++) {
        if (im[i] == 0.0) { /* times (s - re) */
            p[deg + 1] = 0.0;
            for (j = deg + 1; j >= 1; j--)
                p[j] -= re[i] * p[j - 1];
            deg += 1;
        } else { /* times (s^2 - 2 re s + re^2 + im^2) */
            double b = -2.0 * re[i], c = re[i] * re[i] + im[i] * im[i];
            p[deg + 1] = 0.0;
            p[deg + 2] = 0.0;
            for (j = deg + 2; j >= 1; j--)
                p[j] += b * p[j - 1] + (j >= 2 ? c * p[j - 2] : 0.0);
            deg += 2;
        }
    }
    return deg;
}

static td_status check_roots(const double *re, const double *im, int count, const char *name, td_error *err)
{
    if (count < 0 || (count > 0 && (!re || !im)))
        return td_ctl_invalid(err, "zpk", name, "bad count or NULL array");
    if (!td_ctl_all_finite(re, count) || !td_ctl_all_finite(im, count))
        return td_ctl_invalid(err, "zpk", name, "a root is not finite");
    return TD_OK;
}

td_controller *td_controller_create_zpk(const double *zero_re, const double *zero_im, int n_zeros,
                                        const double *pole_re, const double *pole_im, int n_poles, double gain,
                                        double sample_rate, td_error *err)
{
    td_controller *k;
    double *pz, *pp;
    int dz, dp, i;
    if (check_roots(zero_re, zero_im, n_zeros, "zeros", err) != TD_OK ||
        check_roots(pole_re, pole_im, n_poles, "poles", err) != TD_OK)
        return NULL;
    if (!isfinite(gain)) {
        td_ctl_invalid(err, "zpk", "gain", "must be finite (got %g)", gain);
        return NULL;
    }
    if (!(isfinite(sample_rate) && sample_rate >= 0.0)) {
        td_ctl_invalid(err, "zpk", "sample_rate", "must be finite and >= 0 (got %g)", sample_rate);
        return NULL;
    }
    pz = calloc(2 * ((size_t)n_zeros + (size_t)n_poles) + 2, sizeof *pz);
    if (!pz) {
        td_error_set(err, TD_ERR_NOMEM, "out of memory creating a controller");
        return NULL;
    }
    pp = pz + 2 * (size_t)n_zeros + 1;
    dz = expand_roots(zero_re, zero_im, n_zeros, pz);
    dp = expand_roots(pole_re, pole_im, n_poles, pp);
    for (i = 0; i <= dz; i++)
        pz[i] *= gain;
    k = td_ctl_from_polynomials(pz, dz + 1, pp, dp + 1, sample_rate, "zpk", err);
    free(pz);
    return k;
}
