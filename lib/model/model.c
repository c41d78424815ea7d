/*
 * The machine description: growable arrays of parts, each validated as it is added.
 * Cross-references (node numbers, clearances against air gaps) wait for td_model_validate,
 * because parts may be added before the shaft is complete.
 */
#include "model/model_internal.h"
#include "touchdown/dofs.h"
#include "util/error_internal.h"

#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Append one item of `size` bytes to a part array; grows geometrically. */
static td_status part_append(void **items, int *count, int *capacity, size_t size, const void *item, td_error *err)
{
    if (*count == *capacity) {
        int cap = *capacity ? 2 * *capacity : 8;
        void *p = realloc(*items, (size_t)cap * size);
        if (!p)
            return td_error_set(err, TD_ERR_NOMEM, "out of memory adding a model part");
        *items = p;
        *capacity = cap;
    }
    memcpy((char *)*items + (size_t)*count * size, item, size);
    (*count)++;
    return TD_OK;
}

#define APPEND(arr, item, err)                                                                                         \
    part_append((void **)&(arr).items, &(arr).count, &(arr).capacity, sizeof *(arr).items, (item), (err))

static int finite_positive(double v)
{
    return isfinite(v) && v > 0.0;
}
static int finite_nonnegative(double v)
{
    return isfinite(v) && v >= 0.0;
}

static const td_error_site no_site = {NULL, 0, NULL};

/* Fail naming the part, its index and the field at fault ("PART INDEX: FIELD: ..."). */
#define FAIL_AT(err, part, index, field, ...)                                                                          \
    td_error_set_site((err), TD_ERR_INVALID, &(td_error_site){(part), (index), (field)}, &no_site, __VA_ARGS__)

/* TD_OK when ok; else fail naming the field and the rule its value breaks. */
static td_status need(int ok, td_error *err, const char *part, int index, const char *field, const char *rule, double v)
{
    return ok ? TD_OK : FAIL_AT(err, part, index, field, "must %s (got %g)", rule, v);
}

/* A node number of a part being added: at least 0 (the upper bound waits for td_model_validate). */
static td_status need_node(td_error *err, const char *part, int index, const char *field, int node)
{
    return node >= 0 ? TD_OK : FAIL_AT(err, part, index, field, "must be >= 0 (got %d)", node);
}

#define POS "be > 0"
#define NONNEG "be >= 0"

td_status td_model_create(td_model **out, td_error *err)
{
    td_model *m;
    if (!out)
        return td_error_set(err, TD_ERR_INVALID, "td_model_create: NULL output pointer");
    m = calloc(1, sizeof *m);
    if (!m)
        return td_error_set(err, TD_ERR_NOMEM, "out of memory creating a model");
    m->shaft.beam = TD_BEAM_EULER_BERNOULLI;
    m->shaft.mass = TD_MASS_CONSISTENT;
    *out = m;
    return TD_OK;
}

void td_model_free(td_model **model)
{
    td_model *m;
    if (!model || !*model)
        return;
    m = *model;
    free(m->elements.items);
    free(m->discs.items);
    free(m->ambs.items);
    free(m->bearings.items);
    free(m->retainers.items);
    free(m->unbalances.items);
    free(m->changes.items);
    free(m->change_entries.items);
    free(m->speed_points.items);
    free(m->thermals.items);
    td_model_free_controllers(m);
    td_model_free_assessment(m);
    td_model_free_housing(m);
    free(m);
    *model = NULL;
}

/* Duplicate `count` items of `size` bytes; NULL stays NULL. */
static void *dup_items(const void *items, int count, size_t size, int *ok)
{
    void *p;
    if (count == 0)
        return NULL;
    p = malloc((size_t)count * size);
    if (!p) {
        *ok = 0;
        return NULL;
    }
    memcpy(p, items, (size_t)count * size);
    return p;
}

#define CLONE(dst, src, ok)                                                                                            \
    do {                                                                                                               \
        (dst).items = dup_items((src).items, (src).count, sizeof *(src).items, &(ok));                                 \
        (dst).count = (dst).capacity = (src).count;                                                                    \
    } while (0)

td_status td_model_clone(const td_model *model, td_model **out, td_error *err)
{
    td_model *m;
    td_status st;
    int ok = 1;
    if (!model || !out)
        return td_error_set(err, TD_ERR_INVALID, "td_model_clone: NULL argument");
    m = calloc(1, sizeof *m);
    if (!m)
        return td_error_set(err, TD_ERR_NOMEM, "out of memory cloning a model");
    m->shaft = model->shaft;
    m->speed = model->speed;
    m->gravity[0] = model->gravity[0];
    m->gravity[1] = model->gravity[1];
    m->reduction_cutoff = model->reduction_cutoff;
    CLONE(m->elements, model->elements, ok);
    CLONE(m->discs, model->discs, ok);
    CLONE(m->ambs, model->ambs, ok);
    CLONE(m->bearings, model->bearings, ok);
    CLONE(m->retainers, model->retainers, ok);
    CLONE(m->unbalances, model->unbalances, ok);
    CLONE(m->changes, model->changes, ok);
    CLONE(m->change_entries, model->change_entries, ok);
    CLONE(m->speed_points, model->speed_points, ok);
    CLONE(m->thermals, model->thermals, ok);
    m->spin = model->spin;
    m->recovery = model->recovery;
    m->body = model->body;
    m->has_body = model->has_body;
    if (ok)
        ok = td_model_clone_assessment(m, model);
    if (ok)
        ok = td_model_clone_housing(m, model);
    if (!ok) {
        td_model_free(&m);
        return td_error_set(err, TD_ERR_NOMEM, "out of memory cloning a model");
    }
    st = td_model_clone_controllers(m, model, err);
    if (st != TD_OK) {
        td_model_free(&m);
        return st;
    }
    *out = m;
    return TD_OK;
}

#define REFINE_MAX_ELEMENTS (INT_MAX / 8)

/* Split every element of m's shaft into `factor` equal ones, in place. */
static td_status split_elements(td_model *m, int factor, td_error *err)
{
    int count = m->elements.count, i, j;
    td_shaft_element *els = malloc((size_t)count * (size_t)factor * sizeof *els);
    if (!els)
        return td_error_set(err, TD_ERR_NOMEM, "out of memory refining a model");
    for (i = 0; i < count; i++)
        for (j = 0; j < factor; j++) {
            els[i * factor + j] = m->elements.items[i];
            els[i * factor + j].length = m->elements.items[i].length / factor;
        }
    free(m->elements.items);
    m->elements.items = els;
    m->elements.count = m->elements.capacity = count * factor;
    return TD_OK;
}

td_status td_model_refine(const td_model *model, int factor, td_model **out, td_error *err)
{
    td_model *m = NULL;
    td_status st;
    int i;
    if (!model || !out)
        return td_error_set(err, TD_ERR_INVALID, "td_model_refine: NULL argument");
    if (factor < 1)
        return td_error_set(err, TD_ERR_INVALID, "refine: factor %d must be >= 1", factor);
    /* DOF counts (4 per node) and the node renumbering below must stay within int */
    if (model->elements.count > REFINE_MAX_ELEMENTS / factor)
        return td_error_set(err, TD_ERR_INVALID, "refine: %d elements split %d times exceed %d elements",
                            model->elements.count, factor, REFINE_MAX_ELEMENTS);
    st = td_model_validate(model, err); /* every node number is on the shaft */
    if (st == TD_OK)
        st = td_model_clone(model, &m, err);
    if (st == TD_OK)
        st = split_elements(m, factor, err);
    if (st != TD_OK) {
        td_model_free(&m);
        return st;
    }
    /* node i of the coarse shaft sits at the same z as node factor * i of the fine one */
    for (i = 0; i < m->discs.count; i++)
        m->discs.items[i].node *= factor;
    for (i = 0; i < m->ambs.count; i++) {
        m->ambs.items[i].node *= factor;
        m->ambs.items[i].sensor_node *= factor;
    }
    for (i = 0; i < m->bearings.count; i++)
        m->bearings.items[i].node *= factor;
    for (i = 0; i < m->retainers.count; i++)
        m->retainers.items[i].node *= factor;
    for (i = 0; i < m->unbalances.count; i++)
        m->unbalances.items[i].node *= factor;
    *out = m;
    return TD_OK;
}

td_status td_model_set_shaft_options(td_model *m, const td_shaft_options *opt, td_error *err)
{
    if (!m || !opt)
        return td_error_set(err, TD_ERR_INVALID, "shaft options: NULL argument");
    if (opt->beam != TD_BEAM_EULER_BERNOULLI && opt->beam != TD_BEAM_TIMOSHENKO)
        return td_error_set(err, TD_ERR_INVALID, "shaft options: unknown beam theory %d", (int)opt->beam);
    if (opt->mass != TD_MASS_CONSISTENT && opt->mass != TD_MASS_LUMPED)
        return td_error_set(err, TD_ERR_INVALID, "shaft options: unknown mass form %d", (int)opt->mass);
    if (need(finite_nonnegative(opt->rayleigh_alpha), err, "shaft", 0, "rayleigh.alpha", NONNEG, opt->rayleigh_alpha) ||
        need(finite_nonnegative(opt->rayleigh_beta), err, "shaft", 0, "rayleigh.beta", NONNEG, opt->rayleigh_beta))
        return TD_ERR_INVALID;
    if (opt->shear != TD_SHEAR_HUTCHINSON && opt->shear != TD_SHEAR_COWPER && opt->shear != TD_SHEAR_GIVEN)
        return td_error_set(err, TD_ERR_INVALID, "shaft options: unknown shear coefficient form %d", (int)opt->shear);
    if (opt->shear == TD_SHEAR_GIVEN && !(opt->shear_value > 0.0 && opt->shear_value <= 1.0))
        return FAIL_AT(err, "shaft", 0, "shear_coefficient", "must be > 0 and <= 1 (got %g)", opt->shear_value);
    m->shaft = *opt;
    return TD_OK;
}

td_status td_rayleigh_from_ratio(double ratio, const double *frequencies, int count, double *alpha, double *beta,
                                 td_error *err)
{
    double w1, w2;
    int i;
    if (!frequencies || !alpha || !beta)
        return td_error_set(err, TD_ERR_INVALID, "damping: NULL argument");
    if (!(ratio >= 0.0 && ratio < 1.0))
        return FAIL_AT(err, "damping", 0, "ratio", "must be >= 0 and < 1 (got %g)", ratio);
    if (count != 1 && count != 2)
        return FAIL_AT(err, "damping", 0, "frequencies", "needs 1 or 2 frequencies, Hz (got %d)", count);
    for (i = 0; i < count; i++) {
        static const char *const at[] = {"frequencies.[0]", "frequencies.[1]"};
        if (!finite_positive(frequencies[i]))
            return FAIL_AT(err, "damping", 0, at[i], "must be > 0 Hz (got %g)", frequencies[i]);
        if (i > 0 && !(frequencies[i] > frequencies[i - 1]))
            return FAIL_AT(err, "damping", 0, at[i], "must be above the first frequency %g Hz (got %g)",
                           frequencies[i - 1], frequencies[i]);
    }
    /* zeta(w) = alpha / (2 w) + beta w / 2 equal to ratio at w1 and w2 */
    w1 = 2.0 * TD_PI * frequencies[0];
    w2 = count == 2 ? 2.0 * TD_PI * frequencies[1] : 0.0;
    *alpha = count == 2 ? 2.0 * ratio * w1 * w2 / (w1 + w2) : 0.0;
    *beta = 2.0 * ratio / (w1 + w2);
    if (!isfinite(*alpha) || !isfinite(*beta)) /* w1 w2 or w1 + w2 beyond the largest double */
        return FAIL_AT(err, "damping", 0, "frequencies",
                       "the Rayleigh coefficients alpha = 2 zeta w1 w2 / (w1 + w2) and beta = 2 zeta / (w1 + w2) "
                       "overflow (w = 2 pi f, the largest f %g Hz)",
                       frequencies[count - 1]);
    return TD_OK;
}

td_status td_model_add_shaft_element(td_model *m, const td_shaft_element *el, td_error *err)
{
    int i;
    if (!m || !el)
        return td_error_set(err, TD_ERR_INVALID, "shaft element: NULL argument");
    i = m->elements.count;
    if (need(finite_positive(el->length), err, "element", i, "length", POS, el->length) ||
        need(finite_positive(el->outer_diameter), err, "element", i, "outer_diameter", POS, el->outer_diameter))
        return TD_ERR_INVALID;
    if (!finite_nonnegative(el->inner_diameter) || el->inner_diameter >= el->outer_diameter)
        return td_error_set_site(err, TD_ERR_INVALID, &(td_error_site){"element", i, "inner_diameter"},
                                 &(td_error_site){"element", i, "outer_diameter"},
                                 "the inner diameter %g m must be >= 0 and smaller than the outer diameter %g m",
                                 el->inner_diameter, el->outer_diameter);
    if (need(finite_positive(el->material.E), err, "element", i, "material.E", POS, el->material.E) ||
        need(finite_positive(el->material.G), err, "element", i, "material.G", POS, el->material.G) ||
        need(finite_positive(el->material.density), err, "element", i, "material.density", POS, el->material.density))
        return TD_ERR_INVALID;
    return APPEND(m->elements, el, err);
}

td_status td_model_add_disc(td_model *m, const td_disc *disc, td_error *err)
{
    int i;
    if (!m || !disc)
        return td_error_set(err, TD_ERR_INVALID, "disc: NULL argument");
    i = m->discs.count;
    if (need_node(err, "disc", i, "node", disc->node) ||
        need(finite_positive(disc->mass), err, "disc", i, "mass", POS, disc->mass) ||
        need(finite_nonnegative(disc->Ip), err, "disc", i, "Ip", NONNEG, disc->Ip) ||
        need(finite_nonnegative(disc->Id), err, "disc", i, "Id", NONNEG, disc->Id))
        return TD_ERR_INVALID;
    return APPEND(m->discs, disc, err);
}

/* The moments of inertia of a homogeneous hollow circular cylinder (mass m, radii r < R, length
 * t): about its axis m (R^2 + r^2)/2, about a diameter through its centre of mass
 * m (3 (R^2 + r^2) + t^2)/12 (the standard entries of any table of homogeneous solids; with r = 0
 * the disc row of docs/reference-rig.md). The one place the case reader and embedders get them. */
td_status td_disc_from_geometry(const td_disc_geometry *g, td_disc *out, td_error *err)
{
    double R2, r2, area, t;
    if (!g || !out)
        return td_error_set(err, TD_ERR_INVALID, "disc geometry: NULL argument");
    /* index -1: a disc not in a model */
    if (need(finite_positive(g->outer_radius), err, "disc", -1, "outer_radius", POS, g->outer_radius) ||
        need(finite_positive(g->density), err, "disc", -1, "density", POS, g->density))
        return TD_ERR_INVALID;
    if (!finite_nonnegative(g->inner_radius) || g->inner_radius >= g->outer_radius)
        return FAIL_AT(err, "disc", -1, "inner_radius",
                       "the inner radius %g m must be >= 0 and smaller than the outer radius %g m", g->inner_radius,
                       g->outer_radius);
    if (need(finite_nonnegative(g->thickness), err, "disc", -1, "thickness", NONNEG, g->thickness) ||
        need(finite_nonnegative(g->mass), err, "disc", -1, "mass", NONNEG, g->mass))
        return TD_ERR_INVALID;
    if (g->thickness > 0.0 && g->mass > 0.0)
        return FAIL_AT(err, "disc", -1, "mass", "give either the thickness or the mass, not both");
    if (g->thickness == 0.0 && g->mass == 0.0)
        return FAIL_AT(err, "disc", -1, "thickness", "give either the thickness or the mass (> 0)");
    R2 = g->outer_radius * g->outer_radius;
    r2 = g->inner_radius * g->inner_radius;
    area = TD_PI * (R2 - r2);
    out->node = g->node;
    out->mass = g->thickness > 0.0 ? g->density * area * g->thickness : g->mass;
    t = g->thickness > 0.0 ? g->thickness : g->mass / (g->density * area);
    out->Ip = out->mass * (R2 + r2) / 2.0;
    out->Id = out->mass * (3.0 * (R2 + r2) + t * t) / 12.0;
    return TD_OK;
}

td_status td_model_add_point_mass(td_model *m, int node, double mass, td_error *err)
{
    td_disc d;
    d.node = node;
    d.mass = mass;
    d.Ip = 0.0;
    d.Id = 0.0;
    return td_model_add_disc(m, &d, err);
}

td_status td_model_add_amb(td_model *m, const td_amb *amb, td_error *err)
{
    int i;
    if (!m || !amb)
        return td_error_set(err, TD_ERR_INVALID, "amb: NULL argument");
    i = m->ambs.count;
    if (need_node(err, "amb", i, "node", amb->node) || need_node(err, "amb", i, "sensor_node", amb->sensor_node) ||
        need(isfinite(amb->ks), err, "amb", i, "ks", "be finite", amb->ks) ||
        need(isfinite(amb->ki), err, "amb", i, "ki", "be finite", amb->ki) ||
        need(isfinite(amb->kp), err, "amb", i, "kp", "be finite", amb->kp) ||
        need(isfinite(amb->kd), err, "amb", i, "kd", "be finite", amb->kd) ||
        need(finite_nonnegative(amb->kint), err, "amb", i, "kint", NONNEG, amb->kint) ||
        need(finite_nonnegative(amb->tau), err, "amb", i, "tau", NONNEG, amb->tau) ||
        need(finite_positive(amb->force_capacity), err, "amb", i, "force_capacity", POS, amb->force_capacity) ||
        need(finite_nonnegative(amb->air_gap), err, "amb", i, "air_gap", NONNEG, amb->air_gap) ||
        need(finite_nonnegative(amb->slew_rate), err, "amb", i, "slew_rate", NONNEG, amb->slew_rate))
        return TD_ERR_INVALID;
    if (amb->slew_rate > 0.0 && !(amb->tau > 0.0)) /* the limit acts on dFc/dt: Fc must be a state */
        return FAIL_AT(err, "amb", i, "slew_rate",
                       "a slew-rate limit (%g A/s) needs a force lag, tau > 0 or a bandwidth (got tau = %g)",
                       amb->slew_rate, amb->tau);
    return APPEND(m->ambs, amb, err);
}

td_status td_model_add_bearing(td_model *m, const td_bearing *b, td_error *err)
{
    int i;
    if (!m || !b)
        return td_error_set(err, TD_ERR_INVALID, "bearing: NULL argument");
    i = m->bearings.count;
    if (need_node(err, "bearing", i, "node", b->node) ||
        need(finite_nonnegative(b->kxx), err, "bearing", i, "kxx", NONNEG, b->kxx) ||
        need(finite_nonnegative(b->kyy), err, "bearing", i, "kyy", NONNEG, b->kyy) ||
        need(finite_nonnegative(b->cxx), err, "bearing", i, "cxx", NONNEG, b->cxx) ||
        need(finite_nonnegative(b->cyy), err, "bearing", i, "cyy", NONNEG, b->cyy))
        return TD_ERR_INVALID;
    return APPEND(m->bearings, b, err);
}

/* A part of the race that needs another: `value` > 0 only if `base` > 0. */
static td_status race_needs(double value, double base, int i, const char *field, const char *needed, td_error *err)
{
    if (value > 0.0 && !(base > 0.0))
        return FAIL_AT(err, "retainer", i, field, "needs %s > 0 (got %g with %s = %g)", needed, value, needed, base);
    return TD_OK;
}

/* The race as a body (model.h td_race): values >= 0, drag only on a race that can spin, mass and
 * damping only with a mount, and a mount only with a mass (the race would have no dynamics). */
static td_status check_race(const td_race *b, int i, td_error *err)
{
    if (need(finite_nonnegative(b->inertia), err, "retainer", i, "race.inertia", NONNEG, b->inertia) ||
        need(finite_nonnegative(b->drag_torque), err, "retainer", i, "race.drag_torque", NONNEG, b->drag_torque) ||
        need(finite_nonnegative(b->drag_viscous), err, "retainer", i, "race.drag_viscous", NONNEG, b->drag_viscous) ||
        need(finite_nonnegative(b->mass), err, "retainer", i, "race.mass", NONNEG, b->mass) ||
        need(finite_nonnegative(b->mount_stiffness), err, "retainer", i, "mount.stiffness", NONNEG,
             b->mount_stiffness) ||
        need(finite_nonnegative(b->mount_damping), err, "retainer", i, "mount.damping", NONNEG, b->mount_damping) ||
        race_needs(b->drag_torque, b->inertia, i, "race.drag_torque", "race.inertia", err) ||
        race_needs(b->drag_viscous, b->inertia, i, "race.drag_viscous", "race.inertia", err) ||
        race_needs(b->mass, b->mount_stiffness, i, "race.mass", "mount.stiffness", err) ||
        race_needs(b->mount_damping, b->mount_stiffness, i, "mount.damping", "mount.stiffness", err) ||
        race_needs(b->mount_stiffness, b->mass, i, "mount.stiffness", "race.mass", err))
        return TD_ERR_INVALID;
    return TD_OK;
}

/* A retainer's own contact law (model.h td_retainer_contact): all zero, or a stiffness > 0 with
 * the ranges of the run's penalty law (touchdown/options.h). */
static td_status check_retainer_contact(const td_retainer_contact *c, int i, td_error *err)
{
    if (need(finite_nonnegative(c->stiffness), err, "retainer", i, "contact.stiffness", NONNEG, c->stiffness) ||
        need(isfinite(c->exponent) && (c->exponent == 0.0 || c->exponent >= 1.0), err, "retainer", i,
             "contact.exponent", "be >= 1", c->exponent) ||
        need(c->damping == TD_DAMPING_NONE || c->damping == TD_DAMPING_HUNT_CROSSLEY ||
                 c->damping == TD_DAMPING_KELVIN_VOIGT,
             err, "retainer", i, "contact.damping", "be none, hunt-crossley or kelvin-voigt", (double)c->damping) ||
        need(finite_nonnegative(c->damping_coefficient), err, "retainer", i, "contact.damping_coefficient", NONNEG,
             c->damping_coefficient) ||
        race_needs(c->damping_coefficient, c->stiffness, i, "contact.damping_coefficient", "contact.stiffness", err) ||
        race_needs(c->exponent, c->stiffness, i, "contact.exponent", "contact.stiffness", err))
        return TD_ERR_INVALID;
    return TD_OK;
}

td_status td_model_add_retainer(td_model *m, const td_retainer *r, td_error *err)
{
    int i;
    if (!m || !r)
        return td_error_set(err, TD_ERR_INVALID, "retainer: NULL argument");
    i = m->retainers.count;
    if (need_node(err, "retainer", i, "node", r->node) ||
        need(finite_positive(r->clearance), err, "retainer", i, "clearance", POS, r->clearance) ||
        need(finite_positive(r->shaft_radius), err, "retainer", i, "shaft_radius", POS, r->shaft_radius) ||
        need(finite_positive(r->bore_radius), err, "retainer", i, "bore_radius", POS, r->bore_radius))
        return TD_ERR_INVALID;
    /* c = R_b - R_s: the clearance is the gap between the two radii */
    if (fabs(r->bore_radius - r->shaft_radius - r->clearance) > 1e-9 * r->bore_radius)
        return FAIL_AT(err, "retainer", i, "bore_radius",
                       "the bore radius must equal shaft_radius + clearance = %.9g m (got %.9g m)",
                       r->shaft_radius + r->clearance, r->bore_radius);
    if (need(finite_nonnegative(r->friction), err, "retainer", i, "friction", NONNEG, r->friction) ||
        need(isfinite(r->bore_speed), err, "retainer", i, "bore_speed", "be finite", r->bore_speed) ||
        need(isfinite(r->restitution) && r->restitution >= 0.0 && r->restitution <= 1.0, err, "retainer", i,
             "restitution", "lie in [0, 1]", r->restitution) ||
        race_needs(r->stick ? 1.0 : 0.0, r->friction, i, "stick", "friction", err) || check_race(&r->race, i, err) ||
        check_retainer_contact(&r->contact, i, err))
        return TD_ERR_INVALID;
    return APPEND(m->retainers, r, err);
}

int td_retainer_has_race(const td_retainer *r)
{
    return r && (r->race.inertia > 0.0 || r->race.mount_stiffness > 0.0);
}

td_status td_model_add_unbalance(td_model *m, const td_unbalance *u, td_error *err)
{
    int i;
    if (!m || !u)
        return td_error_set(err, TD_ERR_INVALID, "unbalance: NULL argument");
    i = m->unbalances.count;
    if (need_node(err, "unbalance", i, "node", u->node) ||
        need(finite_nonnegative(u->magnitude), err, "unbalance", i, "magnitude", NONNEG, u->magnitude) ||
        need(isfinite(u->phase), err, "unbalance", i, "phase", "be finite", u->phase))
        return TD_ERR_INVALID;
    return APPEND(m->unbalances, u, err);
}

td_status td_model_add_change(td_model *m, const td_change *c, td_error *err)
{
    td_status st;
    int i;
    if (!m || !c)
        return td_error_set(err, TD_ERR_INVALID, "change: NULL argument");
    i = m->changes.count;
    if (need(finite_nonnegative(c->time), err, "change", i, "time", NONNEG, c->time))
        return TD_ERR_INVALID;
    if (c->kind != TD_CHANGE_UNBALANCE && c->kind != TD_CHANGE_AMB_OFF && c->kind != TD_CHANGE_AMB_ON)
        return FAIL_AT(err, "change", i, "kind", "unknown kind %d", (int)c->kind);
    if (need_node(err, "change", i, "index", c->index))
        return TD_ERR_INVALID;
    if (c->kind == TD_CHANGE_UNBALANCE &&
        (need(finite_nonnegative(c->magnitude), err, "change", i, "magnitude", NONNEG, c->magnitude) ||
         need(isfinite(c->phase), err, "change", i, "phase", "be finite", c->phase)))
        return TD_ERR_INVALID;
    st = APPEND(m->changes, c, err);
    if (st == TD_OK && (st = APPEND(m->change_entries, &i, err)) != TD_OK)
        m->changes.count--;
    if (st != TD_OK)
        return st;
    /* keep the schedule sorted by time, equal times in their order of addition; each change keeps
     * its number of addition (td_model_change_entry), the entry a caller or case file wrote */
    for (i = m->changes.count - 1; i > 0 && m->changes.items[i - 1].time > m->changes.items[i].time; i--) {
        td_change tmp = m->changes.items[i - 1];
        int entry = m->change_entries.items[i - 1];
        m->changes.items[i - 1] = m->changes.items[i];
        m->changes.items[i] = tmp;
        m->change_entries.items[i - 1] = m->change_entries.items[i];
        m->change_entries.items[i] = entry;
    }
    return TD_OK;
}

td_status td_model_set_speed(td_model *m, double omega, td_error *err)
{
    if (!m)
        return td_error_set(err, TD_ERR_INVALID, "speed: NULL model");
    if (!TD_SPEED_VALID(omega))
        return td_error_set(err, TD_ERR_INVALID,
                            "speed must be finite and >= 0 rad/s (got %g; the spin is about +z, "
                            "touchdown/dofs.h)",
                            omega);
    m->speed = omega;
    return TD_OK;
}

td_status td_model_add_speed_point(td_model *m, const td_speed_point *p, td_error *err)
{
    int i;
    if (!m || !p)
        return td_error_set(err, TD_ERR_INVALID, "speed ramp: NULL argument");
    i = m->speed_points.count;
    if (need(finite_nonnegative(p->time), err, "speed_ramp", i, "time", NONNEG, p->time) ||
        need(finite_nonnegative(p->speed), err, "speed_ramp", i, "speed", NONNEG, p->speed))
        return TD_ERR_INVALID;
    if (i > 0 && !(p->time > m->speed_points.items[i - 1].time))
        return FAIL_AT(err, "speed_ramp", i, "time", "must come after the previous point's %g s, not %g s",
                       m->speed_points.items[i - 1].time, p->time);
    return APPEND(m->speed_points, p, err);
}

td_status td_model_set_spin(td_model *m, const td_spin *sp, td_error *err)
{
    if (!m || !sp)
        return td_error_set(err, TD_ERR_INVALID, "spin: NULL argument");
    if (need(finite_nonnegative(sp->inertia), err, "spin", 0, "inertia", NONNEG, sp->inertia) ||
        need(isfinite(sp->drive_torque), err, "spin", 0, "drive_torque", "be finite", sp->drive_torque) ||
        need(finite_nonnegative(sp->drag_torque), err, "spin", 0, "drag_torque", NONNEG, sp->drag_torque) ||
        need(finite_nonnegative(sp->drag_viscous), err, "spin", 0, "drag_viscous", NONNEG, sp->drag_viscous))
        return TD_ERR_INVALID;
    if (!sp->free && (sp->drive_torque != 0.0 || sp->drag_torque > 0.0 || sp->drag_viscous > 0.0))
        return FAIL_AT(err, "spin", 0, "free", "torques act only on a free spin (free = true)");
    m->spin = *sp;
    return TD_OK;
}

td_status td_model_set_gravity(td_model *m, double gx, double gy, td_error *err)
{
    if (!m)
        return td_error_set(err, TD_ERR_INVALID, "gravity: NULL model");
    if (!isfinite(gx) || !isfinite(gy))
        return td_error_set(err, TD_ERR_INVALID, "gravity must be finite");
    m->gravity[0] = gx;
    m->gravity[1] = gy;
    return TD_OK;
}

td_status td_model_set_reduction(td_model *m, double cutoff, td_error *err)
{
    if (!m)
        return td_error_set(err, TD_ERR_INVALID, "reduction: NULL model");
    if (!(isfinite(cutoff) && cutoff >= 0.0))
        return FAIL_AT(err, "reduction", 0, "cutoff", "must be a finite frequency >= 0 Hz (got %g)", cutoff);
    m->reduction_cutoff = cutoff;
    return TD_OK;
}

double td_model_reduction(const td_model *m)
{
    return m ? m->reduction_cutoff : 0.0;
}

/* A node of part i: one of the shaft's, whose count is compared against (other: the shaft's nodes). */
static td_status check_node(const td_model *m, const char *part, int i, const char *field, int node, td_error *err)
{
    int nodes = td_model_node_count(m);
    if (node < 0 || node >= nodes)
        return td_error_set_site(err, TD_ERR_INVALID, &(td_error_site){part, i, field},
                                 &(td_error_site){"shaft", 0, "nodes"},
                                 "node %d is out of range (the shaft has nodes 0..%d)", node, nodes - 1);
    return TD_OK;
}

/* Part i of kind `part` sits on `node`, where part j of that kind already is: one per node. */
static td_status fail_node_taken(td_error *err, const char *part, const char *a_part, int i, int j, int node)
{
    return td_error_set_site(err, TD_ERR_INVALID, &(td_error_site){part, i, "node"}, &(td_error_site){part, j, "node"},
                             "node %d already has %s (%s %d)", node, a_part, part, j);
}

/* A retainer must be tighter than every AMB air gap (or the rotor would hit the stator first). */
static td_status check_air_gaps(const td_model *m, int i, td_error *err)
{
    const td_retainer *r = &m->retainers.items[i];
    int j;
    for (j = 0; j < m->ambs.count; j++)
        if (m->ambs.items[j].air_gap > 0.0 && r->clearance >= m->ambs.items[j].air_gap)
            return td_error_set_site(err, TD_ERR_INVALID, &(td_error_site){"retainer", i, "clearance"},
                                     &(td_error_site){"amb", j, "air_gap"},
                                     "clearance %g m is not smaller than the air gap %g m of amb %d", r->clearance,
                                     m->ambs.items[j].air_gap, j);
    return TD_OK;
}

/* Every change names an unbalance or AMB that exists (other: their list, index -1). */
static td_status check_changes(const td_model *m, td_error *err)
{
    int i;
    for (i = 0; i < m->changes.count; i++) {
        const td_change *c = &m->changes.items[i];
        int limit = c->kind == TD_CHANGE_UNBALANCE ? m->unbalances.count : m->ambs.count;
        const char *part = c->kind == TD_CHANGE_UNBALANCE ? "unbalance" : "amb";
        if (c->index >= limit)
            return td_error_set_site(err, TD_ERR_INVALID, &(td_error_site){"change", i, "index"},
                                     &(td_error_site){part, -1, NULL},
                                     "%s %d does not exist (%d defined, indices start at 0; the change at t = %g s)",
                                     c->kind == TD_CHANGE_UNBALANCE ? "unbalance" : "AMB", c->index, limit, c->time);
    }
    return TD_OK;
}

td_status td_model_validate(const td_model *m, td_error *err)
{
    int i, j;
    if (!m)
        return td_error_set(err, TD_ERR_INVALID, "validate: NULL model");
    if (m->elements.count < 1)
        return td_error_set(err, TD_ERR_INVALID, "the shaft has no elements");
    for (i = 0; i < m->discs.count; i++)
        if (check_node(m, "disc", i, "node", m->discs.items[i].node, err))
            return TD_ERR_INVALID;
    for (i = 0; i < m->ambs.count; i++) {
        if (check_node(m, "amb", i, "node", m->ambs.items[i].node, err) ||
            check_node(m, "amb", i, "sensor_node", m->ambs.items[i].sensor_node, err))
            return TD_ERR_INVALID;
        for (j = 0; j < i; j++)
            if (m->ambs.items[j].node == m->ambs.items[i].node)
                return fail_node_taken(err, "amb", "an AMB", i, j, m->ambs.items[i].node);
    }
    for (i = 0; i < m->bearings.count; i++)
        if (check_node(m, "bearing", i, "node", m->bearings.items[i].node, err))
            return TD_ERR_INVALID;
    for (i = 0; i < m->retainers.count; i++) {
        const td_retainer *r = &m->retainers.items[i];
        if (check_node(m, "retainer", i, "node", r->node, err))
            return TD_ERR_INVALID;
        for (j = 0; j < i; j++)
            if (m->retainers.items[j].node == r->node)
                return fail_node_taken(err, "retainer", "a retainer", i, j, r->node);
        if (check_air_gaps(m, i, err))
            return TD_ERR_INVALID;
    }
    for (i = 0; i < m->unbalances.count; i++)
        if (check_node(m, "unbalance", i, "node", m->unbalances.items[i].node, err))
            return TD_ERR_INVALID;
    if (m->spin.free && m->speed_points.count > 0)
        return FAIL_AT(err, "spin", 0, "free",
                       "a free spin has no prescribed ramp (speed_ramp): give one or the other");
    if (td_model_speed_varies(m) && !(td_model_polar_inertia(m) > 0.0 || m->spin.inertia > 0.0))
        return FAIL_AT(err, "spin", 0, "inertia", "a varying speed needs a polar inertia: the rotor has none");
    /* the speed is `speed` before the first point: a first point later than 0 at another speed would
     * step it there, an infinite angular acceleration that no drive gives (and no energy account
     * books) */
    if (m->speed_points.count > 0 && m->speed_points.items[0].time > 0.0 && m->speed_points.items[0].speed != m->speed)
        return FAIL_AT(err, "speed_ramp", 0, "speed",
                       "the speed would step from `speed` %g rad/s to %g rad/s at the ramp's first point (%g s): "
                       "start the ramp at `speed`, or add a point at time 0",
                       m->speed, m->speed_points.items[0].speed, m->speed_points.items[0].time);
    /* housing body: a free spin's torque balance (spin.c) takes the unbalances' accelerations relative
     * to the housing, without the body's */
    if (m->has_body && m->spin.free)
        return FAIL_AT(err, "housing.body", -1, NULL, "a housing body needs a prescribed speed (no free spin)");
    if (td_model_check_recovery(m, err) || td_model_check_controllers(m, err))
        return TD_ERR_INVALID;
    return check_changes(m, err);
}

int td_model_node_count(const td_model *m)
{
    return m && m->elements.count ? m->elements.count + 1 : 0;
}
int td_model_dof_count(const td_model *m)
{
    return TD_DOFS_PER_NODE * td_model_node_count(m);
}
int td_model_shaft_element_count(const td_model *m)
{
    return m ? m->elements.count : 0;
}
int td_model_disc_count(const td_model *m)
{
    return m ? m->discs.count : 0;
}
int td_model_amb_count(const td_model *m)
{
    return m ? m->ambs.count : 0;
}
int td_model_bearing_count(const td_model *m)
{
    return m ? m->bearings.count : 0;
}
int td_model_retainer_count(const td_model *m)
{
    return m ? m->retainers.count : 0;
}
int td_model_unbalance_count(const td_model *m)
{
    return m ? m->unbalances.count : 0;
}
int td_model_change_count(const td_model *m)
{
    return m ? m->changes.count : 0;
}
int td_model_change_entry(const td_model *m, int i)
{
    return m && i >= 0 && i < m->change_entries.count ? m->change_entries.items[i] : -1;
}
double td_model_speed(const td_model *m)
{
    return m ? m->speed : 0.0;
}

void td_model_gravity(const td_model *m, double *gx, double *gy)
{
    if (gx)
        *gx = m ? m->gravity[0] : 0.0;
    if (gy)
        *gy = m ? m->gravity[1] : 0.0;
}

void td_model_shaft_options(const td_model *m, td_shaft_options *out)
{
    if (m && out)
        *out = m->shaft;
}

double td_model_node_position(const td_model *m, int node)
{
    double z = 0.0;
    int i;
    if (!m)
        return 0.0;
    for (i = 0; i < node && i < m->elements.count; i++)
        z += m->elements.items[i].length;
    return z;
}

int td_model_speed_point_count(const td_model *m)
{
    return m ? m->speed_points.count : 0;
}

void td_model_spin(const td_model *m, td_spin *out)
{
    if (m && out)
        *out = m->spin;
}

int td_model_speed_varies(const td_model *m)
{
    return m && (m->spin.free || m->speed_points.count > 0);
}

double td_model_speed_at(const td_model *m, double t, double *rate, double *angle)
{
    /* walk the piecewise-linear profile, integrating the angle segment by segment (trapezoids
     * are exact for linear speeds); at a point itself the slope is the next segment's */
    double w = m ? m->speed : 0.0, t_prev = 0.0, phi = 0.0, slope = 0.0;
    int i, n = m ? m->speed_points.count : 0;
    for (i = 0; i < n; i++) {
        const td_speed_point *p = &m->speed_points.items[i];
        double seg = i > 0 ? (p->speed - w) / (p->time - t_prev) : 0.0;
        if (t < p->time) {
            slope = seg;
            break;
        }
        phi += i > 0 ? (p->time - t_prev) * 0.5 * (w + p->speed) : (p->time - t_prev) * w;
        w = p->speed;
        t_prev = p->time;
    }
    /* from the last point passed (or time 0) to t: speed w + slope (t - t_prev) */
    phi += (t - t_prev) * (w + 0.5 * slope * (t - t_prev));
    w += slope * (t - t_prev);
    if (rate)
        *rate = slope;
    if (angle)
        *angle = phi;
    return w;
}

/* A hollow cylindrical element's mass rho pi L (ro^2 - ri^2) (polar = 0) or polar moment of
 * inertia rho pi L (ro^4 - ri^4) / 2 (polar = 1). */
static double element_inertia(const td_shaft_element *e, int polar)
{
    double ro = 0.5 * e->outer_diameter, ri = 0.5 * e->inner_diameter, ro2 = ro * ro, ri2 = ri * ri;
    double mass = e->material.density * TD_PI * e->length * (ro2 - ri2);
    return polar ? 0.5 * mass * (ro2 + ri2) : mass;
}

double td_model_polar_inertia(const td_model *m)
{
    double total = 0.0;
    int i;
    if (!m)
        return 0.0;
    for (i = 0; i < m->elements.count; i++)
        total += element_inertia(&m->elements.items[i], 1);
    for (i = 0; i < m->discs.count; i++)
        total += m->discs.items[i].Ip;
    return total;
}

double td_model_total_mass(const td_model *m)
{
    double total = 0.0;
    int i;
    if (!m)
        return 0.0;
    for (i = 0; i < m->elements.count; i++)
        total += element_inertia(&m->elements.items[i], 0);
    for (i = 0; i < m->discs.count; i++)
        total += m->discs.items[i].mass;
    return total;
}

double td_model_mass_centre(const td_model *m)
{
    double total = 0.0, moment = 0.0, z = 0.0;
    int i;
    if (!m)
        return 0.0;
    for (i = 0; i < m->elements.count; i++) {
        double mass = element_inertia(&m->elements.items[i], 0), length = m->elements.items[i].length;
        total += mass;
        moment += mass * (z + 0.5 * length);
        z += length;
    }
    for (i = 0; i < m->discs.count; i++) {
        total += m->discs.items[i].mass;
        moment += m->discs.items[i].mass * td_model_node_position(m, m->discs.items[i].node);
    }
    return total > 0.0 ? moment / total : 0.0;
}

/* The housing's reference point (touchdown/housing.h; set in housing.c): by default the rotor's centre of mass. */
double td_model_housing_reference(const td_model *m)
{
    if (!m)
        return 0.0;
    return m->has_housing_reference ? m->housing_reference : td_model_mass_centre(m);
}

#define GETTER(fn, type, arr)                                                                                          \
    td_status fn(const td_model *m, int i, type *out)                                                                  \
    {                                                                                                                  \
        if (!m || !out || i < 0 || i >= m->arr.count)                                                                  \
            return TD_ERR_INVALID;                                                                                     \
        *out = m->arr.items[i];                                                                                        \
        return TD_OK;                                                                                                  \
    }

GETTER(td_model_get_shaft_element, td_shaft_element, elements)
GETTER(td_model_get_speed_point, td_speed_point, speed_points)
GETTER(td_model_get_disc, td_disc, discs)
GETTER(td_model_get_amb, td_amb, ambs)
GETTER(td_model_get_bearing, td_bearing, bearings)
GETTER(td_model_get_retainer, td_retainer, retainers)
GETTER(td_model_get_unbalance, td_unbalance, unbalances)
GETTER(td_model_get_change, td_change, changes)
