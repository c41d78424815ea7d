/* The bridge between a td_sim and the writers (recorder.h). */
#include "run/recorder.h"
#include "model/rigid_motion.h"
#include "util/error_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "touchdown/dofs.h"
#include "touchdown/system.h"

#define REC_MAX_WRITERS 2

struct td_recorder {
    td_writer *writers[REC_MAX_WRITERS];
    int writer_count;
    int dof_count;
    int node_count; /* nodes written */
    int *nodes;
    int retainer_count, amb_count;
    int race_fields;   /* the writers' race columns (td_output_layout) */
    int speed_field;   /* the writers' rotor speed column (td_output_layout) */
    int switch_fields; /* the writers' event fields of a recovery supervisor (td_output_layout) */
    double *q;         /* dof_count: the generalized coordinates (touchdown/system.h), never more */
    double *node_xy;   /* 2 node_count */
    td_retainer_state *ret;
    double *amb_f; /* 2 amb_count */

    /* heat */
    int thermal_fields; /* the writers' temperature columns (td_output_layout) */
    /* housing motion */
    int housing_fields; /* the writers' housing series (td_output_layout) */
    /* the housing's motion at the sample, then a housing body's (td_writer_housing) */
    double housing[TD_WRITER_HOUSING_VALUES + TD_WRITER_HOUSING_BODY_VALUES];
    double *node_abs_xy; /* 2 node_count: the nodes' absolute displacement */
    double *node_z;      /* node_count: their axial positions, m */
    /* housing body */
    int housing_body_fields; /* the writers' body series (td_output_layout) */
    double body_centre;      /* m, axial z of the body's centre (td_housing_body.centre) */
};

static void recorder_free(td_recorder *r)
{
    if (!r)
        return;
    free(r->nodes);
    free(r->q);
    free(r->node_xy);
    free(r->ret);
    free(r->amb_f);
    free(r->node_abs_xy); /* housing motion */
    free(r->node_z);
    free(r);
}

void td_recorder_discard(td_recorder **rec)
{
    int i;
    if (!rec || !*rec)
        return;
    for (i = 0; i < (*rec)->writer_count; i++)
        td_writer_discard(&(*rec)->writers[i]);
    recorder_free(*rec);
    *rec = NULL;
}

/* The output nodes: out->nodes checked against the model, or every node. */
static td_status choose_nodes(td_recorder *r, const td_model *model, const td_output_options *out, td_error *err)
{
    int n = td_model_node_count(model), i;
    if (out->node_count < 0 || out->node_count > TD_OUTPUT_MAX_NODES)
        return td_error_set(err, TD_ERR_INVALID, "output: node_count %d outside 0..%d", out->node_count,
                            TD_OUTPUT_MAX_NODES);
    r->node_count = out->node_count > 0 ? out->node_count : n;
    if (r->node_count == 0)
        return TD_OK;
    r->nodes = malloc((size_t)r->node_count * sizeof *r->nodes);
    if (!r->nodes)
        return td_error_set(err, TD_ERR_NOMEM, "out of memory for the output node list");
    for (i = 0; i < r->node_count; i++) {
        r->nodes[i] = out->node_count > 0 ? out->nodes[i] : i;
        if (r->nodes[i] < 0 || r->nodes[i] >= n)
            return td_error_set(err, TD_ERR_INVALID, "output: node %d does not exist (the shaft has nodes 0..%d)",
                                r->nodes[i], n - 1);
    }
    return TD_OK;
}

/* body_dofs: a housing body's coordinates, after the rotor's in the sim's q (td_sim_get_state). */
static td_status allocate_scratch(td_recorder *r, int body_dofs, td_error *err)
{
    r->q = malloc((size_t)(r->dof_count > 0 ? r->dof_count + body_dofs : 1) * sizeof *r->q);
    r->node_xy = malloc((size_t)(2 * r->node_count + 1) * sizeof *r->node_xy);
    r->ret = calloc((size_t)r->retainer_count + 1, sizeof *r->ret);
    r->amb_f = malloc((size_t)(2 * r->amb_count + 1) * sizeof *r->amb_f);
    if (!r->q || !r->node_xy || !r->ret || !r->amb_f)
        return td_error_set(err, TD_ERR_NOMEM, "out of memory for the output buffers");
    return TD_OK;
}

/* Retainer nodes and clearances, AMB nodes: what a plot of the orbit needs besides the samples. */
static td_status model_tables(const td_recorder *r, const td_model *model, long *ret_nodes, double *clearance,
                              long *amb_nodes, double *amb_capacity, td_error *err)
{
    int i;
    for (i = 0; i < r->retainer_count; i++) {
        td_retainer ret;
        if (td_model_get_retainer(model, i, &ret) != TD_OK)
            return td_error_set(err, TD_ERR_INVALID, "output: cannot read retainer %d of the model", i);
        ret_nodes[i] = ret.node;
        clearance[i] = ret.clearance;
    }
    for (i = 0; i < r->amb_count; i++) {
        td_amb amb;
        if (td_model_get_amb(model, i, &amb) != TD_OK)
            return td_error_set(err, TD_ERR_INVALID, "output: cannot read AMB %d of the model", i);
        amb_nodes[i] = amb.node;
        amb_capacity[i] = amb.force_capacity;
    }
    return TD_OK;
}

static td_status write_model_attributes(td_recorder *r, const td_model *model, const td_output_options *out,
                                        td_error *err)
{
    long *ret_nodes = malloc((size_t)(r->retainer_count + 1) * sizeof *ret_nodes);
    double *clearance = malloc((size_t)(r->retainer_count + 1) * sizeof *clearance);
    long *amb_nodes = malloc((size_t)(r->amb_count + 1) * sizeof *amb_nodes);
    double *amb_capacity = malloc((size_t)(r->amb_count + 1) * sizeof *amb_capacity);
    td_status st = TD_OK;
    int w;
    if (!ret_nodes || !clearance || !amb_nodes || !amb_capacity)
        st = td_error_set(err, TD_ERR_NOMEM, "out of memory for the output attributes");
    if (st == TD_OK)
        st = model_tables(r, model, ret_nodes, clearance, amb_nodes, amb_capacity, err);
    for (w = 0; w < r->writer_count && st == TD_OK; w++) {
        td_writer *wr = r->writers[w];
        st = td_writer_set_double(wr, td_out_name(TD_OUT_SAMPLE_RATE), out->sample_rate, err);
        if (st == TD_OK && r->retainer_count > 0)
            st = td_writer_set_longs(wr, td_out_name(TD_OUT_RETAINER_NODES), ret_nodes, r->retainer_count, err);
        if (st == TD_OK && r->retainer_count > 0)
            st = td_writer_set_doubles(wr, td_out_name(TD_OUT_RETAINER_CLEARANCE), clearance, r->retainer_count, err);
        if (st == TD_OK && r->amb_count > 0)
            st = td_writer_set_longs(wr, td_out_name(TD_OUT_AMB_NODES), amb_nodes, r->amb_count, err);
        if (st == TD_OK && r->amb_count > 0)
            st = td_writer_set_doubles(wr, td_out_name(TD_OUT_AMB_CAPACITY), amb_capacity, r->amb_count, err);
    }
    free(ret_nodes);
    free(clearance);
    free(amb_nodes);
    free(amb_capacity);
    return st;
}

/* 1 if some retainer has states of its own to write: a race body or a rolling state. */
static int has_race_states(const td_model *model)
{
    int i;
    for (i = 0; i < td_model_retainer_count(model); i++) {
        td_retainer ret;
        if (td_model_get_retainer(model, i, &ret) == TD_OK && (td_retainer_has_race(&ret) || ret.stick))
            return 1;
    }
    return 0;
}

/* heat: 1 if some retainer has a thermal network. */
static int has_thermal(const td_model *model)
{
    int i;
    for (i = 0; i < td_model_retainer_count(model); i++)
        if (td_model_get_retainer_thermal(model, i, NULL))
            return 1;
    return 0;
}

static td_status open_writers(td_recorder *r, const td_output_options *out, td_error *err)
{
    td_output_layout layout;
    td_status st = TD_OK;
    layout.node_count = r->node_count;
    layout.nodes = r->nodes;
    layout.retainer_count = r->retainer_count;
    layout.amb_count = r->amb_count;
    layout.race_fields = r->race_fields;
    layout.speed_field = r->speed_field;
    layout.whirl_field = r->race_fields || r->speed_field;
    layout.switch_fields = r->switch_fields;
    layout.thermal_fields = r->thermal_fields;
    layout.housing_fields = r->housing_fields;           /* housing motion */
    layout.housing_body_fields = r->housing_body_fields; /* housing body */
    layout.compression = out->compression;
    layout.window_fields = out->window > 0.0; /* long runs */
    layout.omit_events = out->omit_events;
    if (out->hdf5_path[0])
        st = td_writer_open(TD_WRITER_HDF5, out->hdf5_path, &layout, &r->writers[r->writer_count++], err);
    if (st == TD_OK && out->csv_path[0])
        st = td_writer_open(TD_WRITER_CSV, out->csv_path, &layout, &r->writers[r->writer_count++], err);
    return st;
}

/* housing motion: the buffers of the absolute displacement and the output nodes' axial positions, for a
 * model with housing motion or a housing body (whose own motion the housing fields show too). */
static td_status housing_setup(td_recorder *r, const td_model *model, td_error *err)
{
    td_housing_body body;
    int i;
    r->housing_body_fields = td_model_get_housing_body(model, &body);
    r->body_centre = r->housing_body_fields ? body.centre : 0.0;
    r->housing_fields = td_model_has_housing_motion(model) || r->housing_body_fields;
    if (!r->housing_fields)
        return TD_OK;
    r->node_abs_xy = malloc((size_t)(2 * r->node_count + 1) * sizeof *r->node_abs_xy);
    r->node_z = malloc((size_t)(r->node_count + 1) * sizeof *r->node_z);
    if (!r->node_abs_xy || !r->node_z)
        return td_error_set(err, TD_ERR_NOMEM, "out of memory for the output buffers");
    for (i = 0; i < r->node_count; i++)
        r->node_z[i] = td_model_node_position(model, r->nodes[i]);
    return TD_OK;
}

td_status td_recorder_create(const td_model *model, const td_output_options *out, td_recorder **rec, td_error *err)
{
    td_recorder *r;
    td_status st;
    if (!rec)
        return td_error_set(err, TD_ERR_INVALID, "td_recorder_create: NULL output pointer");
    *rec = NULL;
    if (!model || !out)
        return td_error_set(err, TD_ERR_INVALID, "td_recorder_create: NULL model or output options");
    if (!isfinite(out->sample_rate) || out->sample_rate <= 0.0)
        return td_error_set(err, TD_ERR_INVALID, "output: sample_rate must be > 0 Hz (got %g)", out->sample_rate);
    if (!memchr(out->hdf5_path, '\0', sizeof out->hdf5_path) || !memchr(out->csv_path, '\0', sizeof out->csv_path))
        return td_error_set(err, TD_ERR_INVALID, "output: path not NUL-terminated");
    r = calloc(1, sizeof *r);
    if (!r)
        return td_error_set(err, TD_ERR_NOMEM, "out of memory creating the recorder");
    r->dof_count = td_model_dof_count(model);
    r->retainer_count = td_model_retainer_count(model);
    r->amb_count = td_model_amb_count(model);
    r->race_fields = has_race_states(model);
    r->speed_field = td_model_speed_varies(model);
    r->switch_fields = td_model_get_recovery(model, NULL) > 0;
    r->thermal_fields = has_thermal(model);
    if ((st = choose_nodes(r, model, out, err)) != TD_OK || (st = housing_setup(r, model, err)) != TD_OK ||
        (st = allocate_scratch(r, td_model_housing_body_dofs(model), err)) != TD_OK ||
        (st = open_writers(r, out, err)) != TD_OK || (st = write_model_attributes(r, model, out, err)) != TD_OK) {
        td_recorder_discard(&r);
        return st;
    }
    *rec = r;
    return TD_OK;
}

/* Read nodes, retainers and AMBs from the simulation into the scratch buffers. */
static td_status read_state(td_recorder *r, const td_sim *sim, td_error *err)
{
    td_status st = td_sim_get_state(sim, r->q, NULL);
    const td_system *sys = td_sim_system(sim);
    int i;
    if (st != TD_OK)
        return td_error_set(err, st, "reading the state at t = %.17g s: %s", td_sim_time(sim), td_sim_errmsg(sim));
    for (i = 0; i < r->node_count; i++) { /* interior nodes of a reduced rotor through q_phys = T q */
        r->node_xy[2 * i] = td_system_node_displacement(sys, r->q, r->nodes[i], TD_DOF_X);
        r->node_xy[2 * i + 1] = td_system_node_displacement(sys, r->q, r->nodes[i], TD_DOF_Y);
    }
    for (i = 0; i < r->retainer_count; i++)
        if ((st = td_sim_retainer_state(sim, i, &r->ret[i])) != TD_OK)
            return td_error_set(err, st, "reading retainer %d: %s", i, td_sim_errmsg(sim));
    for (i = 0; i < r->amb_count; i++)
        if ((st = td_sim_amb_force(sim, i, &r->amb_f[2 * i])) != TD_OK)
            return td_error_set(err, st, "reading AMB %d: %s", i, td_sim_errmsg(sim));
    return TD_OK;
}

/*
 * housing motion: the housing's prescribed motion at t (td_model_housing_motion_at) and the nodes'
 * absolute displacement, the relative one plus the housing's rigid motion at the node's z
 * (td_rigid_motion_at): its displacement and its rotation about the reference point z_ref, and a
 * compliant housing's (a body on mounts) own rigid motion relative to the base about its centre z_b
 * (td_sim_housing_body_state; its four values follow the housing's in td_writer_housing's).
 */
static td_status housing_sample(td_recorder *r, const td_sim *sim, double t, td_error *err)
{
    const td_model *model = td_sim_model(sim);
    double z_ref = td_model_housing_reference(model), *b = r->housing + TD_WRITER_HOUSING_VALUES;
    double base[TD_DOFS_PER_NODE], at[TD_DOFS_PER_NODE], body_at[TD_DOFS_PER_NODE];
    td_housing_motion hm;
    td_status st = TD_OK;
    int i;
    td_sim_housing_body_state(sim, b, NULL); /* zeros without a body */
    td_model_housing_motion_at(model, t, &hm);
    memcpy(r->housing, hm.acceleration, 2 * sizeof(double));
    memcpy(r->housing + 2, hm.velocity, 2 * sizeof(double));
    memcpy(r->housing + 4, hm.displacement, 2 * sizeof(double));
    memcpy(r->housing + 6, hm.rate, 2 * sizeof(double));
    memcpy(r->housing + 8, hm.angle, 2 * sizeof(double));
    base[TD_DOF_X] = hm.displacement[0], base[TD_DOF_Y] = hm.displacement[1];
    base[TD_DOF_THETA] = hm.angle[0], base[TD_DOF_PHI] = hm.angle[1];
    for (i = 0; i < r->node_count; i++) {
        td_rigid_motion_at(base, r->node_z[i] - z_ref, at);
        td_rigid_motion_at(b, r->node_z[i] - r->body_centre, body_at);
        r->node_abs_xy[2 * i] = r->node_xy[2 * i] + at[TD_DOF_X];
        r->node_abs_xy[2 * i + 1] = r->node_xy[2 * i + 1] + at[TD_DOF_Y];
        if (r->housing_body_fields) {
            r->node_abs_xy[2 * i] += body_at[TD_DOF_X];
            r->node_abs_xy[2 * i + 1] += body_at[TD_DOF_Y];
        }
    }
    for (i = 0; st == TD_OK && i < r->writer_count; i++)
        st = td_writer_housing(r->writers[i], r->housing, r->node_abs_xy, err);
    return st;
}

td_status td_recorder_sample(td_recorder *r, const td_sim *sim, double t, td_error *err)
{
    td_status st;
    int i;
    if (!r || !sim)
        return td_error_set(err, TD_ERR_INVALID, "td_recorder_sample: NULL argument");
    if (td_system_physical_dof_count(td_sim_system(sim)) != r->dof_count)
        return td_error_set(err, TD_ERR_INVALID, "the simulation has %d DOFs, the output layout %d",
                            td_system_physical_dof_count(td_sim_system(sim)), r->dof_count);
    if ((st = read_state(r, sim, err)) != TD_OK)
        return st;
    if (r->housing_fields && (st = housing_sample(r, sim, t, err)) != TD_OK)
        return st;
    for (i = 0; i < r->writer_count; i++)
        if ((st = td_writer_sample(r->writers[i], t, td_sim_speed(sim), r->node_xy, r->ret, r->amb_f, err)) != TD_OK)
            return st;
    return TD_OK;
}

/* long runs */
td_status td_recorder_observe(td_recorder *r, const td_sim *sim, td_error *err)
{
    if (!r || !sim)
        return td_error_set(err, TD_ERR_INVALID, "td_recorder_observe: NULL argument");
    return read_state(r, sim, err);
}

td_status td_recorder_window(td_recorder *r, const td_window_summary *win, td_error *err)
{
    td_status st;
    int i;
    for (i = 0; i < r->writer_count; i++)
        if ((st = td_writer_window(r->writers[i], win, err)) != TD_OK)
            return st;
    return TD_OK;
}

const td_retainer_state *td_recorder_retainers(const td_recorder *r)
{
    return r->ret;
}
int td_recorder_retainer_count(const td_recorder *r)
{
    return r->retainer_count;
}

td_status td_recorder_event(td_recorder *r, const td_event *ev, long sample, td_error *err)
{
    td_status st;
    int i;
    for (i = 0; i < r->writer_count; i++)
        if ((st = td_writer_event(r->writers[i], ev, sample, err)) != TD_OK)
            return st;
    return TD_OK;
}

/* Apply one td_writer_set_* call to every writer. */
#define FOR_EACH_WRITER(r, call)                                                                                       \
    do {                                                                                                               \
        int i_;                                                                                                        \
        td_status st_;                                                                                                 \
        for (i_ = 0; i_ < (r)->writer_count; i_++) {                                                                   \
            td_writer *w_ = (r)->writers[i_];                                                                          \
            if ((st_ = (call)) != TD_OK)                                                                               \
                return st_;                                                                                            \
        }                                                                                                              \
        return TD_OK;                                                                                                  \
    } while (0)

td_status td_recorder_set_string(td_recorder *r, td_out_id name, const char *value, td_error *err)
{
    FOR_EACH_WRITER(r, td_writer_set_string(w_, td_out_name(name), value, err));
}

td_status td_recorder_set_double(td_recorder *r, td_out_id name, double value, td_error *err)
{
    FOR_EACH_WRITER(r, td_writer_set_double(w_, td_out_name(name), value, err));
}

td_status td_recorder_set_long(td_recorder *r, td_out_id name, long value, td_error *err)
{
    FOR_EACH_WRITER(r, td_writer_set_long(w_, td_out_name(name), value, err));
}

td_status td_recorder_set_doubles(td_recorder *r, td_out_id name, const double *values, int n, td_error *err)
{
    FOR_EACH_WRITER(r, td_writer_set_doubles(w_, td_out_name(name), values, n, err));
}

td_status td_recorder_set_longs(td_recorder *r, td_out_id name, const long *values, int n, td_error *err)
{
    FOR_EACH_WRITER(r, td_writer_set_longs(w_, td_out_name(name), values, n, err));
}

td_status td_recorder_set_stats(td_recorder *r, const td_sim_stats *stats, td_error *err)
{
    FOR_EACH_WRITER(r, td_writer_set_stats(w_, stats, err));
}

td_status td_recorder_close(td_recorder **rec, int complete, const char *reason, td_error *err)
{
    td_status first = TD_OK;
    int i;
    if (!rec || !*rec)
        return TD_OK;
    for (i = 0; i < (*rec)->writer_count; i++) {
        td_error local;
        td_status st = td_writer_close(&(*rec)->writers[i], complete, reason, &local);
        if (st != TD_OK && first == TD_OK)
            first = td_error_set(err, st, "%s", local.message);
    }
    recorder_free(*rec);
    *rec = NULL;
    return first;
}
