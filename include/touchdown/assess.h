/*
 * touchdown/assess.h - what a run's numbers mean against the standards: ISO 14839-2 vibration
 * zones of an AMB machine, and the contact stress of a touchdown ball bearing (Hertz).
 * Units and the undefined value: touchdown/dofs.h. docs/theory.md, "Assessment", gives the
 * equations and their sources.
 */
#ifndef TOUCHDOWN_ASSESS_H
#define TOUCHDOWN_ASSESS_H

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

#ifdef __cplusplus
}
#endif

#endif /* TOUCHDOWN_ASSESS_H */
