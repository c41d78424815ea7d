/*
 * The `controllers` table: each entry a linear controller over AMBs of the case, its law built of
 * blocks in series (case_blocks.c) with the controller API (touchdown/controller.h), in bearing
 * coordinates (the law on each axis of each AMB) or in rigid-body coordinates (a translation and a
 * tilt law in each lateral plane of two AMBs, td_rigid_transform), continuous or sampled, and
 * handed to the model (td_model_add_controller), whose rules (axes in range, each axis driven
 * once, unique names) it keeps. The reader checks what is about the file: the forms, the AMBs it
 * names (their nodes' positions make the rigid-body transform), a sample rate for what needs one.
 *
 * Axis order of a controller's inputs and outputs (the model numbers AMB axes 2 amb + axis):
 * bearing, AMB by AMB as listed, x then y; rigid, plane x (AMB a, AMB b) then plane y.
 */
#include "case/case_schema.h"
#include "util/error_internal.h"

#include <stdlib.h>
#include <string.h>

/* The most AMBs one controller drives (two axes each). */
#define CC_MAX_AMBS 16
/* The most samples of computation delay (a DSP is one to a few samples late; each sample of delay adds
 * a state per output to the analyses' dense eigenproblem). */
#define CC_MAX_DELAY 100

static const char *const coordinate_names[] = {"bearing", "rigid"};
static const char *const discretisation_names[] = {"tustin", "zoh"}; /* td_discretisation order */

typedef struct cc_rec {
    const char *name;
    int ambs[CC_MAX_AMBS];
    int amb_count;
    int rigid;
    double reference_z;
    double sample_rate; /* Hz; 0: continuous */
    int discretisation;
    double prewarp;
    int delay;
    int discretised;     /* runs of blocks in s sampled by `discretisation` so far */
    td_cr_plugin plugin; /* the `plugin` group (case_plugin.c); library NULL: a law */
} cc_rec;

/* ambs: at least one, each an AMB of the case (the model has read them). */
static td_status read_ambs(td_case_reader *r, const config_setting_t *g, const td_cs_key *k, void *rec)
{
    cc_rec *c = rec;
    const config_setting_t *s = config_setting_get_member(g, k->key);
    int i, n = td_model_amb_count(r->c->model);
    td_status st = td_cr_ints(r, g, k->key, CC_MAX_AMBS, TD_CR_ANY_INT_LO, TD_CR_ANY_INT_HI, c->ambs, &c->amb_count);
    if (st != TD_OK)
        return st;
    if (!s)
        return td_cr_missing(r, g, k->key, k->what);
    if (c->amb_count == 0)
        return td_cr_fail(r, s, NULL, "a controller drives at least one AMB");
    for (i = 0; i < c->amb_count; i++)
        if (c->ambs[i] < 0 || c->ambs[i] >= n)
            return td_cr_fail(r, config_setting_get_elem(s, (unsigned)i), NULL,
                              "AMB %d does not exist (%d defined in `ambs`, indices start at 0)", c->ambs[i], n);
    return TD_OK;
}

/* coordinates: "rigid" takes exactly two AMBs. */
static td_status check_coordinates(td_case_reader *r, const config_setting_t *g, const td_cs_key *k, void *rec)
{
    const cc_rec *c = rec;
    (void)k;
    if (c->rigid && c->amb_count != 2)
        return td_cr_fail(r, config_setting_get_member(g, "coordinates"), NULL,
                          "rigid-body coordinates take exactly two AMBs (`ambs` lists %d)", c->amb_count);
    return TD_OK;
}

/* reference_z: rigid only; absent, the rotor's mass centre. */
static td_status read_reference_z(td_case_reader *r, const config_setting_t *g, const td_cs_key *k, void *rec)
{
    cc_rec *c = rec;
    const td_model *m = r->c->model;
    double length = td_model_node_position(m, td_model_node_count(m) - 1);
    td_status st;
    if (!c->rigid && td_cr_has(g, k->key))
        return td_cr_fail(r, config_setting_get_member(g, k->key), NULL,
                          "reference_z is the rigid-body reference: it needs coordinates = \"rigid\"");
    if (!c->rigid)
        return TD_OK;
    st = td_cr_real(r, g, k->key, NULL, td_model_mass_centre(m), TD_CR_FINITE, &c->reference_z);
    if (st == TD_OK && !(c->reference_z >= 0.0 && c->reference_z <= length)) /* a point of the rotor */
        return td_cr_fail(r, config_setting_get_member(g, k->key), NULL, "must lie on the shaft, 0 to %g m (got %g)",
                          length, c->reference_z);
    return st;
}

/* law (bearing), or translation and tilt (rigid): which the coordinates need, each a list; none
 * with a plug-in, which is the law. */
static td_status check_laws(td_case_reader *r, const config_setting_t *g, const td_cs_key *k, void *rec)
{
    static const char *const keys[] = {"law", "translation", "tilt"};
    const cc_rec *c = rec;
    const config_setting_t *list;
    int i, plugin = td_cr_has(g, "plugin");
    (void)k;
    for (i = 0; i < 3; i++) {
        int wanted = !plugin && (i == 0) != (c->rigid != 0);
        td_status st = td_cr_list(r, g, keys[i], &list);
        if (st != TD_OK)
            return st;
        if (!list && wanted)
            return td_cr_missing(r, g, keys[i],
                                 c->rigid ? "rigid coordinates: the blocks of the translation and of the tilt law"
                                          : "the blocks of the law in series, or a `plugin`");
        if (list && !wanted)
            return td_cr_fail(r, list, NULL, "%s",
                              plugin     ? "a plug-in controller's law is its plug-in: give `plugin` or a law, not both"
                              : c->rigid ? "rigid coordinates take `translation` and `tilt`, not `law`"
                                         : "`translation` and `tilt` need coordinates = \"rigid\"");
        if (list && config_setting_length(list) == 0)
            return td_cr_fail(r, list, NULL, "a law has at least one block, e.g. ( { gain = 1.0; } )");
    }
    return TD_OK;
}

/* plugin: sampled, on the AMBs' own axes; what acts on a law's blocks in s it has none of. */
static td_status check_plugin(td_case_reader *r, const config_setting_t *g, const td_cs_key *k, void *rec)
{
    static const char *const keys[] = {"discretisation", "prewarp"};
    const cc_rec *c = rec;
    int i;
    (void)k;
    if (!c->plugin.library)
        return TD_OK;
    if (c->rigid)
        return td_cr_fail(r, config_setting_get_member(g, "coordinates"), NULL,
                          "a plug-in reads and drives each AMB axis itself: coordinates = \"bearing\" only");
    if (!(c->sample_rate > 0.0))
        return td_cr_missing(r, g, "sample_rate", "a plug-in runs sampled: the rate its step is called at, Hz");
    for (i = 0; i < 2; i++)
        if (td_cr_has(g, keys[i]))
            return td_cr_fail(r, config_setting_get_member(g, keys[i]), NULL,
                              "%s applies to a law's blocks, and a plug-in controller has none", keys[i]);
    return TD_OK;
}

/* discretisation, prewarp and delay: what only a sampled controller has. */
static td_status check_sampled(td_case_reader *r, const config_setting_t *g, const td_cs_key *k, void *rec)
{
    const cc_rec *c = rec;
    const config_setting_t *s = config_setting_get_member(g, k->key);
    int set = strcmp(k->key, "delay") == 0     ? c->delay > 0
              : strcmp(k->key, "prewarp") == 0 ? c->prewarp > 0.0
                                               : c->discretisation != TD_DISCRETISE_TUSTIN;
    if (set && !(c->sample_rate > 0.0))
        return td_cr_fail(r, s, NULL, "%s applies to a sampled controller: give its sample_rate", k->key);
    if (set && strcmp(k->key, "prewarp") == 0 && c->discretisation != TD_DISCRETISE_TUSTIN)
        return td_cr_fail(r, s, NULL, "prewarp applies to discretisation = \"tustin\" only");
    return TD_OK;
}

/* *first then second in series (second not NULL; *first NULL: second alone), freeing both; a
 * failure located at block e. */
static td_status chain(td_case_reader *r, const config_setting_t *e, td_controller **first, td_controller *second)
{
    td_controller *k;
    td_error merr;
    if (!*first) {
        *first = second;
        return TD_OK;
    }
    k = td_controller_series(*first, second, &merr);
    td_controller_free(first);
    td_controller_free(&second);
    *first = k;
    return k ? TD_OK : td_cr_model_fail(r, e, merr.code, &merr);
}

/* The run of blocks in s so far (*run) sampled and put in series after *acc. */
static td_status flush(td_case_reader *r, const config_setting_t *e, cc_rec *c, td_controller **acc,
                       td_controller **run)
{
    td_controller *d;
    td_error merr;
    if (!*run)
        return TD_OK;
    d = td_controller_discretise(*run, c->sample_rate, (td_discretisation)c->discretisation, c->prewarp, &merr);
    td_controller_free(run);
    c->discretised++;
    if (!d && merr.site.field && strcmp(merr.site.field, "prewarp") == 0) /* the controller's key, e's grandparent */
        return td_cr_model_fail(r, config_setting_parent(config_setting_parent(e)), merr.code, &merr);
    if (!d)
        return td_cr_model_fail(r, e, merr.code, &merr);
    return chain(r, e, acc, d);
}

/* The law of list `key` of g, its blocks in series; sampled at c->sample_rate when it has one (each
 * run of blocks in s as a whole, by c's discretisation; a block in z as written). */
static td_status build_law(td_case_reader *r, const config_setting_t *g, const char *key, cc_rec *c,
                           td_controller **out)
{
    const config_setting_t *list = config_setting_get_member(g, key), *e = list;
    td_controller *acc = NULL, *run = NULL, *b = NULL;
    int i, sampled = 0;
    td_status st = TD_OK;
    for (i = 0; st == TD_OK && i < config_setting_length(list); i++) {
        st = td_cr_entry(r, list, i, &e);
        if (st == TD_OK)
            st = td_cr_read_block(r, e, c->sample_rate, &b, &sampled);
        if (st == TD_OK && c->sample_rate > 0.0 && !sampled && td_controller_has_velocity_feedthrough(b))
            st = td_cr_fail(r, e, NULL,
                            "an exact derivative (a pid without derivative_filter, or a law improper by one) "
                            "cannot be sampled: give the derivative a filter");
        if (st == TD_OK && sampled)
            st = flush(r, e, c, &acc, &run);
        if (st == TD_OK)
            st = chain(r, e, sampled || !(c->sample_rate > 0.0) ? &acc : &run, b);
        else
            td_controller_free(&b);
        b = NULL;
    }
    if (st == TD_OK)
        st = flush(r, e, c, &acc, &run);
    td_controller_free(&run);
    if (st != TD_OK)
        td_controller_free(&acc);
    *out = acc;
    return st;
}

/* A controller API failure in putting the controller of entry g together, at the key `key`. */
static td_status api_fail(td_case_reader *r, const config_setting_t *g, const char *key, const td_error *merr)
{
    const config_setting_t *s = config_setting_get_member(g, key);
    if (merr->code == TD_ERR_NOMEM)
        return td_error_set(r->err, TD_ERR_NOMEM, "%s: %s", r->path_shown, merr->message);
    return td_cr_fail(r, s ? s : g, NULL, "%s", merr->message);
}

/* The same SISO law on every axis of the AMBs, AMB by AMB, x then y (block-diagonal). */
static td_controller *bearing_law(const td_controller *law, int axes, td_error *merr)
{
    td_controller *k = td_controller_clone(law, merr), *next;
    int i;
    for (i = 1; k && i < axes; i++) {
        next = td_controller_append(k, law, merr);
        td_controller_free(&k);
        k = next;
    }
    return k;
}

/* The rigid-body transforms of the two AMBs' planes about c->reference_z: Tin from the sensor
 * nodes' z (what the law reads), Tout = T^T from the actuator nodes' z (where it pushes), each
 * block-diagonal over the planes x and y (4 x 4, column-major). */
static td_status rigid_transforms(td_case_reader *r, const config_setting_t *g, const cc_rec *c, double Tin[16],
                                  double Tout[16])
{
    const td_model *m = r->c->model;
    td_amb a, b;
    double Ts[4], Ta[4];
    td_error merr;
    int i, j, nodes = td_model_node_count(m);
    td_model_get_amb(m, c->ambs[0], &a);
    td_model_get_amb(m, c->ambs[1], &b);
    if (a.node < 0 || a.node >= nodes || b.node < 0 || b.node >= nodes || a.sensor_node < 0 || a.sensor_node >= nodes ||
        b.sensor_node < 0 || b.sensor_node >= nodes)
        return td_model_validate(m, &merr) != TD_OK ? td_cr_validate_fail(r, &merr) : TD_ERR_PARSE;
    if (td_rigid_transform(td_model_node_position(m, a.sensor_node), td_model_node_position(m, b.sensor_node),
                           c->reference_z, Ts, &merr) != TD_OK ||
        td_rigid_transform(td_model_node_position(m, a.node), td_model_node_position(m, b.node), c->reference_z, Ta,
                           &merr) != TD_OK)
        return api_fail(r, g, "ambs", &merr);
    memset(Tin, 0, 16 * sizeof *Tin);
    memset(Tout, 0, 16 * sizeof *Tout);
    for (i = 0; i < 2; i++)
        for (j = 0; j < 2; j++) {
            Tin[i + 4 * j] = Tin[(i + 2) + 4 * (j + 2)] = Ts[i + 2 * j];
            Tout[i + 4 * j] = Tout[(i + 2) + 4 * (j + 2)] = Ta[j + 2 * i]; /* transposed */
        }
    return TD_OK;
}

/* Translation and tilt in each plane, [x_r, tilt] of plane x then of plane y, made bearing
 * currents: i = Tout K (Tin e). */
static td_status rigid_law(td_case_reader *r, const config_setting_t *g, cc_rec *c, td_controller **out)
{
    td_controller *t = NULL, *tilt = NULL, *plane = NULL, *both = NULL;
    double Tin[16], Tout[16];
    td_error merr;
    td_status st = rigid_transforms(r, g, c, Tin, Tout);
    if (st == TD_OK)
        st = build_law(r, g, "translation", c, &t);
    if (st == TD_OK)
        st = build_law(r, g, "tilt", c, &tilt);
    if (st == TD_OK &&
        (!(plane = td_controller_append(t, tilt, &merr)) || !(both = td_controller_append(plane, plane, &merr)) ||
         !(*out = td_controller_transform(both, 4, Tin, 4, Tout, &merr))))
        st = api_fail(r, g, "tilt", &merr);
    td_controller_free(&t);
    td_controller_free(&tilt);
    td_controller_free(&plane);
    td_controller_free(&both);
    return st;
}

/* The whole controller of entry g: its law over its axes, with its delay; inputs = outputs = the
 * axes in the controller's order. */
static td_status build_controller(td_case_reader *r, const config_setting_t *g, cc_rec *c, td_controller **out,
                                  int *axes)
{
    td_controller *k = NULL, *law = NULL;
    td_error merr;
    int i;
    td_status st = c->rigid ? rigid_law(r, g, c, &k) : build_law(r, g, "law", c, &law);
    if (st == TD_OK && !c->rigid && !(k = bearing_law(law, 2 * c->amb_count, &merr)))
        st = api_fail(r, g, "law", &merr);
    td_controller_free(&law);
    if (st == TD_OK && c->delay > 0) {
        law = td_controller_delay(k, c->delay, &merr);
        td_controller_free(&k);
        k = law;
        if (!k)
            st = api_fail(r, g, "delay", &merr);
    }
    for (i = 0; i < 2 * c->amb_count; i++) /* bearing: a x, a y, b x, ...; rigid: a x, b x, a y, b y */
        axes[i] = c->rigid ? 2 * c->ambs[i % 2] + i / 2 : 2 * c->ambs[i / 2] + i % 2;
    *out = st == TD_OK ? k : NULL;
    return st;
}

/* "FILE:LINE: controllers[i].plugin.library" of entry g's plug-in, a new string (NULL: none, or out
 * of memory). */
static char *plugin_where(const td_case_reader *r, const config_setting_t *g)
{
    const config_setting_t *s = config_setting_lookup((config_setting_t *)g, "plugin.library");
    char where[1200], key[512], *out;
    if (!s)
        return NULL;
    td_cr_where(r, s, where, sizeof where);
    td_cr_key(s, key, sizeof key);
    if ((out = malloc(strlen(where) + strlen(key) + 3)) != NULL)
        sprintf(out, "%s: %s", where, key);
    return out;
}

/* The case's own account of controller entry c (td_case_controller). */
static td_status keep_info(td_case_reader *r, const config_setting_t *g, const cc_rec *c)
{
    td_case *cs = r->c;
    td_case_controller_info *info = realloc(cs->controllers, (size_t)(cs->controller_count + 1) * sizeof *info);
    if (!info)
        return td_cr_fail_file(r->err, TD_ERR_NOMEM, r->path_shown, 0, "out of memory");
    cs->controllers = info;
    info += cs->controller_count++;
    memset(info, 0, sizeof *info);
    info->rigid = c->rigid;
    info->reference_z = c->rigid ? c->reference_z : 0.0;
    info->delay = c->delay;
    info->discretisation = (td_discretisation)c->discretisation;
    info->prewarp = c->prewarp;
    info->discretised = c->discretised > 0;
    info->plugin = c->plugin.library != NULL;
    if (info->plugin && !(info->where = plugin_where(r, g)))
        return td_cr_fail_file(r->err, TD_ERR_NOMEM, r->path_shown, 0, "out of memory");
    return TD_OK;
}

/* discretisation and prewarp act on the blocks in s: written for a law all in z, they would do nothing. */
static td_status check_sampled_nothing(td_case_reader *r, const config_setting_t *g, const cc_rec *c)
{
    static const char *const keys[] = {"discretisation", "prewarp"};
    int i;
    for (i = 0; i < 2 && c->sample_rate > 0.0 && !c->discretised; i++)
        if (td_cr_has(g, keys[i]))
            return td_cr_fail(r, config_setting_get_member(g, keys[i]), NULL,
                              "%s applies to the blocks in s, and every block of this controller is in z", keys[i]);
    return TD_OK;
}

/* A plug-in controller on the axes of its AMBs, AMB by AMB, x then y (bearing coordinates). */
static td_status add_plugin(td_case_reader *r, const config_setting_t *g, const cc_rec *c)
{
    td_plugin_spec spec;
    int i, axes[2 * CC_MAX_AMBS];
    for (i = 0; i < 2 * c->amb_count; i++)
        axes[i] = 2 * c->ambs[i / 2] + i % 2;
    memset(&spec, 0, sizeof spec);
    spec.name = c->name;
    spec.sample_rate = c->sample_rate;
    spec.delay = c->delay;
    spec.n_inputs = spec.n_outputs = 2 * c->amb_count;
    spec.inputs = spec.outputs = axes;
    return td_cr_add_plugin(r, g, &c->plugin, &spec);
}

static td_status add_controller(td_case_reader *r, const config_setting_t *g, void *rec)
{
    cc_rec *c = rec;
    td_controller *k = NULL;
    int axes[2 * CC_MAX_AMBS];
    td_error merr;
    td_status st;
    if (c->plugin.library)
        return (st = add_plugin(r, g, c)) == TD_OK ? keep_info(r, g, c) : st;
    st = build_controller(r, g, c, &k, axes);
    if (st == TD_OK)
        st = check_sampled_nothing(r, g, c);
    if (st == TD_OK && (st = td_model_add_controller(r->c->model, c->name, k, axes, axes, &merr)) != TD_OK)
        st = td_cr_model_fail(r, g, st, &merr);
    td_controller_free(&k);
    return st == TD_OK ? keep_info(r, g, c) : st;
}

static const td_cs_key controller_keys[] = {
    {.key = "name",
     .type = TD_CS_STRING,
     .offset = offsetof(cc_rec, name),
     .need = TD_CS_REQUIRED,
     .what = "the controller's name, unique among the controllers",
     .doc = "its name in messages and events, unique among the controllers (at most 63 characters)"},
    {.key = "ambs",
     .type = TD_CS_CUSTOM,
     .read = read_ambs,
     .doc_type = "array of integers",
     .doc_default = "required",
     .what = "the AMBs it drives, indices in `ambs`",
     .doc = "the AMBs (indices in `ambs`, from 0) whose x and y axes it drives: each sensor is an input, each "
            "amplifier an output; such an AMB leaves out kp, kd and kint"},
    {.key = "coordinates",
     .type = TD_CS_ENUM,
     .offset = offsetof(cc_rec, rigid),
     .names = coordinate_names,
     .name_count = 2,
     .check = check_coordinates,
     .doc = "`\"bearing\"`: `law` on each axis of each AMB; `\"rigid\"`: `translation` and `tilt` in each lateral "
            "plane of exactly two AMBs"},
    {.key = "reference_z",
     .type = TD_CS_REAL,
     .read = read_reference_z,
     .doc_default = "the rotor's mass centre",
     .unit = "m",
     .doc = "the axial position whose displacement the translation law reads (rigid only)"},
    {.key = "law",
     .type = TD_CS_LIST,
     .sub = &td_cs_block,
     .read = check_laws,
     .doc_default = "required (bearing), unless `plugin`",
     .doc = "the blocks of the law in series, e -> first -> ... -> i, below"},
    {.key = "translation",
     .type = TD_CS_CUSTOM,
     .read = td_cs_elsewhere,
     .doc_type = "list",
     .doc_default = "required (rigid)",
     .doc = "the translation law's blocks, as `law`: the force current (A) from the displacement at reference_z"},
    {.key = "tilt",
     .type = TD_CS_CUSTOM,
     .read = td_cs_elsewhere,
     .doc_type = "list",
     .doc_default = "required (rigid)",
     .doc = "the tilt law's blocks, as `law`: the moment current (A m) from the tilt (m/m)"},
    {.key = "plugin",
     .type = TD_CS_GROUP,
     .offset = offsetof(cc_rec, plugin),
     .sub = &td_cs_plugin,
     .check = check_plugin,
     .order = 1, /* after the coordinates, the rate and the delay it is checked against */
     .doc_default = "none (a law)",
     .doc = "instead of `law`: the user's own controller code, a plug-in (touchdown/plugin.h) in a shared "
            "library, below; bearing coordinates, sample_rate required, delay as for a law"},
    {.key = "sample_rate",
     .type = TD_CS_REAL,
     .offset = offsetof(cc_rec, sample_rate),
     .range = TD_CR_POSITIVE,
     .doc_default = "continuous",
     .unit = "Hz",
     .doc = "sampled at this rate, the current held between samples (zero-order hold)"},
    {.key = "discretisation",
     .type = TD_CS_ENUM,
     .offset = offsetof(cc_rec, discretisation),
     .names = discretisation_names,
     .name_count = 2,
     .check = check_sampled,
     .doc = "how the blocks in s become sampled ones (each run of them in series as a whole): bilinear, or exact "
            "for a held input (a resonant block: exact at its frequency with zoh, or tustin prewarped there); refused "
            "when every block is in z"},
    {.key = "prewarp",
     .type = TD_CS_REAL,
     .offset = offsetof(cc_rec, prewarp),
     .range = TD_CR_NONNEGATIVE,
     .check = check_sampled,
     .doc_default = "0 (none)",
     .unit = "Hz",
     .doc = "Tustin only: the frequency where the sampled law matches the continuous one exactly, e.g. a notch's or "
            "a resonant's; refused when every block is in z"},
    {.key = "delay",
     .type = TD_CS_INT,
     .offset = offsetof(cc_rec, delay),
     .lo = 0,
     .hi = CC_MAX_DELAY,
     .check = check_sampled,
     .doc = "whole samples of computation delay (sampled only): the current applied on [t_k, t_k+1) is computed "
            "from the sensors at t_k-delay"},
};
const td_cs_table td_cs_controllers = {"controllers[]", "controllers", controller_keys, TD_CS_COUNT(controller_keys),
                                       sizeof(cc_rec),  NULL,          add_controller};
