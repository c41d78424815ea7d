/*
 * The case keys of the assessment (touchdown/model.h "the bearing's duty"): a retainer's rolling
 * bearing, `retainers[].bearing`, read into the retainer's record (case_parts.c hands it to
 * td_model_set_retainer_bearing once the retainer is added), and the top-level `limits`. The
 * model checks how the values go together (the ball geometry, the zones' order) and names the
 * field, which case_site.c turns back into the setting.
 */
#include "case/case_schema.h"
#include "touchdown/dofs.h"
#include "util/error_internal.h"

#include <string.h>

static const td_cs_key bearing_keys[] = {
    {.key = "static_rating",
     .type = TD_CS_REAL,
     .offset = offsetof(td_retainer_bearing, static_rating),
     .range = TD_CR_POSITIVE,
     .unit = "N",
     .doc_default = "none",
     .doc = "basic static load rating C0 (ISO 76, the maker's catalogue): the summary's `retainer_load_ratio` is the "
            "peak normal force over it"},
    {.key = "dynamic_rating",
     .type = TD_CS_REAL,
     .offset = offsetof(td_retainer_bearing, dynamic_rating),
     .range = TD_CR_POSITIVE,
     .unit = "N",
     .doc_default = "none",
     .doc = "basic dynamic load rating C (ISO 281), for the life estimate"},
    {.key = "life_exponent",
     .type = TD_CS_REAL,
     .offset = offsetof(td_retainer_bearing, life_exponent),
     .def = 3.0,
     .range = TD_CR_POSITIVE,
     .doc_range = "1..10",
     .doc = "exponent p of the rating life L = (C/P)^p (ISO 281): 3 ball bearings, 10/3 roller bearings"},
    {.key = "balls",
     .type = TD_CS_INT,
     .offset = offsetof(td_retainer_bearing, balls),
     .lo = 3,
     .hi = 1000,
     .doc_default = "none",
     .doc = "number of balls Z; with `ball_diameter` and `pitch_diameter` (all three or none) it gives the Hertz "
            "contact stress of the most loaded ball on the inner raceway"},
    {.key = "ball_diameter",
     .type = TD_CS_REAL,
     .offset = offsetof(td_retainer_bearing, ball_diameter),
     .range = TD_CR_POSITIVE,
     .unit = "m",
     .doc_default = "none",
     .doc = "ball diameter D"},
    {.key = "pitch_diameter",
     .type = TD_CS_REAL,
     .offset = offsetof(td_retainer_bearing, pitch_diameter),
     .range = TD_CR_POSITIVE,
     .unit = "m",
     .doc_default = "none",
     .doc = "pitch diameter d_m of the ball set; the inner raceway, d_m - D across, must exceed the bore (2 "
            "`bore_radius`)"},
    {.key = "groove_conformity",
     .type = TD_CS_REAL,
     .offset = offsetof(td_retainer_bearing, groove_conformity),
     .def = 0.52,
     .range = TD_CR_OPEN_UNIT,
     .doc_range = "(0.5, 1)",
     .doc = "inner raceway groove radius over the ball diameter, f_i"},
    {.key = "width",
     .type = TD_CS_REAL,
     .offset = offsetof(td_retainer_bearing, width),
     .range = TD_CR_POSITIVE,
     .unit = "m",
     .doc_default = "none",
     .doc = "width b of the race the shaft touches: the contact pressure for PV is N / (2 R_s b)"},
};
const td_cs_table td_cs_retainer_bearing = {"retainers[].bearing",
                                            "retainer-parts",
                                            bearing_keys,
                                            TD_CS_COUNT(bearing_keys),
                                            sizeof(td_retainer_bearing),
                                            NULL,
                                            NULL};

td_status td_cr_set_retainer_bearing(td_case_reader *r, const config_setting_t *g, const td_retainer_bearing *b)
{
    td_error merr;
    td_status st;
    if (!config_setting_get_member(g, "bearing"))
        return TD_OK;
    st = td_model_set_retainer_bearing(r->c->model, td_model_retainer_count(r->c->model) - 1, b, &merr);
    return st == TD_OK ? TD_OK : td_cr_model_fail(r, g, st, &merr);
}

/* `limits` as read: the zones' boundaries with their count, the other limits as td_limits has them. */
typedef struct cr_limits {
    double zones[3];
    int zone_count;
    double temperature_rise, drops;
    int zone; /* td_vibration_zone */
} cr_limits;

static void limits_preset(void *rec)
{
    cr_limits *l = rec;
    td_zone_limits z;
    td_zone_limits_default(&z);
    l->zones[0] = z.ab;
    l->zones[1] = z.bc;
    l->zones[2] = z.cd;
    l->temperature_rise = TD_UNDEFINED;
    l->drops = TD_UNDEFINED;
    l->zone = TD_ZONE_ACCEPTABLE;
}

static td_status set_limits(td_case_reader *r, const config_setting_t *g, void *rec)
{
    const cr_limits *c = rec;
    td_limits l;
    td_error merr;
    td_status st;
    if (c->zone_count != 0 && c->zone_count != 3)
        return td_cr_fail(r, config_setting_get_member(g, "zones"), NULL,
                          "three boundaries A/B, B/C, C/D as fractions of C_min (got %d)", c->zone_count);
    l.zones.ab = c->zones[0];
    l.zones.bc = c->zones[1];
    l.zones.cd = c->zones[2];
    l.temperature_rise = c->temperature_rise;
    l.drops = c->drops;
    l.zone = c->zone;
    st = td_model_set_limits(r->c->model, &l, &merr);
    return st == TD_OK ? TD_OK : td_cr_model_fail(r, g, st, &merr);
}

static const char *const zone_names[] = {"A", "B", "C", "D"}; /* td_vibration_zone order */

static const td_cs_key limits_keys[] = {
    {.key = "zones",
     .type = TD_CS_REALS,
     .offset = offsetof(cr_limits, zones),
     .count_offset = offsetof(cr_limits, zone_count),
     .hi = 3,
     .range = TD_CR_POSITIVE,
     .doc_range = "3 increasing, > 0",
     .doc_default = "`[0.3, 0.4, 0.5]`",
     .doc = "ISO 14839-2 zone boundaries A/B, B/C, C/D as fractions of C_min, the smallest retainer clearance; the "
            "defaults are the standard's as recalled, not checked against its text "
            "([theory](theory.md#vibration-zones))"},
    {.key = "temperature_rise",
     .type = TD_CS_REAL,
     .offset = offsetof(cr_limits, temperature_rise),
     .need = TD_CS_PRESET,
     .range = TD_CR_POSITIVE,
     .unit = "K",
     .doc_default = "none",
     .doc = "the race temperature rise allowed; a run's peak rise, a total over the run, is judged within it "
            "only when the run ended at rest"},
    {.key = "drops",
     .type = TD_CS_REAL,
     .offset = offsetof(cr_limits, drops),
     .need = TD_CS_PRESET,
     .range = TD_CR_POSITIVE,
     .doc_default = "none",
     .doc = "the drops the touchdown bearing must survive; drops to failure (1 / the run's damage) is judged "
            "within it only when the run ended at rest"},
    {.key = "zone",
     .type = TD_CS_ENUM,
     .offset = offsetof(cr_limits, zone),
     .need = TD_CS_PRESET,
     .names = zone_names,
     .name_count = 4,
     .doc_default = "`\"B\"`",
     .doc = "the largest acceptable ISO 14839-2 zone of a sensor's displacement while levitated; the default is "
            "zone B, \"acceptable for unrestricted long-term operation\" in the standard's zone descriptions "
            "([theory](theory.md#vibration-zones))"},
};
const td_cs_table td_cs_limits = {"limits",          "limits",      limits_keys, TD_CS_COUNT(limits_keys),
                                  sizeof(cr_limits), limits_preset, set_limits};
