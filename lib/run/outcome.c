/*
 * The run summary's answer to "did it touch, and by how much did it miss" (docs/output-format.md,
 * "Clearance margin and shock outcome"): the smallest clearance margin over the retainers (each
 * retainer's is the simulation's, lib/sim/margin.c), whether the rotor touched, and what its contacts
 * came to (td_shock_outcome). Defined for every run, with or without housing motion.
 */
#include "run/outcome.h"
#include "touchdown/dofs.h"

#include <math.h>
#include <stdlib.h>

const char *td_shock_outcome_name(td_shock_outcome o)
{
    switch (o) {
    case TD_SHOCK_NONE: return "none";
    case TD_SHOCK_TOUCH: return "touch";
    case TD_SHOCK_RUB: return "rub";
    case TD_SHOCK_DROP: return "drop";
    case TD_SHOCK_UNSETTLED: return "unsettled";
    default: return NULL;
    }
}

void td_run_outcome_init(td_run_summary *s)
{
    s->min_clearance_margin = TD_UNDEFINED;
    s->min_clearance_retainer = -1;
    s->contact_happened = 0;
    s->shock_outcome = TD_SHOCK_UNDEFINED;
    s->contact_speed = TD_UNDEFINED;
}

void td_run_outcome_undefine(td_run_summary *s)
{
    int k;
    for (k = 0; k < TD_RUN_SUMMARY_RETAINERS; k++)
        s->retainers[k].totals.min_clearance_margin = TD_UNDEFINED;
    s->min_clearance_margin = TD_UNDEFINED;
    s->min_clearance_retainer = -1;
    s->contact_happened = s->contacts > 0 ? 1 : -1; /* it may have touched after the time reached */
    s->shock_outcome = TD_SHOCK_UNDEFINED;
}

/* 1 if nothing will lift the rotor off its retainers: an AMB off at the end (it cannot), or the rotor
 * in contact at the end after contact over at least half of the ending's stretch (td_run_summary_ending:
 * a rub, a rolling or a whirl, at rest; not a bounce, from which working AMBs may still lift it, nor a
 * rotor that has just lifted off). */
static int held_down(const td_run_summary *s, const td_sim *sim, int in_contact)
{
    int a, n = td_model_amb_count(td_sim_model(sim));
    for (a = 0; a < n; a++)
        if (td_sim_amb_mode(sim, a) == TD_AMB_OFF)
            return 1;
    return in_contact && (s->regime == TD_REGIME_RUB || s->regime == TD_REGIME_BACKWARD_WHIRL);
}

void td_run_outcome_collect(td_run_summary *s, const td_sim *sim, int in_contact)
{
    int k, n = td_model_retainer_count(td_sim_model(sim)), touched = s->contacts > 0, sustained = 0;
    /* the revolution at the contacts (the first's speed), not the model's: a run-down's speed is 0 */
    double w = td_is_undefined(s->contact_speed) ? s->speed : s->contact_speed;
    double revolution = w != 0.0 ? 2.0 * TD_PI / fabs(w) : INFINITY;
    for (k = 0; k < n; k++) {
        td_retainer_totals t;
        td_sim_retainer_totals(sim, k, &t);
        if (s->min_clearance_retainer < 0 || t.min_clearance_margin < s->min_clearance_margin) {
            s->min_clearance_margin = t.min_clearance_margin;
            s->min_clearance_retainer = k;
        }
        /* a contact from the start has no onset, but its time */
        touched = touched || t.contacts + t.touch_and_go > 0 || t.contact_time > 0.0;
        /* sustained: a contact that whirled TD_TOUCH_AND_GO_ANGLE, or contact longer than a revolution in all
           (a rotor pressed onto its retainer by a long pulse hardly whirls, and may chatter there) */
        sustained = sustained || t.contacts > 0 || t.contact_time > revolution;
    }
    s->contact_happened = touched;
    /* on the retainers at the end (in contact, or a contact within the last free_window): a drop when
       nothing will lift the rotor off them, else too soon to tell */
    s->shock_outcome = !touched                               ? TD_SHOCK_NONE
                       : !(in_contact || s->free_at_end == 0) ? (sustained ? TD_SHOCK_RUB : TD_SHOCK_TOUCH)
                       : held_down(s, sim, in_contact)        ? TD_SHOCK_DROP
                                                              : TD_SHOCK_UNSETTLED;
}

static const char *contact_word(int v)
{
    return v > 0 ? "yes" : v == 0 ? "no" : "undetermined";
}

void td_run_outcome_format(td_text *b, const td_run_summary *s)
{
    if (td_is_undefined(s->min_clearance_margin))
        td_text_printf(b, "clearance margin            n/a (%s)",
                       s->status != TD_OK ? "the run did not reach its end" : "no retainer");
    else
        td_text_printf(b, "clearance margin            %.6g m, retainer %d (smallest clearance - radius%s)",
                       s->min_clearance_margin, s->min_clearance_retainer,
                       s->min_clearance_margin < 0.0 ? "; below 0: past the clearance, a compliant contact's "
                                                       "penetration or the rigid constraint's drift"
                                                     : "");
    td_text_printf(b, "; contact %s", contact_word(s->contact_happened));
    if (td_shock_outcome_name((td_shock_outcome)s->shock_outcome))
        td_text_printf(b, "; outcome %s\n", td_shock_outcome_name((td_shock_outcome)s->shock_outcome));
    else
        td_text_printf(b, "; outcome n/a\n");
}

void td_run_outcome_json(td_text *b, const td_run_summary *s)
{
    const char *name = td_shock_outcome_name((td_shock_outcome)s->shock_outcome);
    td_text_printf(b, "\"min_clearance_margin\":");
    td_text_json_real(b, s->min_clearance_margin);
    if (s->min_clearance_retainer >= 0)
        td_text_printf(b, ",\"min_clearance_retainer\":%d,", s->min_clearance_retainer);
    else
        td_text_printf(b, ",\"min_clearance_retainer\":null,");
    td_text_printf(b, "\"contact_happened\":%s,",
                   s->contact_happened > 0    ? "true"
                   : s->contact_happened == 0 ? "false"
                                              : "null");
    if (name)
        td_text_printf(b, "\"shock_outcome\":\"%s\",", name);
    else
        td_text_printf(b, "\"shock_outcome\":null,");
}

td_status td_run_outcome_write(td_recorder *rec, const td_run_summary *s, const td_sim *sim, int reached_end,
                               td_error *err)
{
    const char *name = td_shock_outcome_name((td_shock_outcome)s->shock_outcome);
    int k, n = td_model_retainer_count(td_sim_model(sim));
    double *m = calloc((size_t)(n > 0 ? n : 1), sizeof *m);
    td_status st = m ? TD_OK : td_error_set(err, TD_ERR_NOMEM, "out of memory writing the summary");
    for (k = 0; st == TD_OK && k < n; k++) {
        td_retainer_totals t;
        td_sim_retainer_totals(sim, k, &t);
        m[k] = reached_end ? t.min_clearance_margin : TD_UNDEFINED;
    }
    if (st == TD_OK && n > 0)
        st = td_recorder_set_doubles(rec, TD_OUT_RETAINER_MIN_CLEARANCE_MARGIN, m, n, err);
    free(m);
    if (st == TD_OK)
        st = td_recorder_set_double(rec, TD_OUT_SUM_MIN_CLEARANCE_MARGIN, s->min_clearance_margin, err);
    if (st == TD_OK)
        st = td_recorder_set_double(
            rec, TD_OUT_SUM_CONTACT_HAPPENED,
            s->contact_happened == 0 || s->contact_happened == 1 ? (double)s->contact_happened : TD_UNDEFINED, err);
    if (st == TD_OK)
        st = td_recorder_set_string(rec, TD_OUT_SUM_SHOCK_OUTCOME, name ? name : "", err);
    return st;
}
