/*
 * touchdown/assess.h - what a run's numbers mean against the standards: ISO 14839-2 vibration
 * zones of an AMB machine, and the contact stress of a touchdown ball bearing (Hertz).
 * Units and the undefined value: touchdown/dofs.h. docs/theory.md, "Assessment", gives the
 * equations and their sources.
 */
#ifndef TOUCHDOWN_ASSESS_H
#define TOUCHDOWN_ASSESS_H

#include "touchdown/error.h"
#include "touchdown/export.h"

#ifdef __cplusplus
extern "C" {
#endif

/** ISO 14839-2 vibration zones (lib/assess/zones.c). */
typedef enum td_vibration_zone { TD_ZONE_A = 0, TD_ZONE_B = 1, TD_ZONE_C = 2, TD_ZONE_D = 3 } td_vibration_zone;

/** Boundaries A/B, B/C, C/D as fractions of the minimum touchdown clearance C_min (0 < ab < bc < cd). */
typedef struct td_zone_limits {
    double ab, bc, cd;
} td_zone_limits;

/** The default boundaries, A/B 0.3, B/C 0.4, C/D 0.5 of C_min (ISO 14839-2:2004 as recalled; the
 *  standard's text could not be checked here: docs/theory.md, "Vibration zones"). */
TD_API void td_zone_limits_default(td_zone_limits *z);

/**
 * Zone of a displacement D (m, 0-peak of the orbit: the largest radius at the sensor) against
 * C_min (m): A for D <= ab C_min, B for D <= bc C_min, C for D <= cd C_min, else D (a value on a
 * boundary belongs to the better zone). -1 when D is not finite and >= 0, c_min not finite and
 * > 0, or z NULL.
 */
TD_API int td_vibration_zone_of(double displacement, double c_min, const td_zone_limits *z);

/** "A".."D" for a zone, "undefined" for anything else (-1). */
TD_API const char *td_vibration_zone_name(int zone);

/* the bearing's duty: Hertz contact of a ball bearing (lib/assess/hertz.c) */

/** The contact modulus E* = 1 / ((1 - nu1^2)/E1 + (1 - nu2^2)/E2) of bearing steel on bearing steel
 *  (AISI 52100, E = 207.5 GPa, nu = 0.3: Hamrock & Anderson, NASA RP-1105, 1983), Pa. */
#define TD_BEARING_STEEL_CONTACT_MODULUS (207.5e9 / (2.0 * (1.0 - 0.3 * 0.3)))

/** A Hertz point contact: the contact ellipse's semi-axes and its largest pressure. */
typedef struct td_hertz_contact {
    double a;     /**< m, the larger semi-axis (along the direction of the smaller curvature) */
    double b;     /**< m, the smaller semi-axis */
    double p_max; /**< Pa, the largest contact pressure, 3 P / (2 pi a b) */
} td_hertz_contact;

/**
 * The Hertz point contact (Johnson, Contact Mechanics, 1985, sec. 4.2) of two bodies pressed by
 * `load` P >= 0 (N) whose relative principal radii of curvature are rx and ry (m, > 0; the
 * curvature sum 1/rx + 1/ry), with contact modulus `modulus` E* (Pa, > 0): the exact solution, the
 * eccentricity from the complete elliptic integrals (GSL) by bisection. TD_OK, or TD_ERR_INVALID
 * (out all TD_UNDEFINED) for an argument out of range.
 */
TD_API td_status td_hertz_point(double load, double rx, double ry, double modulus, td_hertz_contact *out);

/**
 * The largest Hertz pressure (Pa) of a ball bearing's most loaded ball on its inner raceway under
 * the radial load `radial_load` (N, >= 0): the ball load Q = 5 F_r / Z (Stribeck; Harris &
 * Kotzalas, Rolling Bearing Analysis, 2007, for a radial ball bearing with a small clearance), the
 * raceway's relative radii 1/rx = 2/D + 2/(d_m - D) (rolling direction, zero contact angle) and
 * 1/ry = 2/D - 1/(f_i D) (across the groove), steel on steel. TD_UNDEFINED for a geometry out of
 * range (balls < 1, D <= 0, d_m <= D, f_i <= 0.5).
 */
TD_API double td_ball_inner_contact_stress(double radial_load, int balls, double ball_diameter, double pitch_diameter,
                                           double groove_conformity);

#ifdef __cplusplus
}
#endif

#endif /* TOUCHDOWN_ASSESS_H */
