/*
 * The case keys of the compliant housing, `housing.body` (touchdown/housing.h td_housing_body): the
 * housing as a rigid body on resilient mounts. The model checks how the values go together (the
 * mounts hold the body) and names the field, which case_site.c turns back into the setting.
 */
#include "case/case_schema.h"
#include "touchdown/dofs.h"
#include "util/error_internal.h"

#include <string.h>

#define BODY_STR(x) #x
#define BODY_XSTR(x) BODY_STR(x)

static const td_cs_key mount_keys[] = {
    {.key = "position",
     .type = TD_CS_REAL,
     .offset = offsetof(td_housing_mount, position),
     .need = TD_CS_REQUIRED,
     .what = "the mount's axial position, m",
     .unit = "m",
     .doc = "axial position z of the mount (the shaft's z)"},
    {.key = "stiffness",
     .type = TD_CS_REAL,
     .offset = offsetof(td_housing_mount, stiffness),
     .need = TD_CS_REQUIRED,
     .what = "the mount's stiffness, N/m",
     .range = TD_CR_NONNEGATIVE,
     .unit = "N/m",
     .doc = "the mount's stiffness in each of x and y (isotropic)"},
    {.key = "damping",
     .type = TD_CS_REAL,
     .offset = offsetof(td_housing_mount, damping),
     .def = 0.0,
     .range = TD_CR_NONNEGATIVE,
     .unit = "N s/m",
     .doc = "the mount's viscous damping in each of x and y"},
};
static const td_cs_table mount_table = {"housing.body.mounts[]",  NULL, mount_keys, TD_CS_COUNT(mount_keys),
                                        sizeof(td_housing_mount), NULL, NULL};

/* `mounts`: each entry read by mount_table into the body's array. */
static td_status read_mounts(td_case_reader *r, const config_setting_t *g, const td_cs_key *k, void *rec)
{
    td_housing_body *b = rec;
    const config_setting_t *list, *e;
    int i, n;
    td_status st = td_cr_list(r, g, k->key, &list);
    if (st != TD_OK)
        return st;
    if (!list)
        return td_cr_missing(r, g, k->key, k->what);
    n = config_setting_length(list);
    if (n < 1 || n > TD_HOUSING_MAX_MOUNTS)
        return td_cr_fail(r, list, NULL, "needs 1..%d mounts (got %d)", TD_HOUSING_MAX_MOUNTS, n);
    for (i = 0; st == TD_OK && i < n; i++) {
        st = td_cr_entry(r, list, i, &e);
        if (st == TD_OK)
            st = td_cs_read(r, e, &mount_table, &b->mounts[i]);
    }
    b->mount_count = n;
    return st;
}

static td_status set_body(td_case_reader *r, const config_setting_t *g, void *rec)
{
    td_error merr;
    td_status st = td_model_set_housing_body(r->c->model, rec, &merr);
    return st == TD_OK ? TD_OK : td_cr_model_fail(r, g, st, &merr);
}

static const td_cs_key body_keys[] = {
    {.key = "mass",
     .type = TD_CS_REAL,
     .offset = offsetof(td_housing_body, mass),
     .need = TD_CS_REQUIRED,
     .what = "the housing's mass, kg",
     .range = TD_CR_POSITIVE,
     .unit = "kg",
     .doc = "mass of everything that moves with the housing (stator, retainers), the rotor not included: "
            "the coupled mass matrix adds it ([theory](theory.md#compliant-housing))"},
    {.key = "inertia",
     .type = TD_CS_REAL,
     .offset = offsetof(td_housing_body, inertia),
     .def = 0.0,
     .range = TD_CR_NONNEGATIVE,
     .unit = "kg m^2",
     .doc_default = "0 (the body only translates)",
     .doc = "transverse moment of inertia about the centre of mass: the body tilts (4 DOFs: x, y, theta, phi); "
            "0: it only translates (2 DOFs), its tilt held by the base"},
    {.key = "centre",
     .type = TD_CS_REAL,
     .offset = offsetof(td_housing_body, centre),
     .need = TD_CS_REQUIRED,
     .what = "the axial position of the housing's centre of mass, m",
     .unit = "m",
     .doc = "axial position z of the body's centre of mass, the point it tilts about"},
    {.key = "mounts",
     .type = TD_CS_LIST,
     .sub = &mount_table,
     .read = read_mounts,
     .need = TD_CS_REQUIRED,
     .what = "the housing's resilient mounts",
     .doc_range = "1.." BODY_XSTR(TD_HOUSING_MAX_MOUNTS) " entries",
     .doc = "the resilient mounts between the base and the body; with an inertia at two axial positions at least"},
};
const td_cs_table td_cs_housing_body = {"housing.body",          NULL, body_keys, TD_CS_COUNT(body_keys),
                                        sizeof(td_housing_body), NULL, set_body};
