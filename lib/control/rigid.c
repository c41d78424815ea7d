/*
 * rigid.c - the rigid-body coordinates of two bearing planes (docs/theory.md, "Rigid-body
 * coordinates"; the transform is stated in touchdown/controller.h).
 */
#include "touchdown/controller.h"

#include "util/error_internal.h"

#include <math.h>
#include <stddef.h>

td_status td_rigid_transform(double za, double zb, double zr, double T[4], td_error *err)
{
    double L = zb - za;
    if (!T)
        return td_error_set(err, TD_ERR_INVALID, "rigid transform: NULL T");
    if (!isfinite(za) || !isfinite(zb) || !isfinite(zr))
        return td_error_set(err, TD_ERR_INVALID, "rigid transform: za, zb and zr must be finite (got %g, %g, %g)", za,
                            zb, zr);
    if (L == 0.0)
        return td_error_set(err, TD_ERR_INVALID, "rigid transform: the two bearing planes coincide (za = zb = %g m)",
                            za);
    T[0] = (zb - zr) / L; /* x_r = ((zb - zr) x_a + (zr - za) x_b) / L */
    T[1] = -1.0 / L;      /* tilt = (x_b - x_a) / L */
    T[2] = (zr - za) / L;
    T[3] = 1.0 / L;
    return TD_OK;
}
