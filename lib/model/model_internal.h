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

/* A linear controller as the model keeps it (td_model_add_controller): owned copies of the law and of
 * its axis lists (td_controller_inputs(k) and td_controller_outputs(k) long). */
typedef struct td_model_controller {
    td_controller *k;
    char name[64];
    int *inputs;  /* AMB axis (2 amb + axis) of each input's sensor */
    int *outputs; /* AMB axis each output commands */
} td_model_controller;

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
};

/* The controllers' part in freeing, copying and validating a model (controllers.c). */
void td_model_free_controllers(td_model *m);
/* Deep copies of src's controllers into m, whose controller array is empty; on failure m holds
 * what was copied, for td_model_free. */
td_status td_model_clone_controllers(td_model *m, const td_model *src, td_error *err);
/* Axes in range, each axis driven once, a driven AMB with kp = kd = kint = 0. */
td_status td_model_check_controllers(const td_model *m, td_error *err);

/* The recovery supervisor's rules against the controllers (recovery.c): pairs of existing, distinct,
 * sampled controllers at one rate over the same axes, each controller in one pair at most, and a
 * retainer to take the clearance from. */
td_status td_model_check_recovery(const td_model *m, td_error *err);
/* 1 if controllers i and j are the two laws of one recovery pair (they share their axes). */
int td_model_recovery_paired(const td_model *m, int i, int j);
/* 1 if controller l is the recovery law of a pair: it stands by until the supervisor switches to it. */
int td_model_recovery_standby(const td_model *m, int l);

#endif
