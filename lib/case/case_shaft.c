/*
 * The "shaft" group: geometry (uniform length + elements, or node positions), per-element
 * diameters and material with sections for stepped and hollow shafts, beam theory, mass form
 * and Rayleigh damping. Element i joins nodes i and i + 1 (touchdown/model.h).
 */
#include "case/case_schema.h"
#include "touchdown/dofs.h"
#include "util/error_internal.h"

#include <stdlib.h>
#include <string.h>

static const char *const beam_names[] = {"euler-bernoulli", "timoshenko"};
static const char *const mass_names[] = {"consistent", "lumped"};
static const char *const shear_names[] = {"hutchinson", "cowper"};

/* What the shaft group gives, while it is read: the element lengths, the shaft's element (every
 * element's diameters and material before the sections), the elements and the section that set
 * each (owner, -1: none), and the options. */
typedef struct shaft_rec {
    double *lengths;
    int count;
    td_shaft_element proto;
    td_shaft_element *els;
    int *owner;
    td_shaft_options o;
} shaft_rec;

/* A section of the shaft while it is read: its elements [from, to] and what it sets on them. */
typedef struct section_rec {
    shaft_rec *shaft;
    int index;
    int from, to;
    td_shaft_element proto;
} section_rec;

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

static const td_cs_key material_keys[] = {
    {.key = "E",
     .type = TD_CS_REAL,
     .offset = offsetof(td_material, E),
     .need = TD_CS_REQUIRED,
     .range = TD_CR_POSITIVE,
     .what = "Young's modulus, Pa",
     .unit = "Pa",
     .doc = "Young's modulus"},
    {.key = "G",
     .type = TD_CS_REAL,
     .offset = offsetof(td_material, G),
     .need = TD_CS_REQUIRED,
     .range = TD_CR_POSITIVE,
     .what = "shear modulus, Pa",
     .unit = "Pa",
     .doc = "shear modulus (used by Timoshenko beams)"},
    {.key = "density",
     .type = TD_CS_REAL,
     .offset = offsetof(td_material, density),
     .need = TD_CS_REQUIRED,
     .range = TD_CR_POSITIVE,
     .what = "density, kg/m^3",
     .unit = "kg/m^3",
     .doc = "density"},
};
static const td_cs_table material_table = {"shaft.material",    NULL, material_keys, TD_CS_COUNT(material_keys),
                                           sizeof(td_material), NULL, NULL};

/* A section's material: each key given replaces the shaft's. */
static const td_cs_key section_material_keys[] = {
    {.key = "E",
     .type = TD_CS_REAL,
     .offset = offsetof(td_material, E),
     .need = TD_CS_PRESET,
     .range = TD_CR_POSITIVE,
     .doc_default = "the shaft's",
     .unit = "Pa",
     .doc = "Young's modulus in the section"},
    {.key = "G",
     .type = TD_CS_REAL,
     .offset = offsetof(td_material, G),
     .need = TD_CS_PRESET,
     .range = TD_CR_POSITIVE,
     .doc_default = "the shaft's",
     .unit = "Pa",
     .doc = "shear modulus in the section"},
    {.key = "density",
     .type = TD_CS_REAL,
     .offset = offsetof(td_material, density),
     .need = TD_CS_PRESET,
     .range = TD_CR_POSITIVE,
     .doc_default = "the shaft's",
     .unit = "kg/m^3",
     .doc = "density in the section"},
};
static const td_cs_table section_material_table = {"shaft.sections[].material",
                                                   NULL,
                                                   section_material_keys,
                                                   TD_CS_COUNT(section_material_keys),
                                                   sizeof(td_material),
                                                   NULL,
                                                   NULL};

/* Element index `key` of section sec, 0 .. count - 1: the bound is the shaft's, so a value past it
 * also says where the shaft's elements were written (a --set may have changed them). */
static td_status read_element(td_case_reader *r, const config_setting_t *sec, const char *key, const char *what,
                              int count, int *out)
{
    td_status st = td_cr_int(r, sec, key, what, 0, TD_CR_ANY_INT_LO, TD_CR_ANY_INT_HI, out);
    if (st == TD_OK && (*out < 0 || *out > count - 1))
        return td_cr_fail_vs(r, config_setting_get_member(sec, key), *out < 0 ? NULL : td_cr_shaft_nodes(r),
                             "must lie in [0, %d] (got %d)", count - 1, *out);
    return st;
}

/* A section's elements: `element`, or `from` + `to`; they start from the element at `from`. */
static td_status read_section_range(td_case_reader *r, const config_setting_t *sec, const td_cs_key *k, void *rec)
{
    section_rec *sr = rec;
    int count = sr->shaft->count;
    td_status st;
    (void)k;
    if (td_cr_has(sec, "element")) {
        if (td_cr_has(sec, "from") || td_cr_has(sec, "to"))
            return td_cr_fail(r, config_setting_get_member(sec, "element"), NULL,
                              "give either 'element' or 'from' + 'to', not both");
        st = read_element(r, sec, "element", NULL, count, &sr->from);
        sr->to = sr->from;
    } else {
        st = read_element(r, sec, "from", "first element of the section; or give 'element'", count, &sr->from);
        if (st == TD_OK)
            st = read_element(r, sec, "to", "last element of the section (inclusive)", count, &sr->to);
        if (st == TD_OK && sr->to < sr->from)
            return td_cr_fail(r, config_setting_get_member(sec, "to"), NULL, "must be >= from (%d), got %d", sr->from,
                              sr->to);
    }
    if (st == TD_OK)
        sr->proto = sr->shaft->els[sr->from];
    return st;
}

/* The section's element put on each of its elements, which no other section may hold. */
static td_status place_section(td_case_reader *r, const config_setting_t *sec, void *rec)
{
    section_rec *sr = rec;
    shaft_rec *sh = sr->shaft;
    int i;
    for (i = sr->from; i <= sr->to; i++) {
        if (sh->owner[i] >= 0)
            return td_cr_fail(r, sec, NULL, "element %d is already in sections[%d]; sections must not overlap", i,
                              sh->owner[i]);
        sh->owner[i] = sr->index;
        sr->proto.length = sh->els[i].length;
        sh->els[i] = sr->proto;
    }
    return TD_OK;
}

#define SECTION_PROTO(field) (offsetof(section_rec, proto) + offsetof(td_shaft_element, field))
#define FORM .read = td_cs_elsewhere

static const td_cs_key section_keys[] = {
    {.key = "element",
     .type = TD_CS_INT,
     .read = read_section_range,
     .doc_range = "an element of the shaft",
     .doc_default = "-",
     .doc = "the one element of the section (instead of `from` + `to`)"},
    {.key = "from",
     .type = TD_CS_INT,
     FORM,
     .doc_range = "an element of the shaft",
     .doc_default = "required without `element`",
     .doc = "first element of the section"},
    {.key = "to",
     .type = TD_CS_INT,
     FORM,
     .doc_range = ">= from",
     .doc_default = "required with `from`",
     .doc = "last element of the section (inclusive)"},
    {.key = "outer_diameter",
     .type = TD_CS_REAL,
     .offset = SECTION_PROTO(outer_diameter),
     .need = TD_CS_PRESET,
     .range = TD_CR_POSITIVE,
     .doc_default = "the shaft's",
     .unit = "m",
     .doc = "outer diameter in the section"},
    {.key = "inner_diameter",
     .type = TD_CS_REAL,
     .offset = SECTION_PROTO(inner_diameter),
     .need = TD_CS_PRESET,
     .range = TD_CR_NONNEGATIVE,
     .doc_default = "the shaft's",
     .unit = "m",
     .doc = "inner diameter in the section"},
    {.key = "material",
     .type = TD_CS_GROUP,
     .offset = SECTION_PROTO(material),
     .sub = &section_material_table,
     .doc_default = "the shaft's",
     .doc = "`E`, `G`, `density`: each one given replaces the shaft's"},
};
/* read by read_sections with the shaft's record at hand (not as a list of records of their own) */
static const td_cs_table section_table = {"shaft.sections[]",  NULL, section_keys, TD_CS_COUNT(section_keys),
                                          sizeof(section_rec), NULL, place_section};

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

/* damping { ratio; frequencies = [f1, f2]; }: read by read_damping */
static const td_cs_key damping_keys[] = {
    {.key = "ratio",
     .type = TD_CS_REAL,
     FORM,
     .need = TD_CS_REQUIRED,
     .doc_range = "0 <= ratio < 1",
     .doc = "damping ratio zeta (a loss factor eta is 2 zeta)"},
    {.key = "frequencies",
     .type = TD_CS_REALS,
     FORM,
     .need = TD_CS_REQUIRED,
     .hi = 2,
     .doc_type = "1 or 2 numbers",
     .doc_range = "> 0, increasing",
     .unit = "Hz",
     .doc = "where zeta holds exactly. Two: the Rayleigh fit alpha = 2 zeta w1 w2 / (w1 + w2), beta = 2 zeta / (w1 + "
            "w2) with w = 2 pi f. One: stiffness-proportional only, alpha = 0, beta = 2 zeta / w1. The ratio the model "
            "gets at angular frequency w is zeta(w) = alpha / (2 w) + beta w / 2: exact at the given frequencies, "
            "below zeta between two of them, above zeta outside them (growing with w above the highest); `touchdown "
            "info` prints alpha and beta to check that curve"},
};
static const td_cs_table damping_table = {
    "shaft.damping", NULL, damping_keys, TD_CS_COUNT(damping_keys), 0, NULL, NULL};

/* damping { ratio; frequencies = [f1, f2]; } -> Rayleigh alpha, beta (td_rayleigh_from_ratio checks them) */
static td_status read_damping(td_case_reader *r, const config_setting_t *shaft, const td_cs_key *k, void *rec)
{
    td_shaft_options *o = &((shaft_rec *)rec)->o;
    const config_setting_t *g;
    double ratio = 0.0, f[2];
    td_error merr;
    int n = 0;
    td_status st = td_cr_group(r, shaft, k->key, NULL, &g);
    if (st != TD_OK || !g)
        return st;
    st = td_cs_check_keys(r, g, &damping_table);
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
static td_status read_shear(td_case_reader *r, const config_setting_t *shaft, const td_cs_key *k, void *rec)
{
    td_shaft_options *o = &((shaft_rec *)rec)->o;
    const config_setting_t *s = config_setting_get_member(shaft, k->key);
    int form = TD_SHEAR_HUTCHINSON;
    td_status st;
    if (!s || config_setting_type(s) == CONFIG_TYPE_STRING) {
        st = td_cr_enum(r, shaft, k->key, shear_names, 2, TD_SHEAR_HUTCHINSON, &form);
        o->shear = (td_shear_form)form;
        return st;
    }
    o->shear = TD_SHEAR_GIVEN;
    return td_cr_value_real(r, s, TD_CR_FINITE, &o->shear_value);
}

static const td_cs_key rayleigh_keys[] = {
    {.key = "alpha",
     .type = TD_CS_REAL,
     .offset = offsetof(td_shaft_options, rayleigh_alpha),
     .range = TD_CR_NONNEGATIVE,
     .unit = "1/s",
     .doc = "mass-proportional coefficient"},
    {.key = "beta",
     .type = TD_CS_REAL,
     .offset = offsetof(td_shaft_options, rayleigh_beta),
     .range = TD_CR_NONNEGATIVE,
     .unit = "s",
     .doc = "stiffness-proportional coefficient"},
};
static const td_cs_table rayleigh_table = {"shaft.rayleigh",         NULL, rayleigh_keys, TD_CS_COUNT(rayleigh_keys),
                                           sizeof(td_shaft_options), NULL, NULL};

/* shaft.length + elements, or shaft.nodes: the element lengths */
static td_status read_geometry(td_case_reader *r, const config_setting_t *shaft, const td_cs_key *k, void *rec)
{
    shaft_rec *sh = rec;
    (void)k;
    return read_lengths(r, shaft, &sh->lengths, &sh->count);
}

/* refine: the element count multiplier applied once the whole case is read (case.c); node
 * numbers in the case stay those of the elements as written. */
static td_status read_refine(td_case_reader *r, const config_setting_t *shaft, const td_cs_key *k, void *rec)
{
    int count = ((shaft_rec *)rec)->count;
    td_status st = td_cr_int(r, shaft, k->key, NULL, (int)k->def, k->lo, k->hi, &r->refine);
    if (st == TD_OK && count > TD_CASE_MAX_ELEMENTS / r->refine)
        st = td_cr_fail(r, config_setting_get_member(shaft, k->key), NULL,
                        "%d elements split %d times make %ld (at most %d)", count, r->refine, (long)count * r->refine,
                        TD_CASE_MAX_ELEMENTS);
    return st;
}

/* Every element from the shaft's, then the sections over them. */
static td_status read_sections(td_case_reader *r, const config_setting_t *shaft, const td_cs_key *k, void *rec)
{
    shaft_rec *sh = rec;
    const config_setting_t *sections, *sec;
    section_rec sr;
    int i;
    td_status st;
    sh->els = calloc((size_t)sh->count, sizeof *sh->els);
    sh->owner = malloc((size_t)sh->count * sizeof *sh->owner);
    if (!sh->els || !sh->owner)
        return td_error_set(r->err, TD_ERR_NOMEM, "%s: out of memory", r->path_shown);
    for (i = 0; i < sh->count; i++) {
        sh->els[i] = sh->proto;
        sh->els[i].length = sh->lengths[i];
        sh->owner[i] = -1;
    }
    st = td_cr_list(r, shaft, k->key, &sections);
    for (i = 0; st == TD_OK && sections && i < config_setting_length(sections); i++) {
        st = td_cr_entry(r, sections, i, &sec);
        memset(&sr, 0, sizeof sr);
        sr.shaft = sh;
        sr.index = i;
        if (st == TD_OK)
            st = td_cs_read(r, sec, &section_table, &sr);
    }
    return st;
}

/* The elements, checked and added to the model (once the sections are read). */
static td_status add_elements(td_case_reader *r, const config_setting_t *shaft, const td_cs_key *k, void *rec)
{
    shaft_rec *sh = rec;
    td_error merr;
    int i;
    td_status st = TD_OK;
    (void)k;
    for (i = 0; st == TD_OK && i < sh->count; i++) {
        st = check_element(r, shaft, sh->owner[i], &sh->els[i]);
        if (st != TD_OK)
            break;
        st = td_model_add_shaft_element(r->c->model, &sh->els[i], &merr);
        if (st != TD_OK)
            st = element_fail(r, shaft, sh->owner[i], i, &sh->els[i], st, &merr);
    }
    return st;
}

static td_status set_shaft_options(td_case_reader *r, const config_setting_t *shaft, void *rec)
{
    shaft_rec *sh = rec;
    td_error merr;
    td_status st;
    r->nodes = sh->count + 1;
    st = td_model_set_shaft_options(r->c->model, &sh->o, &merr);
    return st == TD_OK ? TD_OK : td_cr_model_fail(r, shaft, st, &merr);
}

#define SHAFT_PROTO(field) (offsetof(shaft_rec, proto) + offsetof(td_shaft_element, field))
#define SHAFT_OPTION(field) (offsetof(shaft_rec, o) + offsetof(td_shaft_options, field))

/* Read in order: the lengths, refine, the shaft's element, the sections, the options. */
static const td_cs_key shaft_keys[] = {
    {.key = "length",
     .type = TD_CS_REAL,
     .read = read_geometry,
     .range = TD_CR_POSITIVE,
     .doc_default = "required unless `nodes`",
     .unit = "m",
     .doc = "total length, divided into `elements` equal elements"},
    {.key = "elements",
     .type = TD_CS_INT,
     FORM,
     .lo = 1,
     .hi = TD_CASE_MAX_ELEMENTS,
     .doc_default = "required with `length`",
     .doc = "number of elements (nodes = elements + 1)"},
    {.key = "nodes",
     .type = TD_CS_REALS,
     FORM,
     .hi = TD_CASE_MAX_ELEMENTS + 1,
     .doc_range = "strictly increasing, 2 to 10001 of them",
     .doc_default = "-",
     .unit = "m",
     .doc = "axial node positions, strictly increasing, 2 to 10001 of them; element lengths are their differences"},
    {.key = "outer_diameter",
     .type = TD_CS_REAL,
     .offset = SHAFT_PROTO(outer_diameter),
     .need = TD_CS_REQUIRED,
     .range = TD_CR_POSITIVE,
     .order = 2,
     .what = "outer diameter of every element, m",
     .unit = "m",
     .doc = "outer diameter of every element"},
    {.key = "inner_diameter",
     .type = TD_CS_REAL,
     .offset = SHAFT_PROTO(inner_diameter),
     .range = TD_CR_NONNEGATIVE,
     .order = 2,
     .doc_range = ">= 0, below the outer diameter",
     .unit = "m",
     .doc = "bore of every element (hollow shaft); must be below the outer diameter"},
    {.key = "material",
     .type = TD_CS_GROUP,
     .offset = SHAFT_PROTO(material),
     .sub = &material_table,
     .need = TD_CS_REQUIRED,
     .order = 2,
     .what = "material { E; G; density; } of the shaft",
     .doc = "material of every element:"},
    {.key = "sections",
     .type = TD_CS_LIST,
     .sub = &section_table,
     .read = read_sections,
     .check = add_elements,
     .order = 3,
     .doc = "changes for ranges of elements; sections must not overlap"},
    {.key = "beam",
     .type = TD_CS_ENUM,
     .offset = SHAFT_OPTION(beam),
     .names = beam_names,
     .name_count = 2,
     .order = 4,
     .doc = "beam theory (Timoshenko includes shear deformation)"},
    {.key = "mass",
     .type = TD_CS_ENUM,
     .offset = SHAFT_OPTION(mass),
     .names = mass_names,
     .name_count = 2,
     .order = 4,
     .doc = "element mass matrix: consistent with rotary inertia, or half of each element's mass and rotary inertia at "
            "each end (the paper's form)"},
    {.key = "rayleigh",
     .type = TD_CS_GROUP,
     .offset = offsetof(shaft_rec, o),
     .sub = &rayleigh_table,
     .order = 4,
     .doc = "structural damping of the shaft, C += alpha M + beta K:"},
    {.key = "refine",
     .type = TD_CS_INT,
     .read = read_refine,
     .lo = 1,
     .hi = TD_CASE_MAX_ELEMENTS,
     .def = 1,
     .order = 1,
     .doc = "split every element into this many equal ones, for mesh-convergence checks (at most 10000 elements in "
            "all). Every node number in the case (parts, `output.nodes`) stays that of the shaft as written: node i "
            "becomes node `refine` * i, at the same axial position. Outputs, events and `touchdown info` use the "
            "refined numbering. The steady-orbit start is a dense solve: about 1.4 s at 772 DOFs, 53 s at 2,404 "
            "(docs/performance.md)"},
    {.key = "damping",
     .type = TD_CS_GROUP,
     .sub = &damping_table,
     .read = read_damping,
     .order = 4,
     .doc = "structural damping of the shaft as a damping ratio, turned into `rayleigh` alpha and beta "
            "(`td_rayleigh_from_ratio`, docs/theory.md); give `rayleigh` or `damping`, not both"},
    {.key = "shear_coefficient",
     .type = TD_CS_CUSTOM,
     .read = read_shear,
     .order = 4,
     .doc_type = "`\"hutchinson\"`, `\"cowper\"` or a number",
     .doc_range = "a number: in (0, 1]",
     .doc_default = "`\"hutchinson\"`",
     .doc = "Timoshenko shear coefficient kappa of the hollow circular sections: Hutchinson (2001) or Cowper (1966, as "
            "in Friswell et al. 2010 and ROSS) from Poisson's ratio nu = E/(2G) - 1 and the diameter ratio, or one "
            "value for every element ([theory](theory.md#the-rotor-eq-1)); Euler-Bernoulli beams ignore it"},
};
const td_cs_table td_cs_shaft = {"shaft",           "shaft", shaft_keys,       TD_CS_COUNT(shaft_keys),
                                 sizeof(shaft_rec), NULL,    set_shaft_options};

td_status td_cr_read_shaft(td_case_reader *r, const config_setting_t *root)
{
    const config_setting_t *shaft;
    shaft_rec sh;
    td_status st =
        td_cr_group(r, root, "shaft", "the shaft { length; elements; outer_diameter; material; ... }", &shaft);
    if (st != TD_OK)
        return st;
    memset(&sh, 0, sizeof sh);
    st = td_cs_read(r, shaft, &td_cs_shaft, &sh);
    free(sh.lengths);
    free(sh.els);
    free(sh.owner);
    return st;
}
