/*
 * The run summary's part on the touchdown bearing's duty and the AMB machine's vibration
 * (docs/theory.md, "Assessment"): each retainer's peak load against its bearing's static rating,
 * each AMB sensor's largest displacement while it worked and its ISO 14839-2 zone, and the time
 * the rotor took to settle after its first contact. The peaks themselves are the simulation's
 * (lib/sim/totals.c, at the accepted points); this file grades them, prints them and writes them.
 */
#include "run/duty.h"
#include "touchdown/assess.h"
#include "touchdown/dofs.h"

#include <math.h>
#include <stdlib.h>

void td_run_duty_init(td_run_summary *s)
{
    int j;
    s->sensor_clearance = TD_UNDEFINED;
    for (j = 0; j < TD_RUN_SUMMARY_AMBS; j++) {
        s->sensor_peak_displacement[j] = TD_UNDEFINED;
        s->sensor_zone[j] = -1;
    }
    s->contact_onset = TD_UNDEFINED;
    s->settle_time = TD_UNDEFINED;
    s->settled = -1;
    s->contact_totals_converge = 1;
}

void td_run_duty_undefine(td_run_summary *s)
{
    int k;
    for (k = 0; k < TD_RUN_SUMMARY_RETAINERS; k++) {
        td_run_retainer *r = &s->retainers[k];
        r->totals.peak_sliding_velocity = r->totals.peak_friction_power = r->totals.peak_pv = TD_UNDEFINED;
        r->totals.peak_contact_stress = r->totals.peak_race_speed = r->load_ratio = TD_UNDEFINED;
    }
    for (k = 0; k < TD_RUN_SUMMARY_AMBS; k++) {
        s->sensor_peak_displacement[k] = TD_UNDEFINED;
        s->sensor_zone[k] = -1;
    }
    s->settle_time = TD_UNDEFINED;
    s->settled = -1;
}

/* Retainer k's peak normal force over its bearing's static rating C0; TD_UNDEFINED without C0. */
static double load_ratio(const td_model *m, int k, const td_retainer_totals *t)
{
    td_retainer_bearing b;
    if (td_model_get_retainer_bearing(m, k, &b) != TD_OK || !(b.static_rating > 0.0))
        return TD_UNDEFINED;
    return t->peak_normal_force / b.static_rating;
}

/* Settled: in one contact, or free of the retainers, through the whole last stretch (ending_window). */
static void settle(td_run_summary *s)
{
    double since;
    if (td_is_undefined(s->first_contact_time)) {
        s->settled = TD_RUN_NOT_APPLICABLE;
        return;
    }
    since = td_is_undefined(s->contact_onset) ? s->last_contact_time : s->contact_onset;
    s->settled = s->t_reached - since >= s->ending_window;
    s->settle_time = s->settled ? since - s->first_contact_time : TD_UNDEFINED;
}

void td_run_duty_collect(td_run_summary *s, const td_sim *sim)
{
    const td_model *m = td_sim_model(sim);
    td_limits lim;
    int k, n = s->retainer_count < TD_RUN_SUMMARY_RETAINERS ? s->retainer_count : TD_RUN_SUMMARY_RETAINERS;
    for (k = 0; k < n; k++)
        s->retainers[k].load_ratio = load_ratio(m, k, &s->retainers[k].totals);
    td_model_get_limits(m, &lim);
    s->sensor_clearance = td_model_min_retainer_clearance(m);
    s->sensor_count = td_model_amb_count(m);
    for (k = 0; k < s->sensor_count && k < TD_RUN_SUMMARY_AMBS; k++) {
        if (td_sim_sensor_peak_displacement(sim, k, &s->sensor_peak_displacement[k]) != TD_OK)
            s->sensor_peak_displacement[k] = TD_UNDEFINED;
        s->sensor_zone[k] = td_vibration_zone_of(s->sensor_peak_displacement[k], s->sensor_clearance, &lim.zones);
    }
    settle(s);
    s->contact_totals_converge = s->regime != TD_REGIME_BOUNCE; /* the ending's, set before */
}

/* A zone as a file value: 0..3, NaN when undefined. */
static double zone_value(int zone)
{
    return zone >= 0 ? (double)zone : TD_UNDEFINED;
}

/* The AMBs' sensors: peak displacement and zone of each, and the clearance they are graded against. */
static td_status write_sensors(td_recorder *rec, const td_run_summary *s, const td_sim *sim, int reached_end,
                               td_error *err)
{
    const td_model *m = td_sim_model(sim);
    int j, n = td_model_amb_count(m);
    double *d = calloc((size_t)(n > 0 ? n : 1), sizeof *d), *z = calloc((size_t)(n > 0 ? n : 1), sizeof *z);
    td_limits lim;
    td_status st = d && z ? TD_OK : td_error_set(err, TD_ERR_NOMEM, "out of memory writing the summary");
    td_model_get_limits(m, &lim);
    for (j = 0; st == TD_OK && j < n; j++) { /* every AMB, also past the summary's first TD_RUN_SUMMARY_AMBS */
        if (!reached_end || td_sim_sensor_peak_displacement(sim, j, &d[j]) != TD_OK)
            d[j] = TD_UNDEFINED;
        z[j] = zone_value(td_vibration_zone_of(d[j], s->sensor_clearance, &lim.zones));
    }
    if (st == TD_OK)
        st = td_recorder_set_double(rec, TD_OUT_SENSOR_CLEARANCE, s->sensor_clearance, err);
    if (st == TD_OK && n > 0)
        st = td_recorder_set_doubles(rec, TD_OUT_SENSOR_PEAK_DISPLACEMENT, d, n, err);
    if (st == TD_OK && n > 0)
        st = td_recorder_set_doubles(rec, TD_OUT_SENSOR_ZONE, z, n, err);
    free(d);
    free(z);
    return st;
}

td_status td_run_duty_write(td_recorder *rec, const td_run_summary *s, const td_sim *sim, int reached_end,
                            td_error *err)
{
    const td_model *m = td_sim_model(sim);
    int k, n = td_model_retainer_count(m);
    double *v = calloc((size_t)(n > 0 ? n : 1), sizeof *v);
    td_status st = v ? TD_OK : td_error_set(err, TD_ERR_NOMEM, "out of memory writing the summary");
    for (k = 0; st == TD_OK && k < n; k++) {
        td_retainer_totals t;
        td_sim_retainer_totals(sim, k, &t);
        v[k] = reached_end ? load_ratio(m, k, &t) : TD_UNDEFINED;
    }
    if (st == TD_OK && n > 0)
        st = td_recorder_set_doubles(rec, TD_OUT_RETAINER_LOAD_RATIO, v, n, err);
    free(v);
    if (st == TD_OK)
        st = write_sensors(rec, s, sim, reached_end, err);
    if (st == TD_OK)
        st = td_recorder_set_double(rec, TD_OUT_SUM_SETTLE_TIME, s->settle_time, err);
    if (st == TD_OK)
        st = td_recorder_set_double(rec, TD_OUT_SUM_SETTLED,
                                    s->settled == 0 || s->settled == 1 ? (double)s->settled : TD_UNDEFINED, err);
    return st == TD_OK ? td_recorder_set_long(rec, TD_OUT_SUM_CONTACT_TOTALS_CONVERGE, s->contact_totals_converge, err)
                       : st;
}

/* A value with its unit, or "n/a" (undefined: not given, or the run did not reach its end). */
static void value_or_na(td_text *b, const char *label, double v, const char *unit, const char *sep)
{
    if (td_is_undefined(v))
        td_text_printf(b, "%s n/a%s", label, sep);
    else
        td_text_printf(b, "%s %.4g%s%s%s", label, v, unit[0] ? " " : "", unit, sep);
}

void td_run_duty_format(td_text *b, const td_run_summary *s)
{
    int k, n = s->retainer_count < TD_RUN_SUMMARY_RETAINERS ? s->retainer_count : TD_RUN_SUMMARY_RETAINERS;
    for (k = 0; k < n; k++) {
        const td_run_retainer *r = &s->retainers[k];
        td_text_printf(b, "bearing %-2d duty             peaks:", k);
        value_or_na(b, " sliding", r->totals.peak_sliding_velocity, "m/s", ",");
        value_or_na(b, " friction power", r->totals.peak_friction_power, "W", ",");
        value_or_na(b, " PV", r->totals.peak_pv, "Pa m/s", ",");
        value_or_na(b, " Hertz", r->totals.peak_contact_stress, "Pa", ",");
        value_or_na(b, " race speed", r->totals.peak_race_speed, "rad/s", ";");
        value_or_na(b, " load / C0", r->load_ratio, "", "");
        td_text_printf(b, "%s\n",
                       s->peak_converges ? ""
                                         : " (rigid constraint: the load, power, PV and stress peaks do not converge)");
    }
    for (k = 0; k < s->sensor_count && k < TD_RUN_SUMMARY_AMBS; k++) {
        if (td_is_undefined(s->sensor_peak_displacement[k]) || td_is_undefined(s->sensor_clearance)) {
            td_text_printf(b, "AMB %-2d sensor zone          n/a\n", k);
            continue;
        }
        td_text_printf(b, "AMB %-2d sensor zone          %s (ISO 14839-2): largest displacement %.4g m = %.4g C_min\n",
                       k, td_vibration_zone_name(s->sensor_zone[k]), s->sensor_peak_displacement[k],
                       s->sensor_peak_displacement[k] / s->sensor_clearance);
    }
    if (s->settled == 1)
        td_text_printf(b, "time to settle              %.6g s after the first contact (%s)\n", s->settle_time,
                       td_is_undefined(s->contact_onset) ? "free since its last contact ended"
                                                         : "in one contact since, held to the end");
    else
        td_text_printf(b, "time to settle              %s\n",
                       s->settled == 0 ? "not settled (it still touches and leaves its retainers in the last stretch)"
                       : s->settled == TD_RUN_NOT_APPLICABLE ? "n/a (no contact)"
                                                             : "n/a (the run did not reach its end)");
    if (!s->contact_totals_converge)
        td_text_printf(
            b,
            "not converged               total impulse, time in contact, contact counts, mean and rms "
            "normal force, whirl frequency, energy lost in damping and in the contacts%s (it bounces: a chaotic "
            "sequence of impacts)\n",
            s->life_kept ? ", the life's load cycles, damage and drops to failure" : "");
}

/* "KEY":[...] of n numbers, null for undefined. */
static void json_reals(td_text *b, const char *key, const double *v, int n)
{
    int i;
    td_text_printf(b, "\"%s\":[", key);
    for (i = 0; i < n; i++) {
        td_text_printf(b, "%s", i ? "," : "");
        td_text_json_real(b, v[i]);
    }
    td_text_printf(b, "],");
}

void td_run_duty_json(td_text *b, const td_run_summary *s)
{
    int j, n = s->sensor_count < TD_RUN_SUMMARY_AMBS ? s->sensor_count : TD_RUN_SUMMARY_AMBS;
    td_text_printf(b, "\"sensor_clearance\":");
    td_text_json_real(b, s->sensor_clearance);
    td_text_printf(b, ",");
    json_reals(b, "sensor_peak_displacement", s->sensor_peak_displacement, n);
    td_text_printf(b, "\"sensor_zone\":[");
    for (j = 0; j < n; j++)
        td_text_printf(b, "%s%s%s%s", j ? "," : "", s->sensor_zone[j] >= 0 ? "\"" : "",
                       s->sensor_zone[j] >= 0 ? td_vibration_zone_name(s->sensor_zone[j]) : "null",
                       s->sensor_zone[j] >= 0 ? "\"" : "");
    td_text_printf(b, "],\"settle_time\":");
    td_text_json_real(b, s->settle_time);
    td_text_printf(b, ",\"settled\":%s,\"contact_totals_converge\":%s,",
                   s->settled == 1   ? "true"
                   : s->settled == 0 ? "false"
                                     : "null",
                   s->contact_totals_converge ? "true" : "false");
}
