/*
 * The model's recovery supervisor (td_model_set_recovery, touchdown/model.h): its values, checked
 * when it is set, and its rules against the controllers, checked by td_model_validate. The
 * simulation runs it (lib/sim/supervisor.c).
 */
#include "model/model_internal.h"
#include "util/error_internal.h"

#include <math.h>
#include <string.h>

static const td_error_site no_site = {NULL, 0, NULL};

/* Fail naming the recovery table's field at fault ("recovery: FIELD: ..."). */
#define FAIL_AT(err, field, ...)                                                                                       \
    td_error_set_site((err), TD_ERR_INVALID, &(td_error_site){"recovery", -1, (field)}, &no_site, __VA_ARGS__)

/* A rule's values: a finite positive fraction and a finite dwell >= 0. */
static td_status check_rule(const td_recovery_rule *u, const char *fraction, const char *dwell, td_error *err)
{
    if (!(isfinite(u->radius_fraction) && u->radius_fraction > 0.0))
        return FAIL_AT(err, fraction, "must be finite and > 0 (got %g)", u->radius_fraction);
    if (!(isfinite(u->dwell) && u->dwell >= 0.0))
        return FAIL_AT(err, dwell, "must be finite and >= 0 s (got %g)", u->dwell);
    return TD_OK;
}

td_status td_model_set_recovery(td_model *m, const td_recovery *r, td_error *err)
{
    int i;
    if (!m || !r)
        return td_error_set(err, TD_ERR_INVALID, "recovery: NULL argument");
    if (r->pair_count < 0 || r->pair_count > TD_RECOVERY_MAX_PAIRS)
        return FAIL_AT(err, "nominal", "has %d pairs: 0 to %d", r->pair_count, TD_RECOVERY_MAX_PAIRS);
    for (i = 0; i < r->pair_count; i++) {
        if (r->nominal[i] < 0)
            return FAIL_AT(err, "nominal", "pair %d: controller %d must be >= 0", i, r->nominal[i]);
        if (r->controller[i] < 0)
            return FAIL_AT(err, "controller", "pair %d: controller %d must be >= 0", i, r->controller[i]);
    }
    if (r->pair_count > 0 && (check_rule(&r->detect, "detect.radius_fraction", "detect.dwell", err) ||
                              check_rule(&r->release, "release.radius_fraction", "release.dwell", err)))
        return TD_ERR_INVALID;
    /* hysteresis: a release band below the detection band, so that a rotor on the threshold does
     * not switch back and forth at every sample */
    if (r->pair_count > 0 && !(r->release.radius_fraction < r->detect.radius_fraction))
        return FAIL_AT(err, "release.radius_fraction",
                       "must be below detect.radius_fraction (%g; got %g): the release band lies inside the "
                       "detection band (hysteresis)",
                       r->detect.radius_fraction, r->release.radius_fraction);
    if (r->pair_count > 0 && !(isfinite(r->blend) && r->blend >= 0.0))
        return FAIL_AT(err, "blend", "must be finite and >= 0 s (got %g)", r->blend);
    m->recovery = *r;
    m->recovery.enabled = r->enabled != 0;
    return TD_OK;
}

int td_model_get_recovery(const td_model *m, td_recovery *out)
{
    if (out) {
        if (m)
            *out = m->recovery;
        else
            memset(out, 0, sizeof *out);
    }
    return m ? m->recovery.pair_count : 0;
}

double td_recovery_dwell_samples(double dwell, double rate)
{
    double n = dwell * rate, r = floor(n + 0.5);
    return fabs(n - r) <= 1e-9 * fmax(1.0, r) ? r : ceil(n);
}

int td_model_recovery_paired(const td_model *m, int i, int j)
{
    int p;
    for (p = 0; p < m->recovery.pair_count; p++)
        if ((m->recovery.nominal[p] == i && m->recovery.controller[p] == j) ||
            (m->recovery.nominal[p] == j && m->recovery.controller[p] == i))
            return 1;
    return 0;
}

int td_model_recovery_standby(const td_model *m, int l)
{
    int p;
    for (p = 0; m && p < m->recovery.pair_count; p++)
        if (m->recovery.controller[p] == l)
            return 1;
    return 0;
}

/* 1 if the n-long axis lists a and b are equal, entry by entry. */
static int same_axes(const int *a, const int *b, int n)
{
    return memcmp(a, b, (size_t)n * sizeof *a) == 0;
}

/* Pair p's two laws: both exist, differ, are sampled at one rate and read and drive the same axes. */
static td_status check_pair(const td_model *m, int p, td_error *err)
{
    const td_recovery *r = &m->recovery;
    const td_model_controller *a, *b;
    double ra, rb;
    int n = m->controllers.count;
    if (r->nominal[p] >= n)
        return FAIL_AT(err, "nominal", "pair %d: controller %d does not exist (%d controllers)", p, r->nominal[p], n);
    if (r->controller[p] >= n)
        return FAIL_AT(err, "controller", "pair %d: controller %d does not exist (%d controllers)", p, r->controller[p],
                       n);
    a = &m->controllers.items[r->nominal[p]];
    b = &m->controllers.items[r->controller[p]];
    if (r->nominal[p] == r->controller[p])
        return FAIL_AT(err, "controller", "pair %d: \"%s\" is its own recovery law", p, a->name);
    ra = a->sample_rate;
    rb = b->sample_rate;
    if (!(ra > 0.0) || !(rb > 0.0))
        return FAIL_AT(err, ra > 0.0 ? "controller" : "nominal",
                       "pair %d: \"%s\" is continuous: a supervised law is sampled (give it a sample_rate; "
                       "continuous supervised laws are not supported yet)",
                       p, ra > 0.0 ? b->name : a->name);
    if (ra != rb)
        return FAIL_AT(err, "controller",
                       "pair %d: \"%s\" samples at %g Hz, its nominal \"%s\" at %g Hz: a pair runs at one rate", p,
                       b->name, rb, a->name, ra);
    if (a->nin != b->nin || a->nout != b->nout || !same_axes(a->inputs, b->inputs, a->nin) ||
        !same_axes(a->outputs, b->outputs, a->nout))
        return FAIL_AT(err, "controller",
                       "pair %d: \"%s\" and its nominal \"%s\" must read and drive the same AMB axes in the same "
                       "order (the same ambs and coordinates)",
                       p, b->name, a->name);
    return TD_OK;
}

td_status td_model_check_recovery(const td_model *m, td_error *err)
{
    const td_recovery *r = &m->recovery;
    int p, q;
    if (r->pair_count == 0)
        return TD_OK;
    if (m->retainers.count == 0)
        return FAIL_AT(err, NULL,
                       "the supervisor's thresholds are fractions of the smallest retainer clearance: "
                       "the model has no retainer");
    for (p = 0; p < r->pair_count; p++) {
        if (check_pair(m, p, err))
            return TD_ERR_INVALID;
        for (q = 0; q < p; q++)
            if (r->nominal[p] == r->nominal[q] || r->nominal[p] == r->controller[q] ||
                r->controller[p] == r->nominal[q] || r->controller[p] == r->controller[q])
                return FAIL_AT(
                    err, r->nominal[p] == r->nominal[q] || r->nominal[p] == r->controller[q] ? "nominal" : "controller",
                    "pairs %d and %d share a controller: each controller is in one pair at most", q, p);
    }
    return TD_OK;
}
