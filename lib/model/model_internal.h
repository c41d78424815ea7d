/* The td_model record, visible inside the library only. */
#ifndef TD_MODEL_INTERNAL_H
#define TD_MODEL_INTERNAL_H

#include "touchdown/model.h"

/* A growable array of one part type. */
#define TD_PART_ARRAY(type)                                                                                            \
    struct {                                                                                                           \
        type *items;                                                                                                   \
        int count;                                                                                                     \
        int capacity;                                                                                                  \
    }

/* A plug-in controller's spec as the model keeps it (td_model_add_plugin_controller, plugin.c):
 * spec.name is `name`, a copy of the controller's, spec.inputs and spec.outputs its axis lists, spec.library and
 * the parameters owned copies, spec.functions the program's table or the opened library's. */
typedef struct td_model_plugin {
    td_plugin_spec spec;
    char name[64];
    void *handle; /* the library's dlopen handle (closed with the model); NULL for a program's table */
} td_model_plugin;

/* A controller as the model keeps it: a linear law (td_model_add_controller, k set, plugin NULL) or
 * a plug-in (td_model_add_plugin_controller, k NULL), with owned copies of the law and of its axis
 * lists (nin and nout long). */
typedef struct td_model_controller {
    td_controller *k;
    td_model_plugin *plugin;
    char name[64];
    int nin, nout;      /* inputs and outputs */
    double sample_rate; /* Hz; 0: continuous (a plug-in is always sampled) */
    int *inputs;        /* AMB axis (2 amb + axis) of each input's sensor */
    int *outputs;       /* AMB axis each output commands */
} td_model_controller;

/* A retainer's thermal network as the model keeps it (thermal.c). */
typedef struct td_model_thermal {
    int retainer;
    td_retainer_thermal t;
} td_model_thermal;

struct td_model {
    td_shaft_options shaft;
    TD_PART_ARRAY(td_shaft_element) elements;
    TD_PART_ARRAY(td_disc) discs; /* point masses are discs with Ip = Id = 0 */
    TD_PART_ARRAY(td_amb) ambs;
    TD_PART_ARRAY(td_bearing) bearings;
    TD_PART_ARRAY(td_retainer) retainers;
    TD_PART_ARRAY(td_unbalance) unbalances;
    TD_PART_ARRAY(td_change) changes;           /* kept sorted by time (stable) */
    TD_PART_ARRAY(int) change_entries;          /* change i was the change_entries.items[i]-th added */
    double speed;                               /* rad/s */
    TD_PART_ARRAY(td_speed_point) speed_points; /* the ramp, increasing times */
    TD_PART_ARRAY(td_model_controller) controllers;
    td_spin spin;
    td_recovery recovery;    /* the recovery supervisor (recovery.c); pair_count 0: none */
    double gravity[2];       /* m/s^2 */
    double reduction_cutoff; /* Hz: Craig-Bampton reduction of the system (lib/model/reduce.c); 0: full model */
    /* the bearing's duty (assessment.c) */
    td_retainer_bearing *retainer_bearings; /* retainer_bearing_count long (<= retainers.count); NULL: none set */
    int retainer_bearing_count;
    td_limits limits; /* valid when has_limits */
    int has_limits;
    /* heat */
    TD_PART_ARRAY(td_model_thermal) thermals; /* the retainers' thermal networks (thermal.c), by retainer */
    /* housing motion (housing.c) */
    TD_PART_ARRAY(td_housing_pulse) shocks;    /* the housing's acceleration pulses, summed */
    TD_PART_ARRAY(td_housing_pulse) rotations; /* its rotation-rate profiles, summed */
    int history_count;                         /* points of the acceleration history; 0: none */
    double *history;          /* history_count rows (t, ax, ay, vx, vy, dx, dy): the points and the exact
                               * integrals of the piecewise-linear acceleration up to each (from rest at t = 0) */
    double housing_reference; /* m, valid when has_housing_reference */
    int has_housing_reference;
    /* housing body */
    td_housing_body body; /* the compliant housing (housing_body.c), valid when has_body */
    int has_body;
};

/* The controllers' part in freeing, copying and validating a model (controllers.c). */
void td_model_free_controllers(td_model *m);
/* Deep copies of src's controllers into m, whose controller array is empty; on failure m holds
 * what was copied, for td_model_free. */
td_status td_model_clone_controllers(td_model *m, const td_model *src, td_error *err);
/* Axes in range, each axis driven once, a driven AMB with kp = kd = kint = 0. */
td_status td_model_check_controllers(const td_model *m, td_error *err);

/* The plug-ins' part in freeing and copying a controller (plugin.c): a deep copy of src's plug-in
 * into dst (the library opened again) and its release. */
td_status td_model_plugin_clone(td_model_controller *dst, const td_model_controller *src, int i, td_error *err);
/* The spec's values other than the table, the name and the axes (controller i being added): the
 * rate (sampled only), the delay, and named, distinct parameters with finite values. */
td_status td_model_plugin_check(const td_plugin_spec *spec, int i, td_error *err);
/* Owned copies of spec's library path, axis lists and parameters into c (c->name set first; c->plugin
 * allocated); the table is spec's, or the library's, opened here and checked against this ABI. On
 * failure c holds what it could copy, for td_model_plugin_free and free(c->inputs), free(c->outputs). */
td_status td_model_plugin_copy(td_model_controller *c, const td_plugin_spec *spec, int i, td_error *err);
void td_model_plugin_free(td_model_plugin **p);

/* The recovery supervisor's rules against the controllers (recovery.c): pairs of existing, distinct,
 * sampled controllers at one rate over the same axes, each controller in one pair at most, and a
 * retainer to take the clearance from. */
td_status td_model_check_recovery(const td_model *m, td_error *err);
/* 1 if controllers i and j are the two laws of one recovery pair (they share their axes). */
int td_model_recovery_paired(const td_model *m, int i, int j);
/* 1 if controller l is the recovery law of a pair: it stands by until the supervisor switches to it. */
int td_model_recovery_standby(const td_model *m, int l);

/* The assessment's part in freeing and copying a model (assessment.c). */
void td_model_free_assessment(td_model *m);
/* A copy of src's retainer bearings and limits into m (which has none); 0 when out of memory. */
int td_model_clone_assessment(td_model *m, const td_model *src);

/* The housing motion's part in freeing and copying a model (housing.c). */
void td_model_free_housing(td_model *m);
/* A copy of src's housing motion into m (which has none); 0 when out of memory. */
int td_model_clone_housing(td_model *m, const td_model *src);

#endif
