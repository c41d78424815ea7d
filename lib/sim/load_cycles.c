/*
 * The retainers' load cycles and fatigue damage (td_retainer_totals damage, load_cycles;
 * touchdown/assess.h; docs/theory.md, "Touchdown bearing life"), for a retainer whose bearing has a
 * dynamic rating C.
 *
 * The contact normal force goes into a rainflow counter (lib/assess/rainflow.c, gate TD_LIFE_GATE C)
 * at the points the run has reached, each once and in order: every accepted point as
 * td_sim_totals_peaks records it, an integrator step's end beyond the output time only once the run
 * reaches it (monitor.c), never if the run goes on from before it. So the count does not depend on
 * the output grid. The cycles it closes add their damage as they close; those the end of the history
 * closes and its residue are added when the totals are read, as though the history ended there.
 * The race's revolutions under the load add their damage as a time integral over the steps
 * (totals.c, the trapezoid of td_sim_life_rate), taken back to the output time as the other totals.
 */
#include "sim/sim_internal.h"
#include "touchdown/assess.h"
#include "touchdown/model.h"

#include <math.h>

td_status td_sim_life_setup(td_sim *s, td_error *err)
{
    int k;
    for (k = 0; k < s->dae.nr; k++) {
        td_sim_totals *tk = &s->monitor.totals[k];
        td_retainer_bearing b;
        if (td_model_get_retainer_bearing(s->model, k, &b) != TD_OK || !(b.dynamic_rating > 0.0))
            continue;
        tk->law.dynamic_rating = b.dynamic_rating;
        tk->law.life_exponent = b.life_exponent > 0.0 ? b.life_exponent : 3.0;
        tk->cycles = td_rainflow_create(TD_LIFE_GATE * b.dynamic_rating, err);
        if (!tk->cycles)
            return err ? err->code : TD_ERR_NOMEM;
    }
    return TD_OK;
}

void td_sim_life_free(td_sim *s)
{
    int k;
    if (!s->monitor.totals)
        return;
    for (k = 0; k < s->dae.nr; k++)
        td_rainflow_free(&s->monitor.totals[k].cycles);
}

/* The contact load of retainer k at y: its normal force in contact, 0 out of it (as totals.c). */
static double contact_load(const td_sim *s, int k, const double *y)
{
    return s->contacts.ret[k].mode != TD_RMODE_FREE ? td_sim_normal_force(s, k, y) : 0.0;
}

double td_sim_life_rate(const td_sim *s, int k, const double *y)
{
    const td_sim_totals *tk = &s->monitor.totals[k];
    double rate;
    if (!tk->cycles)
        return 0.0;
    rate = td_life_rolling_rate(&tk->law, contact_load(s, k, y), td_sim_race_speed(s, k, y));
    return isfinite(rate) ? rate : 0.0;
}

/* A cycle closed: its count and damage into the retainer's sums (user: the td_sim_totals). */
static void closed(void *user, double range, double mean, double count)
{
    td_sim_totals *tk = user;
    (void)mean;
    tk->closed_cycles += count;
    tk->cycle_damage += td_life_cycle_damage(&tk->law, range, count);
}

void td_sim_life_point(td_sim *s, int k, const double *y)
{
    td_sim_totals *tk = &s->monitor.totals[k];
    double n;
    if (!tk->cycles || tk->life_failed)
        return;
    n = contact_load(s, k, y);
    /* a load that is no number, or a counter that cannot grow: no answer rather than a wrong one */
    if (!isfinite(n) || td_rainflow_add(tk->cycles, n, closed, tk, NULL) != TD_OK)
        tk->life_failed = 1;
}

/* The cycles of the end of the history, summed into a copy of the retainer's sums. */
typedef struct end_sums {
    const td_life_law *law;
    double cycles, damage;
} end_sums;

static void at_end(void *user, double range, double mean, double count)
{
    end_sums *e = user;
    (void)mean;
    e->cycles += count;
    e->damage += td_life_cycle_damage(e->law, range, count);
}

void td_sim_life_get(const td_sim *s, int k, td_retainer_totals *out)
{
    const td_sim_totals *tk = &s->monitor.totals[k];
    end_sums e;
    if (!tk->cycles || tk->life_failed) {
        out->damage = TD_UNDEFINED;
        out->load_cycles = TD_UNDEFINED;
        return;
    }
    e.law = &tk->law;
    e.cycles = tk->closed_cycles;
    e.damage = tk->cycle_damage;
    td_rainflow_residue(tk->cycles, at_end, &e);
    out->damage += e.damage;
    out->load_cycles = e.cycles;
}
