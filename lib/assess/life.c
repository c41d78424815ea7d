/*
 * The touchdown bearing's fatigue damage (touchdown/assess.h td_life_law; docs/theory.md,
 * "Touchdown bearing life"): ISO 281:2007's basic rating life, L10 = (C / P)^p million
 * revolutions (its eq. 1 with the ball bearing's p = 3, 10/3 for roller bearings), whose inverse
 * is the damage of one revolution at the load P under the Palmgren-Miner rule (the variable-load
 * life of ISO 281 and Lundberg-Palmgren is the same sum: the equivalent load's p-th power is the
 * mean of P^p over the revolutions).
 */
#include "touchdown/assess.h"
#include "touchdown/dofs.h"

#include <math.h>

/* Revolutions of the rating life's unit, 10^6 (ISO 281: L10 in millions of revolutions). */
#define TD_LIFE_UNIT 1e6

static int law_ok(const td_life_law *law)
{
    return law && isfinite(law->dynamic_rating) && law->dynamic_rating > 0.0 && isfinite(law->life_exponent) &&
           law->life_exponent > 0.0;
}

double td_life_cycle_damage(const td_life_law *law, double range, double count)
{
    if (!law_ok(law) || !isfinite(range) || range < 0.0 || !isfinite(count))
        return TD_UNDEFINED;
    return count * pow(range / law->dynamic_rating, law->life_exponent) / TD_LIFE_UNIT;
}

double td_life_runs_to_failure(double damage)
{
    if (!isfinite(damage) || damage < 0.0)
        return TD_UNDEFINED;
    return damage > 0.0 ? 1.0 / damage : HUGE_VAL; /* no damage: unlimited, not "none" */
}

double td_life_rolling_rate(const td_life_law *law, double load, double race_speed)
{
    if (!law_ok(law) || !isfinite(load) || !isfinite(race_speed))
        return TD_UNDEFINED;
    if (load <= 0.0)
        return 0.0;
    return pow(load / law->dynamic_rating, law->life_exponent) * fabs(race_speed) / (2.0 * TD_PI) / TD_LIFE_UNIT;
}
