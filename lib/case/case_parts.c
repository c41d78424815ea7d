/*
 * The machine's parts: discs, point masses, AMBs, plain bearings, retainers, unbalances and the
 * schedule of timed changes. Each list entry becomes one td_model_add_* call. The model's rules
 * (value ranges, bore = shaft radius + clearance, nodes on the shaft, one AMB / retainer per
 * node, retainers tighter than the air gaps, schedule indices) are checked by the model alone:
 * its errors name part, index and field, which case_site.c turns back into the setting. The
 * reader checks what is about the file: types, missing and unknown keys, the forms a part may
 * take, units (bandwidth to tau) and the AMB gains' signs, which the model leaves free.
 */
#include "case/case_internal.h"
#include "util/error_internal.h"

#include <math.h>
#include <string.h>

#include "touchdown/dofs.h"

static const char *const disc_keys[] = {"node",      "mass",    "Ip",          "Id", "radius",
                                        "thickness", "density", "bore_radius", NULL};
static const char *const point_mass_keys[] = {"node", "mass", NULL};
static const char *const amb_keys[] = {"node",       "sensor_node", "ks",  "ki",        "kp",
                                       "kd",         "kint",        "tau", "bandwidth", "force_capacity",
                                       "saturation", "air_gap",     NULL};
static const char *const bearing_keys[] = {"node", "kxx", "kyy", "cxx", "cyy", NULL};
static const char *const retainer_keys[] = {"node",     "clearance",  "shaft_radius", "bore_radius",
                                            "friction", "bore_speed", "restitution",  "stick",
                                            "race",     "mount",      "contact",      NULL};
static const char *const race_keys[] = {"inertia", "drag_torque", "drag_viscous", "mass", NULL};
static const char *const mount_keys[] = {"stiffness", "damping", NULL};
static const char *const retainer_contact_keys[] = {"stiffness", "exponent", "damping", "damping_coefficient", NULL};
static const char *const unbalance_keys[] = {"node", "magnitude", "phase", NULL};
static const char *const speed_point_keys[] = {"time", "speed", NULL};
static const char *const spin_keys[] = {"free", "inertia", "drive_torque", "drag_torque", "drag_viscous", NULL};
static const char *const change_keys[] = {"time", "unbalance", "magnitude", "phase", "amb_off", "amb_on", NULL};

/* The first member of g among the NULL-terminated keys, or NULL. */
static const config_setting_t *first_of(const config_setting_t *g, const char *const *keys)
{
    int i;
    for (i = 0; keys[i]; i++)
        if (config_setting_get_member(g, keys[i]))
            return config_setting_get_member(g, keys[i]);
    return NULL;
}

/* A disc given by its geometry: radius, density, optional bore_radius, and thickness or mass
 * (the thickness of a disc of that mass); td_disc_from_geometry computes mass and inertias. */
static td_status read_disc_geometry(td_case_reader *r, const config_setting_t *g, td_disc *d)
{
    const config_setting_t *t = config_setting_get_member(g, "thickness");
    const config_setting_t *m = config_setting_get_member(g, "mass");
    td_disc_geometry geo;
    td_error merr;
    td_status st;
    memset(&geo, 0, sizeof geo);
    geo.node = d->node;
    st = td_cr_real(r, g, "radius", "outer radius, m", 0.0, TD_CR_FINITE, &geo.outer_radius);
    if (st == TD_OK)
        st = td_cr_real(r, g, "density", "density, kg/m^3", 0.0, TD_CR_FINITE, &geo.density);
    if (st == TD_OK)
        st = td_cr_real(r, g, "bore_radius", NULL, 0.0, TD_CR_FINITE, &geo.inner_radius);
    /* 0 stands for "not given" in td_disc_geometry: a value written in the file must be > 0 */
    if (st == TD_OK && m)
        st = td_cr_value_real(r, m, TD_CR_POSITIVE, &geo.mass);
    if (st == TD_OK && (t || !m))
        st = td_cr_real(r, g, "thickness", "axial thickness, m; or the mass, kg", 0.0, TD_CR_POSITIVE, &geo.thickness);
    if (st != TD_OK)
        return st;
    st = td_disc_from_geometry(&geo, d, &merr);
    if (st != TD_OK)
        return td_cr_model_fail(r, g, st, &merr);
    /* the radius is the factor squared twice over; the largest inertia overflows first */
    return td_cr_derived(r, config_setting_get_member(g, "radius"), d->Id > d->Ip ? d->Id : d->Ip,
                         "the disc inertia from radius, thickness (or mass) and density");
}

static td_status read_disc(td_case_reader *r, const config_setting_t *g)
{
    static const char *const geometric[] = {"radius", "thickness", "density", "bore_radius", NULL};
    static const char *const inertial[] = {"Ip", "Id", NULL};
    const config_setting_t *geo;
    td_disc d;
    td_error merr;
    td_status st = td_cr_check_keys(r, g, disc_keys);
    if (st == TD_OK)
        st = td_cr_node(r, g, "node", "node the disc sits on", 0, &d.node);
    if (st != TD_OK)
        return st;
    geo = first_of(g, geometric);
    if (geo && first_of(g, inertial))
        return td_cr_fail(
            r, geo, NULL,
            "give either mass + Ip + Id or the geometry (radius + density + thickness or mass), not both");
    if (geo) {
        st = read_disc_geometry(r, g, &d);
    } else {
        st =
            td_cr_real(r, g, "mass", "disc mass, kg; or give radius + density + thickness", 0.0, TD_CR_FINITE, &d.mass);
        if (st == TD_OK)
            st = td_cr_real(r, g, "Ip", "polar moment of inertia, kg m^2", 0.0, TD_CR_FINITE, &d.Ip);
        if (st == TD_OK)
            st = td_cr_real(r, g, "Id", "diametral moment of inertia, kg m^2", 0.0, TD_CR_FINITE, &d.Id);
    }
    if (st != TD_OK)
        return st;
    st = td_model_add_disc(r->c->model, &d, &merr);
    return st == TD_OK ? TD_OK : td_cr_model_fail(r, g, st, &merr);
}

static td_status read_point_mass(td_case_reader *r, const config_setting_t *g)
{
    int node;
    double mass;
    td_error merr;
    td_status st = td_cr_check_keys(r, g, point_mass_keys);
    if (st == TD_OK)
        st = td_cr_node(r, g, "node", "node the mass sits on", 0, &node);
    if (st == TD_OK)
        st = td_cr_real(r, g, "mass", "mass, kg", 0.0, TD_CR_FINITE, &mass);
    if (st != TD_OK)
        return st;
    st = td_model_add_point_mass(r->c->model, node, mass, &merr);
    return st == TD_OK ? TD_OK : td_cr_model_fail(r, g, st, &merr);
}

/* tau, or bandwidth bw in Hz with tau = 1 / (2 pi bw); exactly one of them. */
static td_status read_amb_lag(td_case_reader *r, const config_setting_t *g, double *tau)
{
    const config_setting_t *t = config_setting_get_member(g, "tau");
    const config_setting_t *bw = config_setting_get_member(g, "bandwidth");
    double hz;
    td_status st;
    if (t && bw)
        return td_cr_fail(r, bw, NULL, "give either tau or bandwidth, not both");
    if (t)
        return td_cr_value_real(r, t, TD_CR_FINITE, tau);
    if (!bw)
        return td_cr_missing(r, g, "bandwidth", "force bandwidth, Hz; or give the time constant tau, s");
    st = td_cr_value_real(r, bw, TD_CR_POSITIVE, &hz);
    if (st == TD_OK)
        *tau = 1.0 / (2.0 * TD_PI * hz);
    return st == TD_OK ? td_cr_derived(r, bw, *tau, "the time constant tau = 1 / (2 pi bandwidth)") : st;
}

static td_status read_amb(td_case_reader *r, const config_setting_t *g)
{
    td_amb a;
    td_error merr;
    td_status st = td_cr_check_keys(r, g, amb_keys);
    if (st == TD_OK)
        st = td_cr_node(r, g, "node", "actuator node", 0, &a.node);
    if (st == TD_OK)
        st = td_cr_node(r, g, "sensor_node", NULL, a.node, &a.sensor_node);
    if (st == TD_OK)
        st = td_cr_real(r, g, "ks", "negative-stiffness coefficient, N/m", 0.0, TD_CR_NONNEGATIVE, &a.ks);
    if (st == TD_OK)
        st = td_cr_real(r, g, "ki", "force/current gain, N/A", 0.0, TD_CR_POSITIVE, &a.ki);
    if (st == TD_OK)
        st = td_cr_real(r, g, "kp", "proportional gain, A/m", 0.0, TD_CR_NONNEGATIVE, &a.kp);
    if (st == TD_OK)
        st = td_cr_real(r, g, "kd", "derivative gain, A s/m", 0.0, TD_CR_NONNEGATIVE, &a.kd);
    if (st == TD_OK)
        st = td_cr_real(r, g, "kint", NULL, 0.0, TD_CR_NONNEGATIVE, &a.kint);
    if (st == TD_OK)
        st = read_amb_lag(r, g, &a.tau);
    if (st == TD_OK)
        st = td_cr_real(r, g, "force_capacity", "force capacity per axis, N", 0.0, TD_CR_FINITE, &a.force_capacity);
    if (st == TD_OK)
        st = td_cr_bool(r, g, "saturation", 0, &a.saturation);
    a.air_gap = 0.0; /* absent: unknown, no retainer check */
    if (st == TD_OK && td_cr_has(g, "air_gap"))
        st = td_cr_real(r, g, "air_gap", NULL, 0.0, TD_CR_POSITIVE, &a.air_gap);
    if (st != TD_OK)
        return st;
    st = td_model_add_amb(r->c->model, &a, &merr);
    return st == TD_OK ? TD_OK : td_cr_model_fail(r, g, st, &merr);
}

static td_status read_bearing(td_case_reader *r, const config_setting_t *g)
{
    td_bearing b;
    td_error merr;
    td_status st = td_cr_check_keys(r, g, bearing_keys);
    if (st == TD_OK)
        st = td_cr_node(r, g, "node", "bearing node", 0, &b.node);
    if (st == TD_OK)
        st = td_cr_real(r, g, "kxx", "stiffness along x, N/m", 0.0, TD_CR_FINITE, &b.kxx);
    if (st == TD_OK)
        st = td_cr_real(r, g, "kyy", NULL, b.kxx, TD_CR_FINITE, &b.kyy);
    if (st == TD_OK)
        st = td_cr_real(r, g, "cxx", NULL, 0.0, TD_CR_FINITE, &b.cxx);
    if (st == TD_OK)
        st = td_cr_real(r, g, "cyy", NULL, b.cxx, TD_CR_FINITE, &b.cyy);
    if (st != TD_OK)
        return st;
    st = td_model_add_bearing(r->c->model, &b, &merr);
    return st == TD_OK ? TD_OK : td_cr_model_fail(r, g, st, &merr);
}

/* A retainer's race { inertia; drag_torque; drag_viscous; mass; } and mount { stiffness; damping; }
 * (model.h td_race: the model checks how they go together). */
static td_status read_race(td_case_reader *r, const config_setting_t *g, td_race *b)
{
    const config_setting_t *race, *mount;
    td_status st = td_cr_group(r, g, "race", NULL, &race);
    if (st == TD_OK && race) {
        st = td_cr_check_keys(r, race, race_keys);
        if (st == TD_OK)
            st = td_cr_real(r, race, "inertia", NULL, 0.0, TD_CR_FINITE, &b->inertia);
        if (st == TD_OK)
            st = td_cr_real(r, race, "drag_torque", NULL, 0.0, TD_CR_FINITE, &b->drag_torque);
        if (st == TD_OK)
            st = td_cr_real(r, race, "drag_viscous", NULL, 0.0, TD_CR_FINITE, &b->drag_viscous);
        if (st == TD_OK)
            st = td_cr_real(r, race, "mass", NULL, 0.0, TD_CR_FINITE, &b->mass);
    }
    if (st == TD_OK)
        st = td_cr_group(r, g, "mount", NULL, &mount);
    if (st == TD_OK && mount) {
        st = td_cr_check_keys(r, mount, mount_keys);
        if (st == TD_OK)
            st = td_cr_real(r, mount, "stiffness", "mount stiffness, N/m", 0.0, TD_CR_FINITE, &b->mount_stiffness);
        if (st == TD_OK)
            st = td_cr_real(r, mount, "damping", NULL, 0.0, TD_CR_FINITE, &b->mount_damping);
    }
    return st;
}

/* A retainer's own contact law { stiffness; exponent; damping; damping_coefficient; } (model.h
 * td_retainer_contact), with the damping names of the run's contact group. */
static td_status read_retainer_contact(td_case_reader *r, const config_setting_t *g, td_retainer_contact *c)
{
    const config_setting_t *cg;
    int damping = 0;
    td_status st = td_cr_group(r, g, "contact", NULL, &cg);
    if (st != TD_OK || !cg)
        return st;
    st = td_cr_check_keys(r, cg, retainer_contact_keys);
    if (st == TD_OK)
        st = td_cr_real(r, cg, "stiffness", "contact stiffness, N/m^exponent", 0.0, TD_CR_FINITE, &c->stiffness);
    /* an exponent not written stays 0 (model.h: taken as 1), so the model's rule that a law needs a
     * stiffness never blames a value the case does not hold */
    if (st == TD_OK)
        st = td_cr_real(r, cg, "exponent", NULL, 0.0, TD_CR_FINITE, &c->exponent);
    if (st == TD_OK)
        st = td_cr_enum(r, cg, "damping", td_cr_damping_names, TD_CR_DAMPING_NAMES, 0, &damping);
    if (st == TD_OK)
        st = td_cr_real(r, cg, "damping_coefficient", NULL, 0.0, TD_CR_FINITE, &c->damping_coefficient);
    c->damping = (td_contact_damping)damping;
    return st;
}

static td_status read_retainer(td_case_reader *r, const config_setting_t *g)
{
    td_retainer ret = {0};
    td_error merr;
    td_status st = td_cr_check_keys(r, g, retainer_keys);
    if (st == TD_OK)
        st = td_cr_node(r, g, "node", "retainer node", 0, &ret.node);
    if (st == TD_OK)
        st = td_cr_real(r, g, "clearance", "radial clearance, m", 0.0, TD_CR_FINITE, &ret.clearance);
    if (st == TD_OK)
        st = td_cr_real(r, g, "shaft_radius", "shaft radius at the retainer, m", 0.0, TD_CR_FINITE, &ret.shaft_radius);
    if (st == TD_OK)
        st = td_cr_real(r, g, "bore_radius", NULL, ret.shaft_radius + ret.clearance, TD_CR_FINITE, &ret.bore_radius);
    if (st == TD_OK)
        st = td_cr_real(r, g, "friction", "Coulomb friction coefficient", 0.0, TD_CR_FINITE, &ret.friction);
    if (st == TD_OK)
        st = td_cr_real(r, g, "bore_speed", NULL, 0.0, TD_CR_FINITE, &ret.bore_speed);
    if (st == TD_OK)
        st = td_cr_real(r, g, "restitution", NULL, 0.0, TD_CR_FINITE, &ret.restitution);
    if (st == TD_OK)
        st = td_cr_bool(r, g, "stick", 0, &ret.stick);
    if (st == TD_OK)
        st = read_race(r, g, &ret.race);
    if (st == TD_OK)
        st = read_retainer_contact(r, g, &ret.contact);
    if (st != TD_OK)
        return st;
    st = td_model_add_retainer(r->c->model, &ret, &merr);
    return st == TD_OK ? TD_OK : td_cr_model_fail(r, g, st, &merr);
}

static td_status read_unbalance(td_case_reader *r, const config_setting_t *g)
{
    td_unbalance u;
    td_error merr;
    td_status st = td_cr_check_keys(r, g, unbalance_keys);
    if (st == TD_OK)
        st = td_cr_node(r, g, "node", "unbalance node", 0, &u.node);
    if (st == TD_OK)
        st = td_cr_real(r, g, "magnitude", "unbalance U, kg m", 0.0, TD_CR_FINITE, &u.magnitude);
    if (st == TD_OK)
        st = td_cr_real(r, g, "phase", NULL, 0.0, TD_CR_FINITE, &u.phase);
    if (st != TD_OK)
        return st;
    st = td_model_add_unbalance(r->c->model, &u, &merr);
    return st == TD_OK ? TD_OK : td_cr_model_fail(r, g, st, &merr);
}

/* One entry of "schedule": { time; unbalance; magnitude; phase; } or { time; amb_off; } or { time; amb_on; } */
static td_status read_change(td_case_reader *r, const config_setting_t *g)
{
    static const char *const kinds[] = {"unbalance", "amb_off", "amb_on", NULL};
    static const char *const unbalance_only[] = {"magnitude", "phase", NULL};
    const config_setting_t *kind, *extra;
    td_change c;
    td_unbalance u;
    td_error merr;
    int k;
    td_status st = td_cr_check_keys(r, g, change_keys);
    if (st == TD_OK)
        st = td_cr_real(r, g, "time", "time of the change, s", 0.0, TD_CR_FINITE, &c.time);
    if (st != TD_OK)
        return st;
    for (k = 0, kind = NULL; kinds[k]; k++) {
        const config_setting_t *s = config_setting_get_member(g, kinds[k]);
        if (s && kind)
            return td_cr_fail(r, s, NULL, "a schedule entry makes one change: unbalance, amb_off or amb_on");
        if (s) {
            kind = s;
            c.kind = k == 0 ? TD_CHANGE_UNBALANCE : k == 1 ? TD_CHANGE_AMB_OFF : TD_CHANGE_AMB_ON;
        }
    }
    if (!kind)
        return td_cr_missing(r, g, "unbalance", "what changes: unbalance = INDEX, amb_off = INDEX or amb_on = INDEX");
    c.magnitude = 0.0;
    c.phase = 0.0;
    if (c.kind == TD_CHANGE_UNBALANCE) {
        /* an unbalance or AMB that exists: the model's rule (td_model_validate) */
        st = td_cr_value_int(r, kind, -2147483647L, 2147483647L, &c.index);
        if (st != TD_OK)
            return st;
        u.phase = 0.0; /* unbalance c.index may not exist; td_model_validate says so */
        td_model_get_unbalance(r->c->model, c.index, &u);
        st = td_cr_real(r, g, "magnitude", "new unbalance U, kg m", 0.0, TD_CR_FINITE, &c.magnitude);
        if (st == TD_OK)
            st = td_cr_real(r, g, "phase", NULL, u.phase, TD_CR_FINITE, &c.phase);
    } else {
        st = td_cr_value_int(r, kind, -2147483647L, 2147483647L, &c.index);
        if (st == TD_OK && (extra = first_of(g, unbalance_only)) != NULL)
            st = td_cr_fail(r, extra, NULL, "only an unbalance change takes a magnitude or phase");
    }
    if (st != TD_OK)
        return st;
    st = td_model_add_change(r->c->model, &c, &merr);
    return st == TD_OK ? TD_OK : td_cr_model_fail(r, g, st, &merr);
}

/* Read every entry of the list `key` with `one` (entries that are groups). */
static td_status read_each(td_case_reader *r, const config_setting_t *root, const char *key,
                           td_status (*one)(td_case_reader *, const config_setting_t *))
{
    const config_setting_t *list, *g;
    int i;
    td_status st = td_cr_list(r, root, key, &list);
    for (i = 0; st == TD_OK && list && i < config_setting_length(list); i++) {
        st = td_cr_entry(r, list, i, &g);
        if (st == TD_OK)
            st = one(r, g);
    }
    return st;
}

/* One entry of "speed_ramp": { time; speed; } */
static td_status read_speed_point(td_case_reader *r, const config_setting_t *g)
{
    td_speed_point p;
    td_error merr;
    td_status st = td_cr_check_keys(r, g, speed_point_keys);
    if (st == TD_OK)
        st = td_cr_real(r, g, "time", "time of the point, s", 0.0, TD_CR_FINITE, &p.time);
    if (st == TD_OK)
        st = td_cr_real(r, g, "speed", "rotor speed at that time, rad/s", 0.0, TD_CR_FINITE, &p.speed);
    if (st != TD_OK)
        return st;
    st = td_model_add_speed_point(r->c->model, &p, &merr);
    return st == TD_OK ? TD_OK : td_cr_model_fail(r, g, st, &merr);
}

/* The group "spin": { free; inertia; drive_torque; drag_torque; drag_viscous; } */
static td_status read_spin(td_case_reader *r, const config_setting_t *root)
{
    const config_setting_t *g;
    td_spin sp;
    td_error merr;
    td_status st = td_cr_group(r, root, "spin", NULL, &g);
    if (st != TD_OK || !g)
        return st;
    st = td_cr_check_keys(r, g, spin_keys);
    if (st == TD_OK)
        st = td_cr_bool(r, g, "free", 0, &sp.free);
    if (st == TD_OK)
        st = td_cr_real(r, g, "inertia", NULL, 0.0, TD_CR_FINITE, &sp.inertia);
    if (st == TD_OK)
        st = td_cr_real(r, g, "drive_torque", NULL, 0.0, TD_CR_FINITE, &sp.drive_torque);
    if (st == TD_OK)
        st = td_cr_real(r, g, "drag_torque", NULL, 0.0, TD_CR_FINITE, &sp.drag_torque);
    if (st == TD_OK)
        st = td_cr_real(r, g, "drag_viscous", NULL, 0.0, TD_CR_FINITE, &sp.drag_viscous);
    if (st != TD_OK)
        return st;
    st = td_model_set_spin(r->c->model, &sp, &merr);
    return st == TD_OK ? TD_OK : td_cr_model_fail(r, g, st, &merr);
}

/* Entry i of every list is part i of its kind (discs then point masses are the model's discs):
 * case_site.c relies on this order to find the setting a model error names. */
td_status td_cr_read_parts(td_case_reader *r, const config_setting_t *root)
{
    td_status st = read_each(r, root, "discs", read_disc);
    if (st == TD_OK)
        st = read_each(r, root, "point_masses", read_point_mass);
    if (st == TD_OK)
        st = read_each(r, root, "ambs", read_amb);
    if (st == TD_OK)
        st = read_each(r, root, "bearings", read_bearing);
    if (st == TD_OK)
        st = read_each(r, root, "retainers", read_retainer);
    if (st == TD_OK)
        st = read_each(r, root, "unbalances", read_unbalance);
    if (st == TD_OK)
        st = read_each(r, root, "schedule", read_change);
    if (st == TD_OK)
        st = read_each(r, root, "speed_ramp", read_speed_point);
    if (st == TD_OK)
        st = read_spin(r, root);
    return st;
}
