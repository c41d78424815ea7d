/* touchdown report: the run file's quantities, read by their output ids (touchdown/result.h), and the
 * limits of the case stored in it (report_limits.c). A name the file does not hold, from an older
 * version or a part not modelled, is "not in this file", never a number. */
#include "report/report.h"

#include "touchdown/assess.h"
#include "touchdown/dofs.h"
#include "touchdown/run.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The flags that say whether a quantity converges with the mesh: the contact totals that a run
 * bouncing at its end does not converge (summary_contact_totals_converge: docs/output-format.md
 * lists what it covers), and the instantaneous peaks of a rigid constraint (the contact load and
 * what follows from it: the summary's "(rigid constraint: ...)"). NONE: no flag applies. */
#define TOTALS TD_OUT_SUM_CONTACT_TOTALS_CONVERGE
#define PEAK TD_OUT_SUM_PEAK_NORMAL_FORCE_CONVERGES
#define NONE TD_OUT_ID_COUNT

/* The quantities, in the report's order: the run's, then each sensor's, then each retainer's
 * (its loads, the bearing's duty, heat and life). Keyed by output id, so that each name is the
 * schema's. The last column marks the totals over the simulated run (they only grow with time).
 * docs/report.md lists them. */
static const report_def defs[] = {
    /* the drop, over the run */
    {TD_OUT_SUM_PEAK_HOUSING_FORCE, "peak housing force", 0, REPORT_LIMIT_NONE, NONE, 0},
    {TD_OUT_SUM_PEAK_NORMAL_FORCE, "peak contact normal force", 0, REPORT_LIMIT_NONE, PEAK, 0},
    {TD_OUT_SUM_TOTAL_IMPULSE, "total impulse", 0, REPORT_LIMIT_NONE, TOTALS, 0},
    {TD_OUT_SUM_FRICTION_WORK, "friction work", 0, REPORT_LIMIT_NONE, NONE, 0},
    {TD_OUT_SUM_FIRST_CONTACT_TIME, "first contact", 0, REPORT_LIMIT_NONE, NONE, 0},
    {TD_OUT_SUM_CONTACT_TIME, "time in contact", 0, REPORT_LIMIT_NONE, TOTALS, 0},
    {TD_OUT_SUM_CONTACTS, "contact onsets", 0, REPORT_LIMIT_NONE, TOTALS, 0},
    {TD_OUT_SUM_ENDING_WHIRL_FREQUENCY, "whirl frequency at the end (busiest retainer)", 0, REPORT_LIMIT_NONE, TOTALS,
     0},
    {TD_OUT_SUM_FINAL_SPEED, "final speed", 0, REPORT_LIMIT_NONE, NONE, 0},
    {TD_OUT_SUM_SETTLE_TIME, "time to settle", 0, REPORT_LIMIT_NONE, NONE, 0},
    {TD_OUT_SENSOR_CLEARANCE, "smallest retainer clearance C_min", 0, REPORT_LIMIT_NONE, NONE, 0},
    /* ISO 14839-2 at each AMB's sensor */
    {TD_OUT_SENSOR_PEAK_DISPLACEMENT, "peak displacement while levitated", 2, REPORT_LIMIT_NONE, NONE, 0},
    {TD_OUT_SENSOR_ZONE, "ISO 14839-2 zone while levitated", 2, REPORT_LIMIT_ZONE, NONE, 0},
    /* each retainer: its loads */
    {TD_OUT_RETAINER_PEAK_HOUSING_FORCE, "peak housing force", 1, REPORT_LIMIT_NONE, NONE, 0},
    {TD_OUT_RETAINER_PEAK_NORMAL_FORCE, "peak contact normal force", 1, REPORT_LIMIT_NONE, PEAK, 0},
    {TD_OUT_RETAINER_IMPULSE, "impulse", 1, REPORT_LIMIT_NONE, TOTALS, 0},
    {TD_OUT_RETAINER_FRICTION_WORK, "friction work", 1, REPORT_LIMIT_NONE, NONE, 0},
    {TD_OUT_RETAINER_CONTACT_TIME, "time in contact", 1, REPORT_LIMIT_NONE, TOTALS, 0},
    /* the bearing's duty */
    {TD_OUT_RETAINER_LOAD_RATIO, "peak normal force / static rating C0", 1, REPORT_LIMIT_RATIO, PEAK, 0},
    {TD_OUT_RETAINER_PEAK_CONTACT_STRESS, "peak contact stress (Hertz)", 1, REPORT_LIMIT_STRESS, PEAK, 0},
    {TD_OUT_RETAINER_PEAK_SLIDING_VELOCITY, "peak sliding velocity", 1, REPORT_LIMIT_NONE, NONE, 0},
    {TD_OUT_RETAINER_PEAK_PV, "peak PV", 1, REPORT_LIMIT_NONE, PEAK, 0},
    {TD_OUT_RETAINER_PEAK_FRICTION_POWER, "peak friction power", 1, REPORT_LIMIT_NONE, PEAK, 0},
    {TD_OUT_RETAINER_PEAK_RACE_SPEED, "peak race speed", 1, REPORT_LIMIT_NONE, NONE, 0},
    /* heat */
    {TD_OUT_RETAINER_DRAG_WORK, "race drag work", 1, REPORT_LIMIT_NONE, NONE, 1},
    {TD_OUT_RETAINER_HEAT, "heat into the race", 1, REPORT_LIMIT_NONE, NONE, 1},
    {TD_OUT_RETAINER_PEAK_TEMPERATURE_RISE, "peak race temperature rise", 1, REPORT_LIMIT_TEMPERATURE, NONE, 1},
    {TD_OUT_RETAINER_PEAK_THERMAL_GROWTH, "peak thermal growth of the race bore", 1, REPORT_LIMIT_NONE, NONE, 1},
    /* life */
    {TD_OUT_RETAINER_LOAD_CYCLES, "load cycles (rainflow)", 1, REPORT_LIMIT_NONE, TOTALS, 1},
    {TD_OUT_RETAINER_DAMAGE, "damage (Miner)", 1, REPORT_LIMIT_NONE, TOTALS, 1},
    {TD_OUT_RETAINER_DROPS_TO_FAILURE, "drops to failure (1 / damage)", 1, REPORT_LIMIT_DROPS, TOTALS, 1},
    /* clearance margin: did it touch, and by how much did it miss (docs/output-format.md) */
    {TD_OUT_SUM_CONTACT_HAPPENED, "contact happened (1 yes, 0 no)", 0, REPORT_LIMIT_NONE, NONE, 0},
    {TD_OUT_SUM_MIN_CLEARANCE_MARGIN, "smallest clearance margin (c - r)", 0, REPORT_LIMIT_NONE, NONE, 0},
    {TD_OUT_RETAINER_MIN_CLEARANCE_MARGIN, "smallest clearance margin (c - r)", 1, REPORT_LIMIT_NONE, NONE, 0},
};

const char *report_state_words(report_state s)
{
    switch (s) {
    case REPORT_VALUE: return "";
    case REPORT_ABSENT: return "not in this file";
    case REPORT_UNDEFINED: return "not computed";
    case REPORT_NO_RATING: return "not computed (no dynamic rating C)";
    default: return "not an answer"; /* the first line says why: the run did not complete */
    }
}

const char *report_verdict_words(report_verdict v)
{
    switch (v) {
    case REPORT_WITHIN: return "within";
    case REPORT_EXCEEDS: return "exceeds";
    case REPORT_NOT_AT_REST: return "not judged: the run ended before the rotor came to rest";
    default: return "-";
    }
}

/* A root attribute of the run file by id: the id when the file holds it, else TD_OUT_ID_COUNT. */
static td_out_id attribute(const td_result *r, td_out_id id)
{
    return id != TD_OUT_ID_COUNT && td_result_has(r, id, NULL) ? id : TD_OUT_ID_COUNT;
}

/* The number of entries of the attribute id (0 when absent or unreadable). */
static int attribute_length(const td_result *r, td_out_id id)
{
    td_result_array a;
    int n = 0;
    if (attribute(r, id) != TD_OUT_ID_COUNT && td_result_read(r, id, NULL, &a, NULL) == TD_OK) {
        n = (int)a.n;
        td_result_array_free(&a);
    }
    return n;
}

/* The limit of a quantity of `part` and its verdict for `value`. A total over the run that only
 * grows (damage, heat) exceeds its limit for certain once it does; it is within only for a run that
 * ended at rest (the whole drop), else not judged. */
static void judge(report_item *it, const report_limits *lim, int at_rest)
{
    double v = it->value, l = TD_UNDEFINED;
    int within = 0;
    switch (it->def->limit) {
    case REPORT_LIMIT_RATIO: l = 1.0, within = v <= l; break;
    case REPORT_LIMIT_TEMPERATURE: l = lim->temperature_rise, within = v <= l; break;
    case REPORT_LIMIT_DROPS: l = lim->drops, within = v >= l; break;
    case REPORT_LIMIT_ZONE: l = lim->zone, within = v <= l; break;
    case REPORT_LIMIT_STRESS: l = TD_BALL_STATIC_STRESS_LIMIT, within = v <= l; break;
    default: break;
    }
    it->limit = l;
    if (it->state != REPORT_VALUE)
        it->verdict = REPORT_NOT_JUDGED;
    else if (isnan(l))
        it->verdict = REPORT_NO_LIMIT;
    else if (!within)
        it->verdict = REPORT_EXCEEDS;
    else
        it->verdict = it->def->run_total && !at_rest ? REPORT_NOT_AT_REST : REPORT_WITHIN;
}

/* Whether the file says the quantity converges: its flag attribute (d->flag) 1 or 0, else -1. */
static int converges(const td_result *r, const report_def *d, int part)
{
    td_result_array a;
    int c = -1;
    if (attribute(r, d->flag) == TD_OUT_ID_COUNT || td_result_read(r, d->flag, NULL, &a, NULL) != TD_OK)
        return -1;
    if (a.n == 1 || (part >= 0 && (size_t)part < a.n))
        c = a.v[a.n == 1 ? 0 : part] != 0.0;
    td_result_array_free(&a);
    return c;
}

/* Life, which a run writes only when some retainer's bearing has a dynamic rating. */
static int needs_rating(td_out_id id)
{
    return id == TD_OUT_RETAINER_LOAD_CYCLES || id == TD_OUT_RETAINER_DAMAGE || id == TD_OUT_RETAINER_DROPS_TO_FAILURE;
}

/* The quantity d of `part` (-1: the run) into the next item. */
static void read_item(const td_result *r, const report_def *d, int part, report *rep)
{
    td_result_array a;
    td_out_id id = attribute(r, d->id);
    size_t k = part < 0 ? 0 : (size_t)part;
    report_item *it;
    int have;
    if (rep->n >= REPORT_MAX_ITEMS)
        return;
    it = &rep->items[rep->n++];
    memset(it, 0, sizeof *it);
    memset(&a, 0, sizeof a);
    have = id != TD_OUT_ID_COUNT && td_result_read(r, id, NULL, &a, NULL) == TD_OK;
    it->def = d;
    it->part = part;
    snprintf(it->units, sizeof it->units, "%s", have ? a.units : "");
    if (!have && needs_rating(d->id) && rep->lim.read && part >= 0 && part < REPORT_MAX_PARTS &&
        isnan(rep->lim.dynamic_rating[part]))
        it->state = REPORT_NO_RATING; /* the run writes life only for a case with a rating */
    else if (!have || k >= a.n)
        it->state = REPORT_ABSENT;
    else if (!rep->complete)
        it->state = REPORT_NOT_ANSWER;
    else if (isnan(a.v[k]) || (d->limit == REPORT_LIMIT_ZONE && a.v[k] < 0.0)) /* a zone: -1 undefined */
        it->state = REPORT_UNDEFINED;
    else
        it->state = REPORT_VALUE, it->value = a.v[k];
    it->converges = it->state == REPORT_VALUE ? converges(r, d, part) : -1;
    judge(it, &rep->lim, rep->at_rest);
    td_result_array_free(&a);
}

/* Every quantity of the run (per 0), of each sensor (2), of each retainer (1), in the table's order. */
static void read_quantities(const td_result *r, report *rep)
{
    static const int pers[3] = {0, 2, 1};
    size_t i;
    int p, k;
    for (p = 0; p < 3; p++) {
        int parts = pers[p] == 0 ? 1 : pers[p] == 1 ? rep->nret : rep->namb;
        for (k = 0; k < parts && k < REPORT_MAX_PARTS; k++)
            for (i = 0; i < sizeof defs / sizeof defs[0]; i++)
                if (defs[i].per == pers[p])
                    read_item(r, &defs[i], pers[p] == 0 ? -1 : k, rep);
    }
}

/* A scalar numeric root attribute by id, NaN when absent. */
static double scalar(const td_result *r, td_out_id id)
{
    td_result_array a;
    double v = TD_UNDEFINED;
    if (td_result_has(r, id, NULL) && td_result_read(r, id, NULL, &a, NULL) == TD_OK) {
        if (a.n == 1)
            v = a.v[0];
        td_result_array_free(&a);
    }
    return v;
}

/* A text root attribute by id into buf ("" when absent). */
static void text(const td_result *r, td_out_id id, char *buf, size_t n)
{
    char *t = NULL;
    buf[0] = '\0';
    if (td_result_has(r, id, NULL) && td_result_read_text(r, id, NULL, &t, NULL) == TD_OK)
        snprintf(buf, n, "%s", t);
    free(t);
}

/* The run's facts: completeness, times, version, ending, the numbers of retainers and sensors. */
static void read_header(const td_result *r, report *rep)
{
    td_result_array a;
    double settled;
    rep->complete = td_result_complete(r);
    rep->flag = td_result_get_flag(r);
    text(r, TD_OUT_INCOMPLETE_REASON, rep->reason, sizeof rep->reason);
    text(r, TD_OUT_LIBRARY_VERSION, rep->version, sizeof rep->version);
    text(r, TD_OUT_SUM_ENDING, rep->ending, sizeof rep->ending);
    rep->t_start = scalar(r, TD_OUT_T_START);
    rep->t_end = scalar(r, TD_OUT_T_END);
    rep->t_reached = scalar(r, TD_OUT_T_REACHED);
    rep->speed = scalar(r, TD_OUT_MODEL_SPEED);
    rep->final_speed = scalar(r, TD_OUT_SUM_FINAL_SPEED);
    rep->at_rest = rep->complete && td_run_at_rest(rep->speed, rep->final_speed);
    settled = scalar(r, TD_OUT_SUM_SETTLED);
    rep->settled = isnan(settled) ? -1 : settled != 0.0;
    rep->nret = attribute_length(r, TD_OUT_RETAINER_CLEARANCE);
    if (rep->nret == 0 && td_result_read(r, TD_OUT_RET_X, NULL, &a, NULL) == TD_OK) {
        rep->nret = a.rank >= 2 ? (int)a.dims[1] : 0;
        td_result_array_free(&a);
    }
    rep->namb = attribute_length(r, TD_OUT_AMB_NODES);
}

int report_read(const td_result *r, const char *path, report *rep)
{
    char *case_text = NULL;
    if (td_result_get_kind(r) != TD_RESULT_RUN) {
        fprintf(stderr, "touchdown report: %s: a %s file, not a run file (touchdown run)\n", path,
                td_result_get_kind(r) == TD_RESULT_MODAL ? "modal" : "sweep");
        return 2;
    }
    rep->path = path;
    read_header(r, rep);
    if (td_result_has(r, TD_OUT_CASE_TEXT, NULL))
        td_result_read_text(r, TD_OUT_CASE_TEXT, NULL, &case_text, NULL);
    report_case_limits(case_text, rep->nret, &rep->lim, rep->description, sizeof rep->description);
    free(case_text);
    read_quantities(r, rep);
    return 0;
}
