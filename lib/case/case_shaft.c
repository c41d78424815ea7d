/*
 * The "shaft" group: geometry (uniform length + elements, or node positions), per-element
 * diameters and material with sections for stepped and hollow shafts, beam theory, mass form
 * and Rayleigh damping. Element i joins nodes i and i + 1 (touchdown/model.h).
 */
#include "case/case_internal.h"
#include "touchdown/dofs.h"
#include "util/error_internal.h"

#include <stdlib.h>
#include <string.h>

static const char *const shaft_keys[] = {
    "length", "elements", "nodes",    "outer_diameter", "inner_diameter", "material",          "sections",
    "beam",   "mass",     "rayleigh", "refine",         "damping",        "shear_coefficient", NULL};
static const char *const material_keys[] = {"E", "G", "density", NULL};
static const char *const section_keys[] = {"element",        "from",     "to", "outer_diameter",
                                           "inner_diameter", "material", NULL};
static const char *const rayleigh_keys[] = {"alpha", "beta", NULL};
static const char *const damping_keys[] = {"ratio", "frequencies", NULL};
static const char *const beam_names[] = {"euler-bernoulli", "timoshenko"};
static const char *const mass_names[] = {"consistent", "lumped"};
static const char *const shear_names[] = {"hutchinson", "cowper"};

/* Element lengths from "length" + "elements" or from the node positions "nodes";
 * *lengths is allocated (caller frees). */
static td_status read_lengths(td_case_reader *r, const config_setting_t *shaft, double **lengths, int *count)
{
    const config_setting_t *nodes = config_setting_get_member(shaft, "nodes");
    double length, *z;
    int n, i;
    td_status st;

    *lengths = NULL;
    if (nodes) {
        if (td_cr_has(shaft, "length") || td_cr_has(shaft, "elements"))
            return td_cr_fail(r, nodes, NULL, "give either 'nodes' or 'length' + 'elements', not both");
        z = malloc((TD_CASE_MAX_ELEMENTS + 1) * sizeof *z);
        if (!z)
            return td_error_set(r->err, TD_ERR_NOMEM, "%s: out of memory", r->path_shown);
        st = td_cr_reals(r, shaft, "nodes", TD_CASE_MAX_ELEMENTS + 1, TD_CR_FINITE, z, &n);
        if (st == TD_OK && n < 2)
            st = td_cr_fail(r, nodes, NULL, "needs at least 2 node positions (got %d)", n);
        for (i = 1; st == TD_OK && i < n; i++) {
            if (!(z[i] > z[i - 1]))
                st = td_cr_fail(r, config_setting_get_elem(nodes, (unsigned)i), NULL,
                                "node positions must increase strictly (%g m follows %g m)", z[i], z[i - 1]);
            else
                st = td_cr_derived(r, config_setting_get_elem(nodes, (unsigned)i), z[i] - z[i - 1],
                                   "the element length from the node positions");
            z[i - 1] = z[i] - z[i - 1]; /* position -> length of element i - 1 */
        }
        if (st != TD_OK) {
            free(z);
            return st;
        }
        *lengths = z;
        *count = n - 1;
        return TD_OK;
    }
    st = td_cr_real(r, shaft, "length", "shaft length, m; or give 'nodes'", 0.0, TD_CR_POSITIVE, &length);
    if (st == TD_OK)
        st = td_cr_int(r, shaft, "elements", "number of equal shaft elements", 0, 1, TD_CASE_MAX_ELEMENTS, &n);
    if (st != TD_OK)
        return st;
    z = malloc((size_t)n * sizeof *z);
    if (!z)
        return td_error_set(r->err, TD_ERR_NOMEM, "%s: out of memory", r->path_shown);
    for (i = 0; i < n; i++)
        z[i] = length / n;
    *lengths = z;
    *count = n;
    return TD_OK;
}

/* A material group; keys absent keep the values already in *m when `partial`, else are required. */
static td_status read_material(td_case_reader *r, const config_setting_t *g, int partial, td_material *m)
{
    td_status st = td_cr_check_keys(r, g, material_keys);
    if (st == TD_OK)
        st = td_cr_real(r, g, "E", partial ? NULL : "Young's modulus, Pa", m->E, TD_CR_POSITIVE, &m->E);
    if (st == TD_OK)
        st = td_cr_real(r, g, "G", partial ? NULL : "shear modulus, Pa", m->G, TD_CR_POSITIVE, &m->G);
    if (st == TD_OK)
        st = td_cr_real(r, g, "density", partial ? NULL : "density, kg/m^3", m->density, TD_CR_POSITIVE, &m->density);
    return st;
}

/* One entry of "sections": element range [from, to], then diameter and material overrides. */
static td_status read_section(td_case_reader *r, const config_setting_t *sec, int count, int *owner, int index,
                              td_shaft_element *els)
{
    const config_setting_t *mat;
    td_shaft_element proto;
    int from, to, i;
    td_status st = td_cr_check_keys(r, sec, section_keys);
    if (st != TD_OK)
        return st;
    if (td_cr_has(sec, "element")) {
        if (td_cr_has(sec, "from") || td_cr_has(sec, "to"))
            return td_cr_fail(r, config_setting_get_member(sec, "element"), NULL,
                              "give either 'element' or 'from' + 'to', not both");
        st = td_cr_int(r, sec, "element", NULL, 0, 0, count - 1, &from);
        to = from;
    } else {
        st = td_cr_int(r, sec, "from", "first element of the section; or give 'element'", 0, 0, count - 1, &from);
        if (st == TD_OK)
            st = td_cr_int(r, sec, "to", "last element of the section (inclusive)", 0, 0, count - 1, &to);
        if (st == TD_OK && to < from)
            return td_cr_fail(r, config_setting_get_member(sec, "to"), NULL, "must be >= from (%d), got %d", from, to);
    }
    if (st != TD_OK)
        return st;
    proto = els[from];
    st = td_cr_real(r, sec, "outer_diameter", NULL, proto.outer_diameter, TD_CR_POSITIVE, &proto.outer_diameter);
    if (st == TD_OK)
        st = td_cr_real(r, sec, "inner_diameter", NULL, proto.inner_diameter, TD_CR_NONNEGATIVE, &proto.inner_diameter);
    if (st == TD_OK)
        st = td_cr_group(r, sec, "material", NULL, &mat);
    if (st == TD_OK && mat)
        st = read_material(r, mat, 1, &proto.material);
    for (i = from; st == TD_OK && i <= to; i++) {
        if (owner[i] >= 0)
            return td_cr_fail(r, sec, NULL, "element %d is already in sections[%d]; sections must not overlap", i,
                              owner[i]);
        owner[i] = index;
        proto.length = els[i].length;
        els[i] = proto;
    }
    return st;
}

/* The setting that gave element i its `key` (a member of the material group when `material`):
 * that of its section (owner >= 0) when the section sets it, else the shaft's, else the shaft. */
static const config_setting_t *element_source(const config_setting_t *shaft, int owner, const char *key, int material)
{
    const config_setting_t *g, *s = NULL;
    if (owner >= 0) {
        g = config_setting_get_elem(config_setting_get_member(shaft, "sections"), (unsigned)owner);
        g = material ? config_setting_get_member(g, "material") : g;
        s = g ? config_setting_get_member(g, key) : NULL;
    }
    if (!s) {
        g = material ? config_setting_get_member(shaft, "material") : shaft;
        s = g ? config_setting_get_member(g, key) : NULL;
    }
    return s ? s : shaft;
}

/* The setting that gave an element the field a model error site names ("inner_diameter",
 * "material.E", "length", ...): element_source of that key; for "length" the node position that
 * ends element i (`nodes`) or the shaft's `length`. */
static const config_setting_t *element_field(const config_setting_t *shaft, int owner, const td_error_site *site)
{
    const char *field = site->field ? site->field : "";
    const config_setting_t *nodes = config_setting_get_member(shaft, "nodes");
    int material = strncmp(field, "material.", 9) == 0;
    if (strcmp(field, "length") == 0 && nodes && site->index + 1 < config_setting_length(nodes))
        return config_setting_get_elem(nodes, (unsigned)(site->index + 1));
    return element_source(shaft, owner, material ? field + 9 : field, material);
}

/* 1 if setting s lies inside the shaft's `sections` list (a section's key or its material's). */
static int in_section(const config_setting_t *shaft, const config_setting_t *s)
{
    const config_setting_t *sections = config_setting_get_member(shaft, "sections");
    for (; s && sections; s = config_setting_parent(s))
        if (s == sections)
            return 1;
    return 0;
}

/* A model error on element e (number i) read from the case, blamed on the setting that gave the
 * element the field it names. When it compares two fields (the inner diameter against the outer
 * one) and a section set one of them while the other is the shaft's, the section's value is the
 * one written for this element: it is blamed, said to be the section's, and the other is named
 * with its place. */
static td_status element_fail(td_case_reader *r, const config_setting_t *shaft, int owner, int i,
                              const td_shaft_element *e, td_status st, const td_error *merr)
{
    const config_setting_t *inner = element_field(shaft, owner, &merr->site), *outer;
    char key[512], where[1200];
    if (st == TD_ERR_NOMEM || !merr->other.field || strcmp(merr->other.field, "outer_diameter") != 0)
        return td_cr_model_fail(r, inner, st, merr);
    outer = element_field(shaft, owner, &merr->other);
    if (in_section(shaft, inner) == in_section(shaft, outer))
        return td_cr_model_fail(r, inner, st, merr);
    td_cr_key(in_section(shaft, outer) ? inner : outer, key, sizeof key);
    td_cr_where(r, in_section(shaft, outer) ? inner : outer, where, sizeof where);
    if (in_section(shaft, outer))
        return td_cr_fail(r, outer, NULL,
                          "the section's outer diameter %g m (element %d) must be larger than the inner diameter "
                          "%g m of %s at %s",
                          e->outer_diameter, i, e->inner_diameter, key, where);
    return td_cr_fail(r, inner, NULL,
                      "the section's inner diameter %g m (element %d) must be >= 0 and smaller than the outer "
                      "diameter %g m of %s at %s",
                      e->inner_diameter, i, e->outer_diameter, key, where);
}

/* The scales of the beam element's matrices must be finite: area and second moment from the
 * diameters, E I and G A from the material, E I / L^3, G A / L, rho A L and rho I / L with the
 * length (the shaft's length or node positions). Each is blamed on the key it grows with. */
static td_status check_element(td_case_reader *r, const config_setting_t *shaft, int owner, const td_shaft_element *e)
{
    const td_material *m = &e->material;
    double d2 = e->outer_diameter * e->outer_diameter, i2 = e->inner_diameter * e->inner_diameter, L = e->length;
    double A = TD_PI / 4.0 * (d2 - i2), I = TD_PI / 64.0 * (d2 * d2 - i2 * i2);
    const config_setting_t *len = config_setting_get_member(shaft, "nodes");
    td_status st;
    if (!len)
        len = config_setting_get_member(shaft, "length");
    st = td_cr_derived(r, element_source(shaft, owner, "outer_diameter", 0), I,
                       "the second moment of area pi (D^4 - d^4) / 64");
    if (st == TD_OK)
        st = td_cr_derived(r, element_source(shaft, owner, "E", 1), m->E * I, "the bending stiffness E I");
    if (st == TD_OK)
        st = td_cr_derived(r, element_source(shaft, owner, "G", 1), m->G * A, "the shear stiffness G A");
    if (st == TD_OK)
        st = td_cr_derived(r, element_source(shaft, owner, "density", 1), m->density * I,
                           "the rotary inertia per length rho I");
    if (st == TD_OK)
        st = td_cr_derived(r, len ? len : shaft, m->E * I / (L * L * L) + m->G * A / L + m->density * I / L,
                           "an element stiffness E I / L^3 from the element length L");
    return st;
}

/* damping { ratio; frequencies = [f1, f2]; } -> Rayleigh alpha, beta (td_rayleigh_from_ratio checks them) */
static td_status read_damping(td_case_reader *r, const config_setting_t *shaft, td_shaft_options *o)
{
    const config_setting_t *g;
    double ratio = 0.0, f[2];
    td_error merr;
    int n = 0;
    td_status st = td_cr_group(r, shaft, "damping", NULL, &g);
    if (st != TD_OK || !g)
        return st;
    st = td_cr_check_keys(r, g, damping_keys);
    if (st == TD_OK && td_cr_has(shaft, "rayleigh"))
        return td_cr_fail(r, g, NULL, "give either 'rayleigh' or 'damping', not both");
    if (st == TD_OK)
        st = td_cr_real(r, g, "ratio", "damping ratio zeta, e.g. 0.01", 0.0, TD_CR_FINITE, &ratio);
    if (st == TD_OK && !td_cr_has(g, "frequencies"))
        return td_cr_fail(r, g, NULL, "missing 'frequencies' (1 or 2 frequencies, Hz, where zeta holds)");
    if (st == TD_OK)
        st = td_cr_reals(r, g, "frequencies", 2, TD_CR_FINITE, f, &n);
    if (st != TD_OK)
        return st;
    st = td_rayleigh_from_ratio(ratio, f, n, &o->rayleigh_alpha, &o->rayleigh_beta, &merr);
    return st == TD_OK ? TD_OK : td_cr_model_fail(r, g, st, &merr);
}

/* shear_coefficient: "hutchinson" (default), "cowper", or a number (model.h td_shear_form; the
 * model checks the number's range). */
static td_status read_shear(td_case_reader *r, const config_setting_t *shaft, td_shaft_options *o)
{
    const config_setting_t *s = config_setting_get_member(shaft, "shear_coefficient");
    int form = TD_SHEAR_HUTCHINSON;
    td_status st;
    if (!s || config_setting_type(s) == CONFIG_TYPE_STRING) {
        st = td_cr_enum(r, shaft, "shear_coefficient", shear_names, 2, TD_SHEAR_HUTCHINSON, &form);
        o->shear = (td_shear_form)form;
        return st;
    }
    o->shear = TD_SHEAR_GIVEN;
    return td_cr_value_real(r, s, TD_CR_FINITE, &o->shear_value);
}

/* beam, mass, rayleigh { alpha; beta; } or damping { ratio; frequencies; } */
static td_status read_shaft_options(td_case_reader *r, const config_setting_t *shaft)
{
    const config_setting_t *ray;
    td_shaft_options o;
    td_error merr;
    int beam, mass;
    td_status st;
    memset(&o, 0, sizeof o);
    st = td_cr_enum(r, shaft, "beam", beam_names, 2, TD_BEAM_EULER_BERNOULLI, &beam);
    if (st == TD_OK)
        st = td_cr_enum(r, shaft, "mass", mass_names, 2, TD_MASS_CONSISTENT, &mass);
    if (st == TD_OK)
        st = td_cr_group(r, shaft, "rayleigh", NULL, &ray);
    if (st == TD_OK && ray) {
        st = td_cr_check_keys(r, ray, rayleigh_keys);
        if (st == TD_OK)
            st = td_cr_real(r, ray, "alpha", NULL, 0.0, TD_CR_NONNEGATIVE, &o.rayleigh_alpha);
        if (st == TD_OK)
            st = td_cr_real(r, ray, "beta", NULL, 0.0, TD_CR_NONNEGATIVE, &o.rayleigh_beta);
    }
    if (st == TD_OK)
        st = read_damping(r, shaft, &o);
    if (st == TD_OK)
        st = read_shear(r, shaft, &o);
    if (st != TD_OK)
        return st;
    o.beam = (td_beam_theory)beam;
    o.mass = (td_mass_form)mass;
    st = td_model_set_shaft_options(r->c->model, &o, &merr);
    return st == TD_OK ? TD_OK : td_cr_model_fail(r, shaft, st, &merr);
}

/* Fill els[0..count) from the shaft defaults and the sections. */
static td_status read_elements(td_case_reader *r, const config_setting_t *shaft, td_shaft_element *els, int count,
                               int *owner)
{
    const config_setting_t *mat, *sections, *sec;
    td_shaft_element proto;
    int i;
    td_status st;

    memset(&proto, 0, sizeof proto);
    st = td_cr_real(r, shaft, "outer_diameter", "outer diameter of every element, m", 0.0, TD_CR_POSITIVE,
                    &proto.outer_diameter);
    if (st == TD_OK)
        st = td_cr_real(r, shaft, "inner_diameter", NULL, 0.0, TD_CR_NONNEGATIVE, &proto.inner_diameter);
    if (st == TD_OK)
        st = td_cr_group(r, shaft, "material", "material { E; G; density; } of the shaft", &mat);
    if (st == TD_OK)
        st = read_material(r, mat, 0, &proto.material);
    if (st != TD_OK)
        return st;
    for (i = 0; i < count; i++) {
        double length = els[i].length;
        els[i] = proto;
        els[i].length = length;
        owner[i] = -1;
    }
    st = td_cr_list(r, shaft, "sections", &sections);
    for (i = 0; st == TD_OK && sections && i < config_setting_length(sections); i++) {
        st = td_cr_entry(r, sections, i, &sec);
        if (st == TD_OK)
            st = read_section(r, sec, count, owner, i, els);
    }
    return st;
}

/* refine: the element count multiplier applied once the whole case is read (case.c); node
 * numbers in the case stay those of the elements as written. */
static td_status read_refine(td_case_reader *r, const config_setting_t *shaft, int count)
{
    td_status st = td_cr_int(r, shaft, "refine", NULL, 1, 1, TD_CASE_MAX_ELEMENTS, &r->refine);
    if (st == TD_OK && count > TD_CASE_MAX_ELEMENTS / r->refine)
        st = td_cr_fail(r, config_setting_get_member(shaft, "refine"), NULL,
                        "%d elements split %d times make %ld (at most %d)", count, r->refine, (long)count * r->refine,
                        TD_CASE_MAX_ELEMENTS);
    return st;
}

td_status td_cr_read_shaft(td_case_reader *r, const config_setting_t *root)
{
    const config_setting_t *shaft;
    td_shaft_element *els = NULL;
    double *lengths = NULL;
    int *owner = NULL, count = 0, i;
    td_error merr;
    td_status st =
        td_cr_group(r, root, "shaft", "the shaft { length; elements; outer_diameter; material; ... }", &shaft);
    if (st == TD_OK)
        st = td_cr_check_keys(r, shaft, shaft_keys);
    if (st == TD_OK)
        st = read_lengths(r, shaft, &lengths, &count);
    if (st == TD_OK)
        st = read_refine(r, shaft, count);
    if (st != TD_OK) {
        free(lengths);
        return st;
    }
    els = calloc((size_t)count, sizeof *els);
    owner = malloc((size_t)count * sizeof *owner);
    if (!els || !owner) {
        st = td_error_set(r->err, TD_ERR_NOMEM, "%s: out of memory", r->path_shown);
        goto done;
    }
    for (i = 0; i < count; i++)
        els[i].length = lengths[i];
    st = read_elements(r, shaft, els, count, owner);
    for (i = 0; st == TD_OK && i < count; i++) {
        st = check_element(r, shaft, owner[i], &els[i]);
        if (st != TD_OK)
            break;
        st = td_model_add_shaft_element(r->c->model, &els[i], &merr);
        if (st != TD_OK)
            st = element_fail(r, shaft, owner[i], i, &els[i], st, &merr);
    }
    if (st == TD_OK)
        st = read_shaft_options(r, shaft);
    r->nodes = count + 1;
done:
    free(lengths);
    free(els);
    free(owner);
    return st;
}
