/*
 * projective leap: the case's `leap` group (td_output_options.leap_*; docs/case-format.md,
 * "Projective leap"), read into the output options, and the rules that tie it to the machine.
 */
#include "case/case_schema.h"
#include "touchdown/run.h"

#include <stddef.h>

static const td_cs_key leap_keys[] = {
    {.key = "burst",
     .type = TD_CS_REAL,
     .offset = offsetof(td_output_options, leap_burst),
     .need = TD_CS_REQUIRED,
     .what = "the burst's length",
     .range = TD_CR_NONNEGATIVE,
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
     .doc_range = ">= 0, < `end_time`",
     .unit = "s",
     .doc = "no leap before this time: the slow rates must not be read over a transient (a fall); refused at or "
            "after `end_time` (an `end_at_rest` run's cap too): no leap could happen"},
};
const td_cs_table td_cs_leap = {"leap", "leap", leap_keys, TD_CS_COUNT(leap_keys), sizeof(td_output_options),
                                NULL,   NULL};

/* projective leap: the options and the machine (td_run_leap_check, the rule td_run applies too), the
 * fault named at its key, or at the group for the machine's. After every other key (the leap group is
 * read last): the schedule, the speed ramp, the spin, the retainers and the housing are the model's,
 * end_time the case's. */
td_status td_cr_check_leap(td_case_reader *r, const config_setting_t *g, const td_cs_key *k, void *rec)
{
    static const char *const keys[] = {NULL, "burst", "factor", "heal", "start", NULL};
    const config_setting_t *s = config_setting_get_member(g, k->key), *at;
    char why[320];
    td_leap_fault f;
    (void)rec;
    if (!s || (f = td_run_leap_check(r->c->model, &r->c->output, r->c->end_time, why, sizeof why)) == TD_LEAP_FINE)
        return TD_OK;
    at = keys[f] ? config_setting_get_member(s, keys[f]) : NULL;
    return td_cr_fail(r, at ? at : s, NULL, "%s", why);
}
