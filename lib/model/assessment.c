/*
 * What a model carries for its assessment (touchdown/model.h): each retainer's rolling bearing
 * (ratings, ball geometry) and the limits a run is assessed against. Neither changes the run;
 * the simulation's totals (lib/sim/totals.c) and the run summary read them.
 */
#include "model/model_internal.h"
#include "touchdown/dofs.h"
#include "util/error_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ISO 281: 3 for ball bearings; a ball's groove radius is 0.515 .. 0.53 of its diameter in deep-groove
 * bearings (Harris & Kotzalas, Rolling Bearing Analysis, 5th ed., 2007, ch. 2), 0.52 taken */
#define DEFAULT_LIFE_EXPONENT 3.0
#define DEFAULT_GROOVE_CONFORMITY 0.52

static const td_error_site no_site = {NULL, 0, NULL};

#define FAIL_AT(err, part, index, field, ...)                                                                          \
    td_error_set_site((err), TD_ERR_INVALID, &(td_error_site){(part), (index), (field)}, &no_site, __VA_ARGS__)

static int finite_nonnegative(double v)
{
    return isfinite(v) && v >= 0.0;
}

void td_model_free_assessment(td_model *m)
{
    free(m->retainer_bearings);
    m->retainer_bearings = NULL;
    m->retainer_bearing_count = 0;
}

int td_model_clone_assessment(td_model *m, const td_model *src)
{
    m->limits = src->limits;
    m->has_limits = src->has_limits;
    m->retainer_bearing_count = 0;
    m->retainer_bearings = NULL;
    if (src->retainer_bearing_count == 0)
        return 1;
    m->retainer_bearings = malloc((size_t)src->retainer_bearing_count * sizeof *m->retainer_bearings);
    if (!m->retainer_bearings)
        return 0;
    memcpy(m->retainer_bearings, src->retainer_bearings,
           (size_t)src->retainer_bearing_count * sizeof *m->retainer_bearings);
    m->retainer_bearing_count = src->retainer_bearing_count;
    return 1;
}

/* The ratings, exponent and width: each finite and >= 0, the exponent 0 or in [1, 10]. */
static td_status check_ratings(const td_retainer_bearing *b, int k, td_error *err)
{
    if (!finite_nonnegative(b->static_rating))
        return FAIL_AT(err, "retainer", k, "bearing.static_rating", "must be >= 0 N (got %g)", b->static_rating);
    if (!finite_nonnegative(b->dynamic_rating))
        return FAIL_AT(err, "retainer", k, "bearing.dynamic_rating", "must be >= 0 N (got %g)", b->dynamic_rating);
    if (!(b->life_exponent == 0.0 || (b->life_exponent >= 1.0 && b->life_exponent <= 10.0)))
        return FAIL_AT(err, "retainer", k, "bearing.life_exponent",
                       "must be in [1, 10] (3 ball, 10/3 roller bearings; got %g)", b->life_exponent);
    if (!finite_nonnegative(b->width))
        return FAIL_AT(err, "retainer", k, "bearing.width", "must be >= 0 m (got %g)", b->width);
    return TD_OK;
}

/* The ball geometry: all of balls, ball and pitch diameters or none; a raceway outside the bore. */
static td_status check_geometry(const td_retainer_bearing *b, const td_retainer *r, int k, td_error *err)
{
    int any = b->balls != 0 || b->ball_diameter != 0.0 || b->pitch_diameter != 0.0;
    if (!(b->groove_conformity == 0.0 || (b->groove_conformity > 0.5 && b->groove_conformity < 1.0)))
        return FAIL_AT(err, "retainer", k, "bearing.groove_conformity", "must be in (0.5, 1) (got %g)",
                       b->groove_conformity);
    if (!any)
        return TD_OK;
    if (b->balls == 0) /* named at a diameter given: the key the user wrote */
        return FAIL_AT(err, "retainer", k, b->ball_diameter != 0.0 ? "bearing.ball_diameter" : "bearing.pitch_diameter",
                       "needs balls: the ball geometry is balls, ball_diameter and pitch_diameter, or none");
    if (b->balls < 3)
        return FAIL_AT(err, "retainer", k, "bearing.balls", "must be >= 3 (got %d)", b->balls);
    if (!(isfinite(b->ball_diameter) && b->ball_diameter > 0.0))
        return FAIL_AT(err, "retainer", k, b->ball_diameter != 0.0 ? "bearing.ball_diameter" : "bearing.balls",
                       "needs ball_diameter > 0 m (got %g): the ball geometry is balls, ball_diameter and "
                       "pitch_diameter, or none",
                       b->ball_diameter);
    if (!(isfinite(b->pitch_diameter) && b->pitch_diameter > b->ball_diameter))
        return FAIL_AT(err, "retainer", k, "bearing.pitch_diameter", "must exceed ball_diameter %g m (got %g)",
                       b->ball_diameter, b->pitch_diameter);
    /* the inner raceway, d_m - D across, carries the bore 2 R_b the shaft touches */
    if (b->pitch_diameter - b->ball_diameter <= 2.0 * r->bore_radius)
        return FAIL_AT(err, "retainer", k, "bearing.pitch_diameter",
                       "gives an inner raceway of %g m across (pitch_diameter - ball_diameter): it must exceed the "
                       "bore, 2 bore_radius = %g m",
                       b->pitch_diameter - b->ball_diameter, 2.0 * r->bore_radius);
    return TD_OK;
}

td_status td_model_set_retainer_bearing(td_model *m, int k, const td_retainer_bearing *b, td_error *err)
{
    td_retainer_bearing copy;
    td_status st;
    if (!m || !b)
        return td_error_set(err, TD_ERR_INVALID, "retainer bearing: NULL argument");
    if (k < 0 || k >= m->retainers.count)
        return td_error_set(err, TD_ERR_INVALID, "retainer bearing: no retainer %d (the model has %d)", k,
                            m->retainers.count);
    st = check_ratings(b, k, err);
    if (st == TD_OK)
        st = check_geometry(b, &m->retainers.items[k], k, err);
    if (st != TD_OK)
        return st;
    if (k >= m->retainer_bearing_count) {
        td_retainer_bearing *p = realloc(m->retainer_bearings, (size_t)m->retainers.count * sizeof *p);
        if (!p)
            return td_error_set(err, TD_ERR_NOMEM, "out of memory setting a retainer's bearing");
        memset(p + m->retainer_bearing_count, 0, (size_t)(m->retainers.count - m->retainer_bearing_count) * sizeof *p);
        m->retainer_bearings = p;
        m->retainer_bearing_count = m->retainers.count;
    }
    copy = *b;
    if (copy.life_exponent == 0.0)
        copy.life_exponent = DEFAULT_LIFE_EXPONENT;
    if (copy.groove_conformity == 0.0)
        copy.groove_conformity = DEFAULT_GROOVE_CONFORMITY;
    m->retainer_bearings[k] = copy;
    return TD_OK;
}

td_status td_model_get_retainer_bearing(const td_model *m, int k, td_retainer_bearing *out)
{
    if (!m || !out || k < 0 || k >= m->retainers.count)
        return TD_ERR_INVALID;
    if (k < m->retainer_bearing_count && m->retainer_bearings[k].life_exponent != 0.0) {
        *out = m->retainer_bearings[k];
        return TD_OK;
    }
    memset(out, 0, sizeof *out);
    out->life_exponent = DEFAULT_LIFE_EXPONENT;
    out->groove_conformity = DEFAULT_GROOVE_CONFORMITY;
    return TD_OK;
}

/* A limit that is TD_UNDEFINED (none) or finite and > 0. */
static int limit_ok(double v)
{
    return td_is_undefined(v) || (isfinite(v) && v > 0.0);
}

td_status td_model_set_limits(td_model *m, const td_limits *l, td_error *err)
{
    const td_zone_limits *z;
    if (!m || !l)
        return td_error_set(err, TD_ERR_INVALID, "limits: NULL argument");
    z = &l->zones;
    if (!(isfinite(z->ab) && isfinite(z->cd) && z->ab > 0.0 && z->ab < z->bc && z->bc < z->cd))
        return FAIL_AT(err, "limits", -1, "zones",
                       "must be three increasing fractions of C_min above 0, A/B < B/C < C/D (got %g, %g, %g)", z->ab,
                       z->bc, z->cd);
    if (!limit_ok(l->temperature_rise))
        return FAIL_AT(err, "limits", -1, "temperature_rise", "must be > 0 K (got %g)", l->temperature_rise);
    if (!limit_ok(l->drops))
        return FAIL_AT(err, "limits", -1, "drops", "must be > 0 (got %g)", l->drops);
    if (l->zone < TD_ZONE_A || l->zone > TD_ZONE_D)
        return FAIL_AT(err, "limits", -1, "zone", "must be a zone A..D (got %d)", l->zone);
    m->limits = *l;
    m->has_limits = 1;
    return TD_OK;
}

void td_model_get_limits(const td_model *m, td_limits *out)
{
    if (!out)
        return;
    if (m && m->has_limits) {
        *out = m->limits;
        return;
    }
    td_zone_limits_default(&out->zones);
    out->temperature_rise = TD_UNDEFINED;
    out->drops = TD_UNDEFINED;
    out->zone = TD_ZONE_ACCEPTABLE;
}
