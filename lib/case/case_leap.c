/*
 * projective leap: the case's `leap` group (td_output_options.leap_*; docs/case-format.md,
 * "Projective leap"), read into the output options, and the rules that tie it to the machine.
 */
#include "case/case_schema.h"

#include <stddef.h>

/* projective leap: leap { burst; factor; heal; start; } (td_output_options.leap_*; the run loop,
 * lib/run/leap.c). A burst of at least one sample interval (the rates are read at grid samples), or 0:
 * no leaps (a case that ships with leaps run in full by one override, `leap.burst = 0`). */
static td_status check_leap_burst(td_case_reader *r, const config_setting_t *g, const td_cs_key *k, void *rec)
{
    const td_output_options *o = rec;
    if (o->leap_burst != 0.0 && o->leap_burst * o->sample_rate < 1.0)
        return td_cr_fail(r, config_setting_get_member(g, k->key), NULL,
                          "%g s is shorter than the sample interval 1 / output.sample_rate = %g s", o->leap_burst,
                          1.0 / o->sample_rate);
    return TD_OK;
}

static td_status check_leap_factor(td_case_reader *r, const config_setting_t *g, const td_cs_key *k, void *rec)
{
    const td_output_options *o = rec;
    if (!(o->leap_factor >= 1.0))
        return td_cr_fail(r, config_setting_get_member(g, k->key), NULL, "must be >= 1 (got %g)", o->leap_factor);
    return TD_OK;
}

static const td_cs_key leap_keys[] = {
    {.key = "burst",
     .type = TD_CS_REAL,
     .offset = offsetof(td_output_options, leap_burst),
     .need = TD_CS_REQUIRED,
     .what = "the burst's length",
     .range = TD_CR_NONNEGATIVE,
     .check = check_leap_burst,
     .doc_range = "0, or at least 1 / output.sample_rate",
     .unit = "s",
     .doc = "the stretch of full integration the slow rates are read over (the speed's, every total's, the energy "
            "account's terms); 0: no leaps, every second integrated (`--set leap.burst=0` runs a case that "
            "leaps in full)"},
    {.key = "factor",
     .type = TD_CS_REAL,
     .offset = offsetof(td_output_options, leap_factor),
     .need = TD_CS_REQUIRED,
     .what = "the leap's length in bursts",
     .range = TD_CR_POSITIVE,
     .check = check_leap_factor,
     .doc_range = ">= 1",
     .doc = "a leap is this many bursts long (rounded down to whole sample intervals)"},
    {.key = "heal",
     .type = TD_CS_REAL,
     .offset = offsetof(td_output_options, leap_heal),
     .need = TD_CS_REQUIRED,
     .what = "the healing stretch",
     .range = TD_CR_NONNEGATIVE,
     .unit = "s",
     .doc = "integrated after each leap, and before the first burst, and not read: the fast motion re-settles "
            "at the leapt speed"},
    {.key = "start",
     .type = TD_CS_REAL,
     .offset = offsetof(td_output_options, leap_start),
     .need = TD_CS_REQUIRED,
     .what = "the time the leaps may begin",
     .range = TD_CR_NONNEGATIVE,
     .unit = "s",
     .doc = "no leap before this time: the slow rates must not be read over a transient (a fall)"},
};
const td_cs_table td_cs_leap = {"leap", "leap", leap_keys, TD_CS_COUNT(leap_keys), sizeof(td_output_options),
                                NULL,   NULL};

/* projective leap: only a speed that is a state can be leapt */
td_status td_cr_check_leap(td_case_reader *r, const config_setting_t *g, const td_cs_key *k, void *rec)
{
    const config_setting_t *s = config_setting_get_member(g, k->key);
    td_spin sp;
    int i;
    (void)rec;
    if (!s || r->c->output.leap_burst == 0.0) /* none asked for, or turned off */
        return TD_OK;
    td_model_spin(r->c->model, &sp);
    if (!td_model_speed_varies(r->c->model) || !sp.free)
        return td_cr_fail(r, s, NULL, "a leap needs the speed as a free state (spin.free = true)");
    for (i = 0; i < td_model_change_count(r->c->model); i++) { /* the simulation's clock stays in a leap */
        td_change ch;
        if (td_model_get_change(r->c->model, i, &ch) == TD_OK && ch.time > r->c->output.leap_start)
            return td_cr_fail(r, config_setting_get_member(s, "start"), NULL,
                              "%g s is before the schedule's change at %g s: a leap would move it",
                              r->c->output.leap_start, ch.time);
    }
    return TD_OK;
}
