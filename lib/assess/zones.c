/*
 * ISO 14839-2 vibration zones (touchdown/assess.h). The standard grades an AMB machine by the
 * largest 0-peak displacement at its sensors against the minimum touchdown clearance C_min:
 * zone A (newly commissioned), B (unrestricted long-term operation), C (restricted operation),
 * D (damage likely). The boundaries below are the ones recalled for ISO 14839-2:2004; its text
 * could not be consulted (docs/theory.md, "Vibration zones"), so they are defaults a case
 * overrides with limits.zones.
 */
#include "touchdown/assess.h"

#include <math.h>
#include <stddef.h>

void td_zone_limits_default(td_zone_limits *z)
{
    if (!z)
        return;
    z->ab = 0.3;
    z->bc = 0.4;
    z->cd = 0.5;
}

int td_vibration_zone_of(double displacement, double c_min, const td_zone_limits *z)
{
    if (!z || !isfinite(displacement) || displacement < 0.0 || !isfinite(c_min) || !(c_min > 0.0))
        return -1;
    if (displacement <= z->ab * c_min)
        return TD_ZONE_A;
    if (displacement <= z->bc * c_min)
        return TD_ZONE_B;
    if (displacement <= z->cd * c_min)
        return TD_ZONE_C;
    return TD_ZONE_D;
}

const char *td_vibration_zone_name(int zone)
{
    static const char *const names[] = {"A", "B", "C", "D"};
    return zone >= TD_ZONE_A && zone <= TD_ZONE_D ? names[zone] : "undefined";
}
