/*
 * The tables of the machine's parts: discs, point masses, AMBs, plain bearings, retainers,
 * unbalances, the schedule of timed changes, the speed ramp and the spin. Each list entry is read
 * into a record of its own by its table and handed to the model by the table's finish, one
 * td_model_add_* call (case_schema.h). The model's rules
 * (value ranges, bore = shaft radius + clearance, nodes on the shaft, one AMB / retainer per
 * node, retainers tighter than the air gaps, schedule indices) are checked by the model alone:
 * its errors name part, index and field, which case_site.c turns back into the setting. The
 * reader checks what is about the file: types, missing and unknown keys, the forms a part may
 * take, units (bandwidth to tau) and the AMB gains' signs, which the model leaves free.
 */
#include "case/case_schema.h"
#include "util/error_internal.h"

#include <math.h>
#include <string.h>

#include "touchdown/dofs.h"

/* Here, in the lower of the two files whose tables use them (case_options.c: the run's contact). */
const char *const td_cr_damping_names[TD_CR_DAMPING_NAMES] = {"none", "hunt-crossley", "kelvin-voigt"};

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

/* A model error of adding a part, located at the entry g. */
static td_status added(td_case_reader *r, const config_setting_t *g, td_status st, const td_error *merr)
{
    return st == TD_OK ? TD_OK : td_cr_model_fail(r, g, st, merr);
}

/* discs[]: mass + Ip + Id, or the geometry (read with the `mass` key, in the disc's order). */
static td_status read_disc_form(td_case_reader *r, const config_setting_t *g, const td_cs_key *k, void *rec)
{
    static const char *const geometric[] = {"radius", "thickness", "density", "bore_radius", NULL};
    static const char *const inertial[] = {"Ip", "Id", NULL};
    const config_setting_t *geo = first_of(g, geometric);
    td_disc *d = rec;
    td_status st;
    (void)k;
    if (geo && first_of(g, inertial))
        return td_cr_fail(
            r, geo, NULL,
            "give either mass + Ip + Id or the geometry (radius + density + thickness or mass), not both");
    if (geo)
        return read_disc_geometry(r, g, d);
    st = td_cr_real(r, g, "mass", "disc mass, kg; or give radius + density + thickness", 0.0, TD_CR_FINITE, &d->mass);
    if (st == TD_OK)
        st = td_cr_real(r, g, "Ip", "polar moment of inertia, kg m^2", 0.0, TD_CR_FINITE, &d->Ip);
    if (st == TD_OK)
        st = td_cr_real(r, g, "Id", "diametral moment of inertia, kg m^2", 0.0, TD_CR_FINITE, &d->Id);
    return st;
}

static td_status add_disc(td_case_reader *r, const config_setting_t *g, void *rec)
{
    td_error merr;
    return added(r, g, td_model_add_disc(r->c->model, rec, &merr), &merr);
}

#define NODE_RANGE .lo = TD_CR_ANY_INT_LO, .hi = TD_CR_ANY_INT_HI
#define FORM .read = td_cs_elsewhere

static const td_cs_key disc_keys[] = {
    {.key = "node",
     .type = TD_CS_INT,
     .offset = offsetof(td_disc, node),
     .need = TD_CS_REQUIRED,
     NODE_RANGE,
     .what = "node the disc sits on",
     .doc = "node the disc sits on"},
    {.key = "mass",
     .type = TD_CS_REAL,
     .read = read_disc_form,
     .rule = TD_CR_POSITIVE,
     .doc_default = "required (inertia form); geometry form: instead of `thickness`",
     .unit = "kg",
     .doc = "mass"},
    {.key = "Ip",
     .type = TD_CS_REAL,
     FORM,
     .rule = TD_CR_NONNEGATIVE,
     .doc_default = "required (inertia form)",
     .unit = "kg m^2",
     .doc = "polar moment of inertia (about the spin axis)"},
    {.key = "Id",
     .type = TD_CS_REAL,
     FORM,
     .rule = TD_CR_NONNEGATIVE,
     .doc_default = "required (inertia form)",
     .unit = "kg m^2",
     .doc = "diametral moment of inertia (about a diameter through the centre of mass)"},
    {.key = "radius",
     .type = TD_CS_REAL,
     FORM,
     .rule = TD_CR_POSITIVE,
     .doc_default = "required (geometry form)",
     .unit = "m",
     .doc = "outer radius R"},
    {.key = "thickness",
     .type = TD_CS_REAL,
     FORM,
     .rule = TD_CR_POSITIVE,
     .doc_default = "required (geometry form) unless `mass` is given",
     .unit = "m",
     .doc = "axial thickness t"},
    {.key = "density",
     .type = TD_CS_REAL,
     FORM,
     .rule = TD_CR_POSITIVE,
     .doc_default = "required (geometry form)",
     .unit = "kg/m^3",
     .doc = "density"},
    {.key = "bore_radius",
     .type = TD_CS_REAL,
     FORM,
     .doc_range = ">= 0, < radius",
     .doc_default = "0",
     .unit = "m",
     .doc = "radius r of the bore (a disc shrunk on the shaft: the shaft is modelled separately)"},
};
const td_cs_table td_cs_discs = {"discs[]",       "discs", disc_keys, TD_CS_COUNT(disc_keys),
                                 sizeof(td_disc), NULL,    add_disc};

/* A point mass: a disc without rotary inertia (td_model_add_point_mass). */
typedef struct point_mass_rec {
    int node;
    double mass;
} point_mass_rec;

static td_status add_point_mass(td_case_reader *r, const config_setting_t *g, void *rec)
{
    const point_mass_rec *p = rec;
    td_error merr;
    return added(r, g, td_model_add_point_mass(r->c->model, p->node, p->mass, &merr), &merr);
}

static const td_cs_key point_mass_keys[] = {
    {.key = "node",
     .type = TD_CS_INT,
     .offset = offsetof(point_mass_rec, node),
     .need = TD_CS_REQUIRED,
     NODE_RANGE,
     .what = "node the mass sits on",
     .doc = "node of the mass"},
    {.key = "mass",
     .type = TD_CS_REAL,
     .offset = offsetof(point_mass_rec, mass),
     .need = TD_CS_REQUIRED,
     .rule = TD_CR_POSITIVE,
     .what = "mass, kg",
     .unit = "kg",
     .doc = "mass (no rotary inertia), e.g. AMB rotor laminations"},
};
const td_cs_table td_cs_point_masses = {"point_masses[]",       "discs", point_mass_keys, TD_CS_COUNT(point_mass_keys),
                                        sizeof(point_mass_rec), NULL,    add_point_mass};

/* tau, or bandwidth bw in Hz with tau = 1 / (2 pi bw); exactly one of them. */
static td_status read_amb_lag(td_case_reader *r, const config_setting_t *g, const td_cs_key *k, void *rec)
{
    const config_setting_t *t = config_setting_get_member(g, "tau");
    const config_setting_t *bw = config_setting_get_member(g, "bandwidth");
    double hz, *tau = &((td_amb *)rec)->tau;
    td_status st;
    (void)k;
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

/* The entry of the case's `controllers` that lists AMB entry g among its `ambs`, or NULL (an entry
 * written wrongly is no one's: case_control.c reports it when it reads it). */
static const config_setting_t *amb_driver(td_case_reader *r, const config_setting_t *g)
{
    const config_setting_t *list = config_setting_get_member(config_root_setting(&r->cfg), "controllers");
    int i, j, amb = config_setting_index(g);
    for (i = 0; list && config_setting_is_list(list) && i < config_setting_length(list); i++) {
        const config_setting_t *e = config_setting_get_elem(list, (unsigned)i);
        const config_setting_t *ambs = config_setting_is_group(e) ? config_setting_get_member(e, "ambs") : NULL;
        for (j = 0; ambs && config_setting_is_aggregate(ambs) && j < config_setting_length(ambs); j++)
            if (config_setting_type(config_setting_get_elem(ambs, (unsigned)j)) == CONFIG_TYPE_INT &&
                config_setting_get_int(config_setting_get_elem(ambs, (unsigned)j)) == amb)
                return e;
    }
    return NULL;
}

/* kp, kd and kint: the shorthand law's gains, required (kp, kd) unless a controller drives the AMB,
 * which replaces that law: then none of them may be written. */
static td_status read_amb_gain(td_case_reader *r, const config_setting_t *g, const td_cs_key *k, void *rec)
{
    const config_setting_t *driver = amb_driver(r, g);
    char key[256], where[1200];
    double *at = (double *)((unsigned char *)rec + k->offset);
    if (!driver)
        return td_cr_real(r, g, k->key, k->need == TD_CS_REQUIRED ? k->what : NULL, 0.0, k->range, at);
    *at = 0.0;
    if (!td_cr_has(g, k->key))
        return TD_OK;
    td_cr_key(driver, key, sizeof key);
    td_cr_where(r, driver, where, sizeof where);
    return td_cr_fail(r, config_setting_get_member(g, k->key), NULL,
                      "this AMB is driven by controller %s at %s, which replaces the kp, kd, kint law: leave %s out",
                      key, where, k->key);
}

static td_status add_amb(td_case_reader *r, const config_setting_t *g, void *rec)
{
    td_error merr;
    return added(r, g, td_model_add_amb(r->c->model, rec, &merr), &merr);
}

static const td_cs_key amb_keys[] = {
    {.key = "node",
     .type = TD_CS_INT,
     .offset = offsetof(td_amb, node),
     .need = TD_CS_REQUIRED,
     NODE_RANGE,
     .what = "actuator node",
     .doc = "actuator node"},
    {.key = "sensor_node",
     .type = TD_CS_INT,
     .offset = offsetof(td_amb, sensor_node),
     .need = TD_CS_SAME_AS,
     .def_from = offsetof(td_amb, node),
     NODE_RANGE,
     .doc_default = "`node`",
     .doc = "sensor node (collocated when equal)"},
    {.key = "ks",
     .type = TD_CS_REAL,
     .offset = offsetof(td_amb, ks),
     .need = TD_CS_REQUIRED,
     .range = TD_CR_NONNEGATIVE,
     .what = "negative-stiffness coefficient, N/m",
     .unit = "N/m",
     .doc = "negative-stiffness coefficient of the magnet"},
    {.key = "ki",
     .type = TD_CS_REAL,
     .offset = offsetof(td_amb, ki),
     .need = TD_CS_REQUIRED,
     .range = TD_CR_POSITIVE,
     .what = "force/current gain, N/A",
     .unit = "N/A",
     .doc = "force/current gain"},
    {.key = "kp",
     .type = TD_CS_REAL,
     .offset = offsetof(td_amb, kp),
     .need = TD_CS_REQUIRED,
     .read = read_amb_gain,
     .range = TD_CR_NONNEGATIVE,
     .what = "proportional gain, A/m; left out when a controller drives the AMB",
     .doc_default = "required, unless a controller drives the AMB (then not written)",
     .unit = "A/m",
     .doc = "proportional gain"},
    {.key = "kd",
     .type = TD_CS_REAL,
     .offset = offsetof(td_amb, kd),
     .need = TD_CS_REQUIRED,
     .read = read_amb_gain,
     .range = TD_CR_NONNEGATIVE,
     .what = "derivative gain, A s/m; left out when a controller drives the AMB",
     .doc_default = "required, unless a controller drives the AMB (then not written)",
     .unit = "A s/m",
     .doc = "derivative gain"},
    {.key = "kint",
     .type = TD_CS_REAL,
     .offset = offsetof(td_amb, kint),
     .read = read_amb_gain,
     .range = TD_CR_NONNEGATIVE,
     .unit = "A/(m s)",
     .doc = "integral gain: 0 is PD (the paper's law); > 0 adds an integrator per axis that centres the rotor under a "
            "steady load (gravity); it holds while the AMB is off and stops while the force is clipped (`saturation`)"},
    {.key = "tau",
     .type = TD_CS_REAL,
     .read = read_amb_lag,
     .rule = TD_CR_NONNEGATIVE,
     .doc_default = "one of tau or bandwidth required",
     .unit = "s",
     .doc = "force lag time constant (0: no lag)"},
    {.key = "bandwidth",
     .type = TD_CS_REAL,
     FORM,
     .range = TD_CR_POSITIVE,
     .doc_default = "one of tau or bandwidth required",
     .unit = "Hz",
     .doc = "force bandwidth; tau = 1/(2 pi bandwidth)"},
    {.key = "force_capacity",
     .type = TD_CS_REAL,
     .offset = offsetof(td_amb, force_capacity),
     .need = TD_CS_REQUIRED,
     .rule = TD_CR_POSITIVE,
     .what = "force capacity per axis, N",
     .unit = "N",
     .doc = "largest force per axis"},
    {.key = "saturation",
     .type = TD_CS_BOOL,
     .offset = offsetof(td_amb, saturation),
     .doc = "clip the total axis force ks x + Fc at +-force_capacity (and stop the integrator against the clip)"},
    {.key = "air_gap",
     .type = TD_CS_REAL,
     .offset = offsetof(td_amb, air_gap),
     .range = TD_CR_POSITIVE,
     .doc_default = "unknown",
     .unit = "m",
     .doc = "radial air gap; every retainer clearance must be smaller than it"}, /* 0: unknown, no retainer check */
    {.key = "slew_rate",
     .type = TD_CS_REAL,
     .offset = offsetof(td_amb, slew_rate),
     .range = TD_CR_NONNEGATIVE,
     .unit = "A/s",
     .doc = "the amplifier's slew-rate limit (0: none): dFc/dt is clipped to +-ki slew_rate (needs a `bandwidth` or "
            "`tau` > 0; the integrator stops while the limit holds against it, as against `saturation`; a machine "
            "with a limit is integrated without the closed-form flight, as with `saturation`)"},
};
const td_cs_table td_cs_ambs = {"ambs[]", "ambs", amb_keys, TD_CS_COUNT(amb_keys), sizeof(td_amb), NULL, add_amb};

static td_status add_bearing(td_case_reader *r, const config_setting_t *g, void *rec)
{
    td_error merr;
    return added(r, g, td_model_add_bearing(r->c->model, rec, &merr), &merr);
}

static const td_cs_key bearing_keys[] = {
    {.key = "node",
     .type = TD_CS_INT,
     .offset = offsetof(td_bearing, node),
     .need = TD_CS_REQUIRED,
     NODE_RANGE,
     .what = "bearing node",
     .doc = "bearing node"},
    {.key = "kxx",
     .type = TD_CS_REAL,
     .offset = offsetof(td_bearing, kxx),
     .need = TD_CS_REQUIRED,
     .rule = TD_CR_NONNEGATIVE,
     .what = "stiffness along x, N/m",
     .unit = "N/m",
     .doc = "stiffness along x"},
    {.key = "kyy",
     .type = TD_CS_REAL,
     .offset = offsetof(td_bearing, kyy),
     .need = TD_CS_SAME_AS,
     .def_from = offsetof(td_bearing, kxx),
     .rule = TD_CR_NONNEGATIVE,
     .doc_default = "`kxx`",
     .unit = "N/m",
     .doc = "stiffness along y"},
    {.key = "cxx",
     .type = TD_CS_REAL,
     .offset = offsetof(td_bearing, cxx),
     .rule = TD_CR_NONNEGATIVE,
     .unit = "N s/m",
     .doc = "damping along x"},
    {.key = "cyy",
     .type = TD_CS_REAL,
     .offset = offsetof(td_bearing, cyy),
     .need = TD_CS_SAME_AS,
     .def_from = offsetof(td_bearing, cxx),
     .rule = TD_CR_NONNEGATIVE,
     .doc_default = "`cxx`",
     .unit = "N s/m",
     .doc = "damping along y"},
};
const td_cs_table td_cs_bearings = {"bearings[]",       "bearings", bearing_keys, TD_CS_COUNT(bearing_keys),
                                    sizeof(td_bearing), NULL,       add_bearing};

/* A retainer's race { inertia; drag_torque; drag_viscous; mass; } and mount { stiffness; damping; }
 * (model.h td_race: the model checks how they go together). */
static const td_cs_key race_keys[] = {
    {.key = "inertia",
     .type = TD_CS_REAL,
     .offset = offsetof(td_race, inertia),
     .rule = TD_CR_NONNEGATIVE,
     .unit = "kg m^2",
     .doc = "polar moment of inertia J of what turns with the race; > 0 makes Omega_b a state"},
    {.key = "drag_torque",
     .type = TD_CS_REAL,
     .offset = offsetof(td_race, drag_torque),
     .rule = TD_CR_NONNEGATIVE,
     .unit = "N m",
     .doc = "constant drag torque of the bearing (needs `inertia` > 0)"},
    {.key = "drag_viscous",
     .type = TD_CS_REAL,
     .offset = offsetof(td_race, drag_viscous),
     .rule = TD_CR_NONNEGATIVE,
     .unit = "N m s/rad",
     .doc = "viscous drag, torque per rad/s (needs `inertia` > 0)"},
    {.key = "mass",
     .type = TD_CS_REAL,
     .offset = offsetof(td_race, mass),
     .rule = TD_CR_NONNEGATIVE,
     .unit = "kg",
     .doc = "mass that moves on the mount (needs `mount.stiffness` > 0, which needs it)"},
};
static const td_cs_table race_table = {
    "retainers[].race", "retainer-parts", race_keys, TD_CS_COUNT(race_keys), sizeof(td_race), NULL, NULL};

static const td_cs_key mount_keys[] = {
    {.key = "stiffness",
     .type = TD_CS_REAL,
     .offset = offsetof(td_race, mount_stiffness),
     .need = TD_CS_REQUIRED,
     .rule = TD_CR_NONNEGATIVE,
     .what = "mount stiffness, N/m",
     .doc_default = "required in `mount`",
     .unit = "N/m",
     .doc = "isotropic radial stiffness of the mount (> 0 needs `race.mass` > 0)"},
    {.key = "damping",
     .type = TD_CS_REAL,
     .offset = offsetof(td_race, mount_damping),
     .rule = TD_CR_NONNEGATIVE,
     .unit = "N s/m",
     .doc = "radial damping of the mount"},
};
static const td_cs_table mount_table = {
    "retainers[].mount", "retainer-parts", mount_keys, TD_CS_COUNT(mount_keys), sizeof(td_race), NULL, NULL};

/* A retainer's own contact law (model.h td_retainer_contact), with the damping names of the run's
 * contact group. An exponent not written stays 0 (model.h: taken as 1), so the model's rule that
 * a law needs a stiffness never blames a value the case does not hold. */
static const td_cs_key retainer_contact_keys[] = {
    {.key = "stiffness",
     .type = TD_CS_REAL,
     .offset = offsetof(td_retainer_contact, stiffness),
     .need = TD_CS_REQUIRED,
     .rule = TD_CR_NONNEGATIVE,
     .what = "contact stiffness, N/m^exponent",
     .doc_default = "required in `contact`",
     .unit = "N/m^exponent",
     .doc = "contact stiffness Kc between shaft and race (> 0: this retainer's contact is compliant whatever the run's "
            "`contact.model`)"},
    {.key = "exponent",
     .type = TD_CS_REAL,
     .offset = offsetof(td_retainer_contact, exponent),
     .doc_range = "0 or >= 1",
     .doc_default = "0 (taken as 1)",
     .doc = "1 linear, 1.5 Hertzian; 0 (not written) is taken as 1"},
    {.key = "damping",
     .type = TD_CS_ENUM,
     .offset = offsetof(td_retainer_contact, damping),
     .names = td_cr_damping_names,
     .name_count = TD_CR_DAMPING_NAMES,
     .doc = "damping law, as the run's `contact.damping`"},
    {.key = "damping_coefficient",
     .type = TD_CS_REAL,
     .offset = offsetof(td_retainer_contact, damping_coefficient),
     .rule = TD_CR_NONNEGATIVE,
     .unit = "s/m or N s/m",
     .doc = "as the run's `contact.damping_coefficient`"},
};
static const td_cs_table retainer_contact_table = {"retainers[].contact",
                                                   "retainer-parts",
                                                   retainer_contact_keys,
                                                   TD_CS_COUNT(retainer_contact_keys),
                                                   sizeof(td_retainer_contact),
                                                   NULL,
                                                   NULL};

/* heat */
/* A retainer's thermal network (model.h td_retainer_thermal), checked as read; expansion absent:
 * TD_UNDEFINED, no growth reported. */
static const td_cs_key thermal_keys[] = {
    {.key = "race_capacity",
     .type = TD_CS_REAL,
     .offset = offsetof(td_retainer_thermal, race_capacity),
     .need = TD_CS_REQUIRED,
     .range = TD_CR_POSITIVE,
     .what = "heat capacity of the race node, J/K",
     .unit = "J/K",
     .doc = "heat capacity C_r of the race node (the races and balls)"},
    {.key = "housing_capacity",
     .type = TD_CS_REAL,
     .offset = offsetof(td_retainer_thermal, housing_capacity),
     .need = TD_CS_REQUIRED,
     .range = TD_CR_POSITIVE,
     .what = "heat capacity of the housing node, J/K",
     .unit = "J/K",
     .doc = "heat capacity C_h of the housing node"},
    {.key = "race_housing_conductance",
     .type = TD_CS_REAL,
     .offset = offsetof(td_retainer_thermal, race_housing_conductance),
     .need = TD_CS_REQUIRED,
     .range = TD_CR_POSITIVE,
     .what = "thermal conductance race to housing, W/K",
     .unit = "W/K",
     .doc = "thermal conductance G_rh from the race node to the housing node"},
    {.key = "housing_ambient_conductance",
     .type = TD_CS_REAL,
     .offset = offsetof(td_retainer_thermal, housing_ambient_conductance),
     .need = TD_CS_REQUIRED,
     .range = TD_CR_NONNEGATIVE,
     .what = "thermal conductance housing to ambient, W/K",
     .unit = "W/K",
     .doc = "thermal conductance G_ha from the housing to the ambient (0: insulated, no steady state)"},
    {.key = "expansion",
     .type = TD_CS_REAL,
     .offset = offsetof(td_retainer_thermal, expansion),
     .def = NAN,
     .range = TD_CR_NONNEGATIVE,
     .doc_default = "none (no growth reported)",
     .unit = "1/K",
     .doc = "linear thermal expansion coefficient alpha of the race: the bore's radial growth alpha R_b dT_r at the "
            "peak is reported (an output only: the clearance does not change)"},
};
static const td_cs_table thermal_table = {"retainers[].thermal",
                                          "retainer-parts",
                                          thermal_keys,
                                          TD_CS_COUNT(thermal_keys),
                                          sizeof(td_retainer_thermal),
                                          NULL,
                                          NULL};

/* bore_radius: absent, shaft_radius + clearance (the model's rule when given) */
static td_status read_bore_radius(td_case_reader *r, const config_setting_t *g, const td_cs_key *k, void *rec)
{
    td_retainer *ret = rec;
    return td_cr_real(r, g, k->key, NULL, ret->shaft_radius + ret->clearance, TD_CR_FINITE, &ret->bore_radius);
}

/* A retainer entry as read: the retainer, then the groups the model keeps beside it. */
typedef struct cr_retainer {
    td_retainer r; /* first: the keys' offsets are td_retainer's */
    /* the bearing's duty */
    td_retainer_bearing bearing;
    /* heat */
    td_retainer_thermal thermal; /* race_capacity 0: no `thermal` group */
} cr_retainer;

static td_status add_retainer(td_case_reader *r, const config_setting_t *g, void *rec)
{
    cr_retainer *c = rec;
    td_error merr;
    td_status st = added(r, g, td_model_add_retainer(r->c->model, &c->r, &merr), &merr);
    if (st == TD_OK)
        st = td_cr_set_retainer_bearing(r, g, &c->bearing);
    if (st == TD_OK && c->thermal.race_capacity > 0.0) /* heat */
        st = added(
            r, g,
            td_model_set_retainer_thermal(r->c->model, td_model_retainer_count(r->c->model) - 1, &c->thermal, &merr),
            &merr);
    return st;
}

static const td_cs_key retainer_keys[] = {
    {.key = "node",
     .type = TD_CS_INT,
     .offset = offsetof(td_retainer, node),
     .need = TD_CS_REQUIRED,
     NODE_RANGE,
     .what = "retainer node",
     .doc = "retainer node"},
    {.key = "clearance",
     .type = TD_CS_REAL,
     .offset = offsetof(td_retainer, clearance),
     .need = TD_CS_REQUIRED,
     .rule = TD_CR_POSITIVE,
     .what = "radial clearance, m",
     .unit = "m",
     .doc = "radial clearance c"},
    {.key = "shaft_radius",
     .type = TD_CS_REAL,
     .offset = offsetof(td_retainer, shaft_radius),
     .need = TD_CS_REQUIRED,
     .rule = TD_CR_POSITIVE,
     .what = "shaft radius at the retainer, m",
     .unit = "m",
     .doc = "shaft radius R_s at the retainer (enters the sliding velocity, eq. 16)"},
    {.key = "bore_radius",
     .type = TD_CS_REAL,
     .read = read_bore_radius,
     .rule = TD_CR_POSITIVE,
     .doc_default = "`shaft_radius + clearance`",
     .unit = "m",
     .doc = "bore radius R_b; if given it must equal shaft_radius + clearance"},
    {.key = "friction",
     .type = TD_CS_REAL,
     .offset = offsetof(td_retainer, friction),
     .need = TD_CS_REQUIRED,
     .rule = TD_CR_NONNEGATIVE,
     .what = "Coulomb friction coefficient",
     .doc = "Coulomb friction coefficient mu (eq. 17)"},
    {.key = "bore_speed",
     .type = TD_CS_REAL,
     .offset = offsetof(td_retainer, bore_speed),
     .unit = "rad/s",
     .doc = "rotation speed Omega_b of the bore (0: housing not rotating)"},
    {.key = "restitution",
     .type = TD_CS_REAL,
     .offset = offsetof(td_retainer, restitution),
     .rule = TD_CR_FRACTION,
     .doc = "coefficient of restitution e of the impact (0: plastic)"},
    {.key = "stick",
     .type = TD_CS_BOOL,
     .offset = offsetof(td_retainer, stick),
     .doc =
         "Coulomb friction with sticking: rolling without slip (v_s = 0) is a state, held while the friction force it "
         "needs stays within mu N ([theory](theory.md#stick-rolling-without-slip-as-a-state-retainersstick--true)); "
         "false: the paper's sliding law (eq. 17) with its slip band. Needs `friction` > 0"},
    {.key = "race",
     .type = TD_CS_GROUP,
     .offset = offsetof(td_retainer, race),
     .sub = &race_table,
     .doc = "the inner race as a body, below (none: the paper's rigid bore, fixed in the housing)"},
    {.key = "mount",
     .type = TD_CS_GROUP,
     .offset = offsetof(td_retainer, race),
     .sub = &mount_table,
     .doc = "the race's mount to the housing, below (none: rigid)"},
    {.key = "contact",
     .type = TD_CS_GROUP,
     .offset = offsetof(td_retainer, contact),
     .sub = &retainer_contact_table,
     .doc_default = "the run's `contact`",
     .doc = "the retainer's own compliant contact law, below"},
    /* the bearing's duty */
    {.key = "bearing",
     .type = TD_CS_GROUP,
     .offset = offsetof(cr_retainer, bearing),
     .sub = &td_cs_retainer_bearing,
     .doc_default = "none",
     .doc = "the rolling bearing, for its assessment (ratings, ball geometry, width), below; it changes nothing in "
            "the run"},
    /* heat */
    {.key = "thermal",
     .type = TD_CS_GROUP,
     .offset = offsetof(cr_retainer, thermal),
     .sub = &thermal_table,
     .doc_default = "none (no temperatures)",
     .doc = "the race-housing-ambient thermal network heated by the retainer's friction and drag, below "
            "([theory](theory.md#thermal-retainers))"},
};
const td_cs_table td_cs_retainers = {"retainers[]",       "retainers", retainer_keys, TD_CS_COUNT(retainer_keys),
                                     sizeof(cr_retainer), NULL,        add_retainer};

static td_status add_unbalance(td_case_reader *r, const config_setting_t *g, void *rec)
{
    td_error merr;
    return added(r, g, td_model_add_unbalance(r->c->model, rec, &merr), &merr);
}

static const td_cs_key unbalance_keys[] = {
    {.key = "node",
     .type = TD_CS_INT,
     .offset = offsetof(td_unbalance, node),
     .need = TD_CS_REQUIRED,
     NODE_RANGE,
     .what = "unbalance node",
     .doc = "node of the unbalance"},
    {.key = "magnitude",
     .type = TD_CS_REAL,
     .offset = offsetof(td_unbalance, magnitude),
     .need = TD_CS_REQUIRED,
     .rule = TD_CR_NONNEGATIVE,
     .what = "unbalance U, kg m",
     .unit = "kg m",
     .doc = "U at t = 0"},
    {.key = "phase", .type = TD_CS_REAL, .offset = offsetof(td_unbalance, phase), .unit = "rad", .doc = "phase"},
};
const td_cs_table td_cs_unbalances = {"unbalances[]",       "unbalances", unbalance_keys, TD_CS_COUNT(unbalance_keys),
                                      sizeof(td_unbalance), NULL,         add_unbalance};

/* What a schedule entry changes: unbalance = INDEX with its magnitude and phase, amb_off = INDEX
 * or amb_on = INDEX (read with the `unbalance` key). */
static td_status read_change_kind(td_case_reader *r, const config_setting_t *g, const td_cs_key *k, void *rec)
{
    static const char *const kinds[] = {"unbalance", "amb_off", "amb_on", NULL};
    static const char *const unbalance_only[] = {"magnitude", "phase", NULL};
    const config_setting_t *kind = NULL, *extra;
    td_change *c = rec;
    td_unbalance u;
    int i;
    td_status st;
    (void)k;
    for (i = 0; kinds[i]; i++) {
        const config_setting_t *s = config_setting_get_member(g, kinds[i]);
        if (s && kind)
            return td_cr_fail(r, s, NULL, "a schedule entry makes one change: unbalance, amb_off or amb_on");
        if (s) {
            kind = s;
            c->kind = i == 0 ? TD_CHANGE_UNBALANCE : i == 1 ? TD_CHANGE_AMB_OFF : TD_CHANGE_AMB_ON;
        }
    }
    if (!kind)
        return td_cr_missing(r, g, "unbalance", "what changes: unbalance = INDEX, amb_off = INDEX or amb_on = INDEX");
    /* an unbalance or AMB that exists: the model's rule (td_model_validate) */
    st = td_cr_value_int(r, kind, TD_CR_ANY_INT_LO, TD_CR_ANY_INT_HI, &c->index);
    if (st != TD_OK || c->kind != TD_CHANGE_UNBALANCE)
        return st == TD_OK && (extra = first_of(g, unbalance_only)) != NULL
                   ? td_cr_fail(r, extra, NULL, "only an unbalance change takes a magnitude or phase")
                   : st;
    u.phase = 0.0; /* unbalance c->index may not exist; td_model_validate says so */
    td_model_get_unbalance(r->c->model, c->index, &u);
    st = td_cr_real(r, g, "magnitude", "new unbalance U, kg m", 0.0, TD_CR_FINITE, &c->magnitude);
    if (st == TD_OK)
        st = td_cr_real(r, g, "phase", NULL, u.phase, TD_CR_FINITE, &c->phase);
    return st;
}

static td_status add_change(td_case_reader *r, const config_setting_t *g, void *rec)
{
    td_error merr;
    return added(r, g, td_model_add_change(r->c->model, rec, &merr), &merr);
}

static const td_cs_key change_keys[] = {
    {.key = "time",
     .type = TD_CS_REAL,
     .offset = offsetof(td_change, time),
     .need = TD_CS_REQUIRED,
     .rule = TD_CR_NONNEGATIVE,
     .what = "time of the change, s",
     .unit = "s",
     .doc = "time of the change"},
    {.key = "unbalance",
     .type = TD_CS_INT,
     .read = read_change_kind,
     NODE_RANGE,
     .doc_default = "-",
     .doc = "index of the unbalance that changes (from 0, in the order of `unbalances`)"},
    {.key = "magnitude",
     .type = TD_CS_REAL,
     FORM,
     .rule = TD_CR_NONNEGATIVE,
     .doc_default = "required with `unbalance`",
     .unit = "kg m",
     .doc = "its new magnitude U"},
    {.key = "phase",
     .type = TD_CS_REAL,
     FORM,
     .doc_default = "the unbalance's `phase`",
     .unit = "rad",
     .doc = "its new phase"},
    {.key = "amb_off",
     .type = TD_CS_INT,
     FORM,
     NODE_RANGE,
     .doc_default = "-",
     .doc = "index of an AMB that fails: its forces drop to zero"},
    {.key = "amb_on",
     .type = TD_CS_INT,
     FORM,
     NODE_RANGE,
     .doc_default = "-",
     .doc = "index of an AMB that is restored"},
};
const td_cs_table td_cs_schedule = {"schedule[]",      "schedule", change_keys, TD_CS_COUNT(change_keys),
                                    sizeof(td_change), NULL,       add_change};

static td_status add_speed_point(td_case_reader *r, const config_setting_t *g, void *rec)
{
    td_error merr;
    return added(r, g, td_model_add_speed_point(r->c->model, rec, &merr), &merr);
}

static const td_cs_key speed_point_keys[] = {
    {.key = "time",
     .type = TD_CS_REAL,
     .offset = offsetof(td_speed_point, time),
     .need = TD_CS_REQUIRED,
     .rule = TD_CR_NONNEGATIVE,
     .doc_range = ">= 0, increasing",
     .what = "time of the point, s",
     .unit = "s",
     .doc = "time of the point"},
    {.key = "speed",
     .type = TD_CS_REAL,
     .offset = offsetof(td_speed_point, speed),
     .need = TD_CS_REQUIRED,
     .rule = TD_CR_NONNEGATIVE,
     .what = "rotor speed at that time, rad/s",
     .unit = "rad/s",
     .doc = "speed at that time: linear between points, `speed` before the first, the last point's after it; the "
            "integrator stops at every point. A first point after time 0 must be at `speed` (else the speed would step "
            "there: refused); one at time 0 starts the run at its speed. The run's work bounds (touchdown/limits.h) "
            "take the highest speed reached up to `end_time`"},
};
const td_cs_table td_cs_speed_ramp = {"speed_ramp[]",         "speed", speed_point_keys, TD_CS_COUNT(speed_point_keys),
                                      sizeof(td_speed_point), NULL,    add_speed_point};

static td_status set_spin(td_case_reader *r, const config_setting_t *g, void *rec)
{
    td_error merr;
    return added(r, g, td_model_set_spin(r->c->model, rec, &merr), &merr);
}

static const td_cs_key spin_keys[] = {
    {.key = "free",
     .type = TD_CS_BOOL,
     .offset = offsetof(td_spin, free),
     .doc = "`true`: the speed is a state starting at `speed`, J dOmega/dt = drive_torque - drag_torque sgn(Omega) - "
            "drag_viscous Omega - sum R_s F_t"},
    {.key = "inertia",
     .type = TD_CS_REAL,
     .offset = offsetof(td_spin, inertia),
     .rule = TD_CR_NONNEGATIVE,
     .doc_default = "the rotor's",
     .unit = "kg m^2",
     .doc = "polar moment of inertia J (0: shaft elements and discs, `td_model_polar_inertia`, printed by `touchdown "
            "info`)"},
    {.key = "drive_torque",
     .type = TD_CS_REAL,
     .offset = offsetof(td_spin, drive_torque),
     .unit = "N m",
     .doc = "constant torque along the spin (a motor; 0 after a trip)"},
    {.key = "drag_torque",
     .type = TD_CS_REAL,
     .offset = offsetof(td_spin, drag_torque),
     .rule = TD_CR_NONNEGATIVE,
     .unit = "N m",
     .doc = "constant drag (seals, windage, motor losses), regularised over 0.01 rad/s at standstill"},
    {.key = "drag_viscous",
     .type = TD_CS_REAL,
     .offset = offsetof(td_spin, drag_viscous),
     .rule = TD_CR_NONNEGATIVE,
     .unit = "N m s/rad",
     .doc = "viscous drag"},
};
const td_cs_table td_cs_spin = {"spin", "speed", spin_keys, TD_CS_COUNT(spin_keys), sizeof(td_spin), NULL, set_spin};
