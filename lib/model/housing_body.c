/*
 * The compliant housing (touchdown/housing.h td_housing_body; docs/theory.md, "Compliant housing"):
 * the housing as a rigid body on resilient mounts, as the model keeps it; its DOFs in the assembled
 * system are assemble_body.c's.
 */
#include "model/model_internal.h"
#include "util/error_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const td_error_site no_site = {NULL, 0, NULL};

/* Fail naming the body's field ("housing.body: FIELD: ..."). */
#define FAIL_BODY(err, field, ...)                                                                                     \
    td_error_set_site((err), TD_ERR_INVALID, &(td_error_site){"housing.body", -1, (field)}, &no_site, __VA_ARGS__)

/* Fail naming mount i's field ("housing.body.mounts I: FIELD: ..."); fields are literals, which the
 * error keeps by pointer. */
#define FAIL_MOUNT(err, i, field, ...)                                                                                 \
    td_error_set_site((err), TD_ERR_INVALID, &(td_error_site){"housing.body.mounts", (i), (field)}, &no_site,          \
                      __VA_ARGS__)

/* The mounts hold the body: a total stiffness > 0, and with an inertia a tilt stiffness too (mounts
 * at two positions at least: det [sum k, sum k d; sum k d, sum k d^2] > 0). */
static td_status check_mounts(const td_housing_body *b, td_error *err)
{
    double k = 0.0, kd = 0.0, kdd = 0.0;
    int i;
    for (i = 0; i < b->mount_count; i++) {
        const td_housing_mount *mt = &b->mounts[i];
        double d = mt->position - b->centre;
        if (!isfinite(mt->position))
            return FAIL_MOUNT(err, i, "position", "must be finite (got %g)", mt->position);
        if (!(isfinite(mt->stiffness) && mt->stiffness >= 0.0))
            return FAIL_MOUNT(err, i, "stiffness", "must be >= 0 N/m (got %g)", mt->stiffness);
        if (!(isfinite(mt->damping) && mt->damping >= 0.0))
            return FAIL_MOUNT(err, i, "damping", "must be >= 0 N s/m (got %g)", mt->damping);
        k += mt->stiffness, kd += mt->stiffness * d, kdd += mt->stiffness * d * d;
    }
    if (!(k > 0.0))
        return FAIL_BODY(err, "mounts", "the mounts' total stiffness must be > 0: nothing holds the body");
    if (b->inertia > 0.0 && !(k * kdd - kd * kd > 1e-12 * k * kdd))
        return FAIL_BODY(err, "mounts",
                         "a body with an inertia tilts: it needs stiff mounts at two axial positions at least");
    return TD_OK;
}

td_status td_model_set_housing_body(td_model *m, const td_housing_body *b, td_error *err)
{
    td_status st;
    if (!m || !b)
        return td_error_set(err, TD_ERR_INVALID, "housing body: NULL argument");
    if (!(isfinite(b->mass) && b->mass > 0.0))
        return FAIL_BODY(err, "mass", "must be > 0 kg (got %g)", b->mass);
    if (!(isfinite(b->inertia) && b->inertia >= 0.0))
        return FAIL_BODY(err, "inertia", "must be >= 0 kg m^2 (got %g)", b->inertia);
    if (!isfinite(b->centre))
        return FAIL_BODY(err, "centre", "must be finite (got %g)", b->centre);
    if (b->mount_count < 1 || b->mount_count > TD_HOUSING_MAX_MOUNTS)
        return FAIL_BODY(err, "mounts", "needs 1..%d mounts (got %d)", TD_HOUSING_MAX_MOUNTS, b->mount_count);
    st = check_mounts(b, err);
    if (st != TD_OK)
        return st;
    m->body = *b;
    memset(m->body.mounts + b->mount_count, 0, (size_t)(TD_HOUSING_MAX_MOUNTS - b->mount_count) * sizeof *b->mounts);
    m->has_body = 1;
    return TD_OK;
}

int td_model_get_housing_body(const td_model *m, td_housing_body *out)
{
    int has = m && m->has_body;
    if (out) {
        if (has)
            *out = m->body;
        else
            memset(out, 0, sizeof *out);
    }
    return has;
}

int td_model_housing_body_dofs(const td_model *m)
{
    return m && m->has_body ? (m->body.inertia > 0.0 ? 4 : 2) : 0;
}
