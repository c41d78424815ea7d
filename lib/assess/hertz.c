/*
 * Hertz point contact (touchdown/assess.h), for the contact stress of a touchdown ball bearing.
 *
 * Johnson, Contact Mechanics (1985), sec. 4.2: two bodies with relative curvatures A < B
 * (A = 1/(2 r_large), B = 1/(2 r_small)) pressed by P meet on an ellipse of semi-axes a > b
 * (a along the direction of A), eccentricity e^2 = 1 - b^2/a^2, with
 *   B / A = (E(e) / (1 - e^2) - K(e)) / (K(e) - E(e)),
 * K and E the complete elliptic integrals of modulus e, and (the pressure p0 sqrt(1 - x^2/a^2 - y^2/b^2)
 * carrying P = 2/3 pi a b p0)
 *   a^3 = 3 P (K - E) / (2 pi E* A e^2),   b = a sqrt(1 - e^2),   p0 = 3 P / (2 pi a b).
 * B/A grows from 1 (e = 0, a circle: a^3 = 3 P R / (4 E*), R = 1/(2A)) without bound as e -> 1, so
 * e follows by bisection on log(b/a). The approximations often used instead (Hamrock & Brewe,
 * J. Lubr. Technol. 105, 1983) are within a few per cent of this; the tests compare both with an
 * independent solution by scipy's elliptic integrals.
 */
#include "touchdown/assess.h"
#include "touchdown/dofs.h"

#include <gsl/gsl_mode.h>
#include <gsl/gsl_sf_ellint.h>
#include <math.h>
#include <stddef.h>

/* b/a below this (B/A about 3e8) is no bearing contact: refused rather than solved */
#define HERTZ_MIN_AXIS_RATIO 1e-7
#define HERTZ_BISECTIONS 200
/* B/A within this of 1: the circle (the ellipse's formula loses its digits to K - E there) */
#define HERTZ_CIRCLE 1e-9

/* (K - E) / e^2 and B/A at the axis ratio s = b/a (e^2 = 1 - s^2). */
static double ratio_at(double s, double *k_minus_e_over_m)
{
    double m = 1.0 - s * s, k = sqrt(m);
    double K = gsl_sf_ellint_Kcomp(k, GSL_PREC_DOUBLE), E = gsl_sf_ellint_Ecomp(k, GSL_PREC_DOUBLE);
    *k_minus_e_over_m = (K - E) / m;
    return (E / (s * s) - K) / (K - E);
}

/* The axis ratio s = b/a whose B/A is rho (> 1), by bisection on log s; 0 beyond the range. */
static double axis_ratio(double rho, double *k_minus_e_over_m)
{
    double lo = log(HERTZ_MIN_AXIS_RATIO), hi = 0.0, mid;
    int i;
    if (ratio_at(HERTZ_MIN_AXIS_RATIO, k_minus_e_over_m) < rho)
        return 0.0;
    for (i = 0; i < HERTZ_BISECTIONS && hi - lo > 1e-15; i++) {
        mid = 0.5 * (lo + hi);
        if (ratio_at(exp(mid), k_minus_e_over_m) > rho) /* too eccentric: s up */
            lo = mid;
        else
            hi = mid;
    }
    mid = exp(0.5 * (lo + hi));
    ratio_at(mid, k_minus_e_over_m);
    return mid;
}

td_status td_hertz_point(double load, double rx, double ry, double modulus, td_hertz_contact *out)
{
    double A, B, s, kme;
    if (!out)
        return TD_ERR_INVALID;
    out->a = out->b = out->p_max = TD_UNDEFINED;
    if (!(isfinite(load) && load >= 0.0 && isfinite(rx) && rx > 0.0 && isfinite(ry) && ry > 0.0 && isfinite(modulus) &&
          modulus > 0.0))
        return TD_ERR_INVALID;
    A = 0.5 / fmax(rx, ry);
    B = 0.5 / fmin(rx, ry);
    if (load == 0.0) {
        out->a = out->b = out->p_max = 0.0;
        return TD_OK;
    }
    if (B / A - 1.0 <= HERTZ_CIRCLE) {
        out->a = out->b = cbrt(3.0 * load / (8.0 * modulus * A)); /* R = 1/(2A) */
    } else {
        s = axis_ratio(B / A, &kme);
        if (!(s > 0.0))
            return TD_ERR_INVALID;
        out->a = cbrt(3.0 * load * kme / (2.0 * TD_PI * modulus * A));
        out->b = out->a * s;
    }
    out->p_max = 3.0 * load / (2.0 * TD_PI * out->a * out->b);
    return TD_OK;
}

double td_ball_inner_contact_stress(double radial_load, int balls, double ball_diameter, double pitch_diameter,
                                    double groove_conformity)
{
    td_hertz_contact h;
    double D = ball_diameter, dm = pitch_diameter, f = groove_conformity;
    if (!(balls >= 1 && isfinite(D) && D > 0.0 && isfinite(dm) && dm > D && isfinite(f) && f > 0.5 &&
          isfinite(radial_load) && radial_load >= 0.0))
        return TD_UNDEFINED;
    /* rolling direction: ball (D/2) on the raceway (d_m - D)/2, both convex; across: the groove f D, concave */
    if (td_hertz_point(5.0 * radial_load / balls, 1.0 / (2.0 / D + 2.0 / (dm - D)), 1.0 / (2.0 / D - 1.0 / (f * D)),
                       TD_BEARING_STEEL_CONTACT_MODULUS, &h) != TD_OK)
        return TD_UNDEFINED;
    return h.p_max;
}
