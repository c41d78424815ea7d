/*
 * touchdown/assess.h - what a run's numbers mean against the standards: ISO 14839-2 vibration
 * zones of an AMB machine, the contact stress of a touchdown ball bearing (Hertz), and its life
 * (rainflow-counted load cycles against its rating life).
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

/** The largest zone acceptable by default: zone B, "acceptable for unrestricted long-term operation"
 *  (ISO 14839-2:2004's zone descriptions, which follow ISO 10816-1's: A newly commissioned machines,
 *  B unrestricted long-term operation, C a limited period only, D damage may result). */
#define TD_ZONE_ACCEPTABLE TD_ZONE_B

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

/** Pa, the largest contact stress of a radial ball bearing at its static rating C0 (ISO 76: 4200 MPa
 *  at the most loaded ball's contact, a permanent deformation of about 1/10000 of the ball diameter). */
#define TD_BALL_STATIC_STRESS_LIMIT 4.2e9

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
/* life (lib/assess/rainflow.c, lib/assess/life.c; docs/theory.md, "Touchdown bearing life") */

/**
 * An online rainflow counter (ASTM E1049-85 (2017), 5.4.4, "rainflow counting"): the history's
 * values come one at a time (td_rainflow_add); each reversal goes onto a stack, and the ranges of
 * the three-point rule that close go to the caller as they close, a full cycle (count 1) or, on
 * the range that holds the history's first point, a half cycle (count 0.5). What is left on the
 * stack at the end, the residue, counts as half cycles (td_rainflow_residue), as in the
 * standard's worked example (its Fig. 6 and Table 4).
 *
 * Hysteresis gate: a turn of the history is a reversal only once the history has moved back from
 * its extreme by more than `gate` (>= 0, in the units of the values); smaller wiggles are not
 * reversals and add no cycle. The gate 0 keeps every strict turn (the standard's peak-valley
 * step; equal neighbouring values are one point). Ranges below the gate can still close where the
 * gate let their reversals through (a wiggle larger than the gate turns twice).
 */
typedef struct td_rainflow td_rainflow;

/** A counted cycle: its range (|peak - valley| >= 0), its mean ((peak + valley) / 2), its count
 *  (1: a full cycle, 0.5: a half cycle). */
typedef void (*td_rainflow_cycle_fn)(void *user, double range, double mean, double count);

/** A counter with its hysteresis gate (finite, >= 0; else TD_ERR_INVALID). NULL on failure. */
TD_API td_rainflow *td_rainflow_create(double gate, td_error *err);
/** Free a counter; NULL is accepted. */
TD_API void td_rainflow_free(td_rainflow **rf);
/** The history's next value (finite; else TD_ERR_INVALID and the counter unchanged). The cycles it
 *  closes go to fn(user, ...) (fn may be NULL); TD_ERR_NOMEM when the stack cannot grow (the value
 *  is then not taken: the counter is as before the call). */
TD_API td_status td_rainflow_add(td_rainflow *rf, double value, td_rainflow_cycle_fn fn, void *user, td_error *err);
/** The residue as half cycles, each range between neighbouring points left on the stack, the
 *  history's last extreme included, as though the history ended now. The counter is unchanged:
 *  it can go on taking values. */
TD_API void td_rainflow_residue(const td_rainflow *rf, td_rainflow_cycle_fn fn, void *user);
/** Values taken so far. */
TD_API long td_rainflow_values(const td_rainflow *rf);

/**
 * The touchdown bearing's fatigue damage (docs/theory.md, "Touchdown bearing life"): the basic
 * rating life of ISO 281:2007 (eq. 1, L10 = (C / P)^p million revolutions, 90 % reliability) taken
 * per load cycle and per revolution, summed by the Palmgren-Miner rule. A load cycle of range dF
 * counts as one revolution at the load dF; a revolution of the race under the load F counts as one
 * revolution at F. The damage of a run is the fraction of the L10 life it used; 1 / damage the
 * runs like it the bearing survives.
 */
typedef struct td_life_law {
    double dynamic_rating; /**< C, N: the basic dynamic radial load rating (ISO 281) */
    double life_exponent;  /**< p: 3 for ball bearings, 10/3 for roller bearings (ISO 281) */
} td_life_law;

/** The hysteresis gate of the contact load's rainflow count, as a fraction of C: a load cycle this
 *  small adds (1e-3)^p of a revolution's damage, 1e-9 of it for p = 3 (docs/theory.md). */
#define TD_LIFE_GATE 1e-3

/** Miner damage of `count` load cycles (1 or 0.5) of range dF (N): count (dF / C)^p 1e-6.
 *  TD_UNDEFINED when the law is not a finite C > 0 and p > 0, or dF is not finite and >= 0. */
TD_API double td_life_cycle_damage(const td_life_law *law, double range, double count);
/** Runs like the one that did `damage` the bearing survives: 1 / damage; +infinity (unlimited) for a
 *  run that used none of the life (damage 0); TD_UNDEFINED when damage is not finite and >= 0 (no
 *  rating). So NaN and infinity tell "not computed" from "no damage" in files and sweep tables. */
TD_API double td_life_runs_to_failure(double damage);
/** Miner damage per second of the race turning at race_speed (rad/s) under the load F (N):
 *  (F / C)^p |race_speed| / (2 pi) 1e-6 (0 for F <= 0). TD_UNDEFINED as td_life_cycle_damage. */
TD_API double td_life_rolling_rate(const td_life_law *law, double load, double race_speed);

#ifdef __cplusplus
}
#endif

#endif /* TOUCHDOWN_ASSESS_H */
